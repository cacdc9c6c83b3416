#pragma once
// An optimal control problem in symbolic form, built from a spec: states, controls, dynamics
// f(x, u), running cost L, endpoint constraints psi, all in the solver's normalized units.
#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::pmp {

// Normalized units of the solver: length, time and mass scales.
struct Units {
  std::string length_name, time_name;
  double length_km = 1, time_s = 1, mass_kg = 1;
  double speed_km_s() const { return length_km / time_s; }
  // Force unit [N]: mass * length / time^2 in SI.
  double force_N() const { return mass_kg * length_km * 1e3 / (time_s * time_s); }
};

struct Named {
  Named(std::string n, std::string m, std::string u, double v = 0, std::string src = "")
      : name(std::move(n)), meaning(std::move(m)), unit(std::move(u)), value(v), source(std::move(src)) {}
  std::string name, meaning, unit;
  double value = 0;    // normalized; for parameters only
  std::string source;  // parameters: "" (a constant) or "ephemeris:<body>:<event>" (evaluated by the runtime)
};

struct Control {
  std::string name, meaning;
  std::string kind;  // "throttle" (bounded scalar in [0,1]) or "direction" (component of a unit vector)
};

// psi(x(t_k), p) = 0 at t0 or tf. `targets` are parameter names whose values psi compares with.
struct EndpointConstraint {
  std::string id, kind, at;    // kind: initial_state | rendezvous; at: t0 | tf
  std::vector<GiNaC::ex> psi;  // in the state symbols (evaluated at `at`)
  std::vector<std::string> psi_names;
  std::vector<std::string> fixed_states;  // states psi fixes (for meaning and counting)
  io::json target;                        // the spec's target, for the generator's ephemeris mode
};

struct Problem {
  std::string id, dynamics_model, objective;
  Units units;
  symbolic::SymbolTable symbols;
  std::vector<Named> states, parameters;
  std::vector<Control> controls;
  std::vector<GiNaC::ex> f;  // state rhs, one per state
  GiNaC::ex running_cost;    // L (with the homotopy parameter eps)
  GiNaC::ex endpoint_cost;   // phi (Mayer term), in states at tf
  std::vector<EndpointConstraint> constraints;
  double t0 = 0, tf = 0;     // normalized
  double epoch_mjd2000 = 0;  // calendar epoch of t0, for ephemeris targets
  bool has_epoch = false;
  double initial_mass = 1;  // normalized (the mass scale is m0, so 1)
};

// Name of the costate of state `x` (l_x) and of a symbol at an event time (x_tf).
std::string costate_name(const std::string& state);
std::string at_event(const std::string& name, const std::string& event);

// Builds the problem of a validated spec. Throws std::invalid_argument / std::domain_error
// naming the spec field for what this engine cannot formulate.
Problem build_problem(const io::json& spec);

}  // namespace helios::pmp

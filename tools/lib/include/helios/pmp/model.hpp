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
  double value = 0;  // normalized; for parameters only
  // Parameters: "" (a constant) or evaluated by the runtime at the event: "ephemeris:<body>:<event>"
  // (JPL low-precision state), "ephemeris_rate:<body>:<event>" (its time derivative),
  // "coast:<constraint>:<event>" (a coasting target's state, propagated from its state at t0).
  std::string source;
};

struct Control {
  std::string name, meaning;
  // "throttle" (bounded scalar in [0,1]), "direction" (component of a unit vector) or
  // "sail_normal" (component of a sail's unit normal n, admissible where n.r >= 0).
  std::string kind;
};

// psi(t_k, x(t_k), p) = 0 at t0 or tf, comparing states with target parameters.
struct EndpointConstraint {
  std::string id, kind, at;      // kind: initial_state | rendezvous; at: t0 | tf
  std::vector<GiNaC::ex> psi;    // in the state symbols (evaluated at `at`)
  std::vector<GiNaC::ex> psi_t;  // d psi / d t_k through the target's motion (0 for a fixed state)
  std::vector<std::string> psi_names;
  std::vector<std::string> fixed_states;  // states psi fixes (for meaning and counting)
  io::json target;                        // the spec's target, for the generator's ephemeris mode
};

// An ideal flat sail: acceleration k (n.rhat)^2 n added to the velocity states, n the unit normal.
struct SailModel {
  GiNaC::ex k;                        // ac (rref/r)^2
  std::vector<GiNaC::ex> rhat;        // r/|r|
  std::vector<std::string> velocity;  // the states the acceleration enters
};

struct Problem {
  std::string id, dynamics_model, objective;
  Units units;
  symbolic::SymbolTable symbols;
  std::vector<Named> states, parameters;
  std::vector<Control> controls;
  std::string propulsion;                  // low_thrust | solar_sail
  std::vector<std::string> perturbations;  // names of the accelerations added to two-body gravity
  std::vector<GiNaC::ex> f;                // state rhs, one per state (may contain the time symbol t)
  SailModel sail;                          // when propulsion is solar_sail
  std::vector<GiNaC::ex> coast_f;          // unpowered r, v dynamics in the gravity field (coasting targets)
  GiNaC::ex running_cost;                  // L (with the homotopy parameter eps)
  GiNaC::ex endpoint_cost;                 // phi (Mayer term), in states at tf
  std::vector<EndpointConstraint> constraints;
  double t0 = 0, tf = 0;  // normalized; tf is the window's upper end when the final time is free
  bool free_final_time = false;
  double tf_min = 0;         // normalized lower end of the final-time window
  double epoch_mjd2000 = 0;  // calendar epoch of t0, for ephemeris targets
  bool has_epoch = false;
  double initial_mass = 1;  // normalized (the mass scale is m0, so 1)
  bool has_state(const std::string& name) const;
};

// Name of the costate of state `x` (l_x) and of a symbol at an event time (x_tf).
std::string costate_name(const std::string& state);
std::string at_event(const std::string& name, const std::string& event);

// Builds the problem of a validated spec. Throws std::invalid_argument / std::domain_error
// naming the spec field for what this engine cannot formulate.
Problem build_problem(const io::json& spec);

}  // namespace helios::pmp

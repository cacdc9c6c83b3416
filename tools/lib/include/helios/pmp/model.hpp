#pragma once
// An optimal control problem in symbolic form, built from a spec: states, controls, dynamics
// f(x, u), running cost L, endpoint constraints psi, all in the solver's normalized units.
#include <ginac/ginac.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "helios/astro/kepler.hpp"
#include "helios/derivation/names.hpp"
#include "helios/derivation/sections.hpp"
#include "helios/io/json_io.hpp"
#include "helios/symbolic/chain_rule.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::pmp {

// The names of the derivation artifact (l_x, x_tf, x_<id>_m, t_<id>, psi_<id>_<j>...).
namespace names = derivation::names;

// Normalized units of the solver: length, time and mass scales.
struct Units {
  std::string length_name, time_name;
  double length_km = 1, time_s = 1, mass_kg = 1;
  double speed_km_s() const { return length_km / time_s; }
  // Force unit [N]: mass * length / time^2 in SI.
  double force_N() const { return mass_kg * length_km * 1e3 / (time_s * time_s); }
};

struct Named {
  Named(std::string n, std::string m, std::string u, double v = 0, std::string src = "", std::string r = "")
      : name(std::move(n)),
        meaning(std::move(m)),
        unit(std::move(u)),
        value(v),
        source(std::move(src)),
        role(std::move(r)) {}
  std::string name, meaning, unit;
  double value = 0;  // normalized; for parameters only
  // Parameters: "" (a constant) or evaluated by the runtime at the event: "ephemeris:<body>:<event>"
  // (JPL low-precision state), "ephemeris_rate:<body>:<event>" (its time derivative),
  // "coast:<constraint>:<event>" (a coasting target's state, propagated from its state at t0).
  std::string source;
  // What the tools downstream ask a parameter for, by role rather than by name: "thrust_scale"
  // (the thrust is proportional to it, jointly with the others of that role: Tmax, or a
  // solar-electric engine's powers; the runtime's thrust continuation multiplies them all),
  // "exhaust_velocity" (c = g0 Isp), or "" (a constant of the problem).
  std::string role;
};

struct Control {
  std::string name, meaning;
  // "throttle" (bounded scalar in [0,1]), "direction" (component of a unit vector) or
  // "sail_normal" (component of a sail's unit normal n, admissible where n.r >= 0).
  std::string kind;
};

// A condition g(x) > 0 a constraint's rows do not impose: they also hold on its mirror (an orbit
// of the stated plane run the other way, the periapsis opposite the stated one), which a
// converged extremal must not be on. The runtime checks it on every extremal it returns.
// expression: in the symbols of the constraint's rows.
using SideCondition = derivation::sections::SideCondition<GiNaC::ex>;

// psi(t_k, x(t_k), p) = 0 at t0 or tf, comparing states with target parameters.
struct EndpointConstraint {
  std::string id, kind, at;      // kind: initial_state | rendezvous | flyby (position only) | orbit_insertion
  std::vector<GiNaC::ex> psi;    // in the state symbols (evaluated at `at`)
  std::vector<GiNaC::ex> psi_t;  // d psi / d t_k through the target's motion (0 for a fixed state)
  std::vector<std::string> psi_names;
  std::vector<bool> psi_inequality;       // true: the row is a bound psi_j <= 0 (active only in pass 2)
  std::vector<std::string> fixed_states;  // states psi fixes (for meaning and counting)
  io::json target;                        // the spec's target, for the generator's ephemeris mode
  // psi is not solved for the states it involves (an orbit: five rows in six states), so its
  // multipliers are shooting variables and every state's transversality row an equation.
  bool multipliers_unknown = false;
  // Unknowns inside psi that no state fixes (a departure orbit's anomaly): shooting variables found
  // by stationarity, dPhi/dq = nu^T dpsi/dq = 0, guessed uniformly in [lo, hi].
  struct FreeParameter {
    std::string name, meaning;
    double lo = 0, hi = 0;
  };
  std::vector<FreeParameter> free_parameters;
  std::vector<SideCondition> must_be_positive;
};

// A body on a Keplerian orbit about the central body, propagated by the runtime.
struct OrbitBody {
  std::string name;
  astro::Elements elements;  // a in normalized length, angles in rad, mean anomaly at `epoch`
  double epoch = 0;          // normalized time of the elements, from the time origin
};

// An event inside the trajectory at a free epoch t_<id> in [window_lo, window_hi] (Bryson-Ho):
//   psi = [ c(t_<id>, x-, p) ; x+ - g(t_<id> + duration, x-, p) ] = 0,
// x- = the state arriving (symbols <state>_<id>_m), x+ = the state leaving (<state>_<id>_p).
// c are the conditions on the arriving state; g maps it to the leaving state (the identity for a
// flyby, the target's state after a stay, a rotated excess velocity for a gravity assist).
struct InteriorEvent {
  std::string id, kind;  // rendezvous | flyby | gravity_assist
  double window_lo = 0, window_hi = 0, duration = 0;
  std::vector<GiNaC::ex> c;
  std::vector<std::string> c_names;
  std::vector<bool> c_inequality;               // true: the row is a bound c_j <= 0 (active only in pass 2)
  std::vector<GiNaC::ex> map;                   // g, one per state
  std::vector<std::string> free_parameters;     // Category C parameters inside psi (found by stationarity)
  std::vector<SideCondition> must_be_positive;  // in the state just before the event
  io::json target;
};

// An ideal flat sail: acceleration k (n.rhat)^2 n added to the velocity states, n the unit normal.
struct SailModel {
  GiNaC::ex k;                        // ac (rref/r)^2
  std::vector<GiNaC::ex> rhat;        // r/|r|
  std::vector<std::string> velocity;  // the states the acceleration enters
};

// One term of the dynamics (kind "force") or of the running cost ("cost") as the derivation
// lists it: its name, the parameters it uses, and what else a reader needs to recompute it.
struct TermListing {
  std::string name, kind;
  std::vector<std::string> parameters;
  io::json details;
};

struct Problem {
  std::string id, dynamics_model, objective;
  Units units;
  symbolic::SymbolTable symbols;
  std::vector<Named> states, parameters;
  std::vector<Control> controls;
  std::string propulsion;                  // low_thrust | solar_sail
  std::vector<std::string> perturbations;  // names of the accelerations added to two-body gravity
  std::vector<TermListing> terms;          // the forces, then the costs, whose sums are f and L
  std::vector<GiNaC::ex> f;                // state rhs, one per state (may contain the time symbol t)
  // Named quantities f may hold (a fitted thruster's input power, thrust and mass flow), each in
  // the states, the parameters and the earlier ones; the costate equations differentiate through
  // them by the chain rule, and every expression of the derivation may keep their names.
  std::vector<derivation::sections::Intermediate<GiNaC::ex>> intermediates;
  SailModel sail;  // when propulsion is solar_sail
  // The engine's thrust at full throttle (Tmax, or a solar-electric engine's T(r)) with the
  // parameters it uses, and its mass-flow law, the flow at full throttle (Tmax/c, T(r)/c) with the
  // parameters that uses: recorded by the engine's term for the mass rate and the fuel cost (no flow
  // for an engine of constant mass without an exhaust velocity).
  GiNaC::ex max_thrust, max_mass_flow;
  std::vector<std::string> thrust_parameters, flow_parameters;
  std::vector<GiNaC::ex> coast_f;  // unpowered r, v dynamics in the gravity field (coasting targets)
  GiNaC::ex running_cost;          // L (with the homotopy parameter eps)
  GiNaC::ex endpoint_cost;         // phi (Mayer term), in states at tf
  std::vector<EndpointConstraint> constraints;
  std::vector<InteriorEvent> events;  // in time order
  std::vector<OrbitBody> orbit_bodies;
  // d/dt of every time-dependent parameter (a target's state at an event): parameter -> rate.
  std::map<std::string, GiNaC::ex> parameter_rates;
  double t0 = 0, tf = 0;  // normalized; tf is the window's upper end when the final time is free
  bool free_final_time = false;
  bool free_departure = false;  // t0 slides in [t0_min, t0_max]; tf = t0 + (tf - t0 nominal)
  double t0_min = 0, t0_max = 0;
  double tf_min = 0;         // normalized lower end of the final-time window
  double epoch_mjd2000 = 0;  // calendar epoch of t0, for ephemeris targets
  bool has_epoch = false;
  // minimum_initial_mass: m(t0) is free (a shooting variable), m(tf) is fixed at final_mass; the
  // mass scale is then the final mass. Otherwise the mass scale is m0 and m(t0) = 1.
  bool free_initial_mass = false;
  double final_mass = 1;
  bool has_state(const std::string& name) const;
  // The intermediates, for differentiating through them.
  symbolic::ChainRule chain_rule() const;
  bool has_control(const std::string& name) const;
};

// Builds the problem of a validated spec. Throws std::invalid_argument / std::domain_error
// naming the spec field for what this engine cannot formulate.
Problem build_problem(const io::json& spec);

}  // namespace helios::pmp

#pragma once
// The necessary conditions of a problem (Pontryagin) as a typed result:
// the Hamiltonian, the canonical system, the control law, the boundary, jump, stationarity and
// transversality conditions, and the shooting system built from them. Expressions are GiNaC
// expressions in the symbols of `problem.symbols`; pmp::derivation_json writes the artifact.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp {

// Minimizer of H over a unit thrust direction a that enters H linearly: a* = -b/|b|.
struct DirectionLaw {
  std::vector<std::string> controls;
  std::vector<GiNaC::ex> b;
  std::vector<GiNaC::ex> law;       // a_j*
  std::vector<GiNaC::ex> gradient;  // g_j = dH/da_j
  std::string costate_block;        // e.g. "l_vx, l_vy, l_vz" if b is that block of costates (primer vector)
};

// Minimizer of H over a flat sail's unit normal n (n.rhat >= 0), through its cone angle.
struct SailLaw {
  std::vector<std::string> controls;
  std::vector<std::pair<std::string, GiNaC::ex>> definitions;  // sail_A, sail_B, sail_alpha, in order
  GiNaC::ex cone_angle;                                        // alpha*(x, lambda, definitions)
  std::vector<GiNaC::ex> law;  // n* in terms of the cone angle symbol sail_alpha and the definitions
  std::string stationarity;    // dh/dalpha = 0 as a polynomial in tan(alpha), as text
};

// Minimizer of H over a throttle u in [0, 1] that enters H at most quadratically.
struct ThrottleLaw {
  std::string control;
  GiNaC::ex switching;           // dH/du at u = 0 and eps = 0: u* = 1 where it is negative (bang-bang)
  GiNaC::ex at_lower, at_upper;  // dH/du at u = 0 and u = 1
  GiNaC::ex second;              // d2H/du2
  GiNaC::ex interior;            // the root of dH/du = 0 (0 when dH/du does not depend on u)
};

struct ControlLaw {
  DirectionLaw direction;  // no controls when the problem has no thrust direction
  std::optional<SailLaw> sail;
  std::optional<ThrottleLaw> throttle;
};

// A state's value at t0: solved from psi(x(t0)) = 0, or a shooting variable (a free m(t0)).
struct InitialValue {
  std::string state;
  GiNaC::ex value;
};

// The conditions an endpoint constraint imposes. At t0 the states it fixes have free costates;
// at tf lambda(tf) - lambda0 dphi/dx - nu^T dpsi/dx = 0, one row per state, and the rows of
// the states psi fixes determine the equality multipliers (eliminated).
struct EndpointConditions {
  EndpointConstraint constraint;
  std::vector<std::string> multipliers;   // nu_<id>_<j>, one per row of psi
  std::vector<GiNaC::ex> transversality;  // the rows at tf, in the state symbols
  std::vector<GiNaC::ex> eliminated;      // the rows that determine the equality multipliers
  std::string time_condition;             // what the constraint adds to a free time's condition
};

// The costate leaving an interior event: explicit for a state the map carries over, otherwise a
// shooting variable (`value` is then its symbol) with its jump row as an equation.
struct CostateAfterEvent {
  std::string costate;
  GiNaC::ex value;
  bool shooting_variable = false;
};

// The conditions of an interior event (Bryson-Ho) from psi = [c ; x+ - g].
struct EventConditions {
  InteriorEvent event;
  std::string time_symbol;
  GiNaC::ex time;                        // t_<id> in its shooting variable t_<id>_frac
  std::vector<GiNaC::ex> psi;            // c, then x+ - g
  std::vector<std::string> multipliers;  // nu_<id>_<j> of c, then -lambda(t+) of x+ - g
  std::vector<CostateAfterEvent> costate_map;
};

struct ShootingVariable {
  std::string name, meaning;
  std::string role;  // "" (a costate at t0 or lambda0), multiplier, time_fraction, parameter, initial_state
  std::string init;
  std::optional<std::pair<double, double>> range = std::nullopt;
};

// A bound's row, held at an edge of its window while a leg is solved alone and the bound is active.
struct HeldWhenActive {
  std::string variable;
  int value = 0;
};

struct ShootingEquation {
  std::string name;
  GiNaC::ex expression;
  std::string meaning, source;
  // A bound psi_j <= 0 (two passes): while inactive the equation is `multiplier` = 0.
  bool inequality = false;
  std::string multiplier = "";
  std::optional<HeldWhenActive> held_when_active = std::nullopt;
  // The equation that replaces this one while a leg is solved alone.
  std::optional<GiNaC::ex> alone_expression = std::nullopt;
};

struct Shooting {
  std::vector<ShootingVariable> variables;
  std::vector<ShootingEquation> equations;
};

// A value of H the runtime evaluates (H_<at>) for the conditions of a free time.
struct HamiltonianValue {
  std::string at, meaning;
};

struct Derivation {
  Problem problem;                      // with the symbols the derivation adds (multipliers, values at events)
  GiNaC::ex hamiltonian;                // H = lambda0 L + lambda^T f
  bool smoothed = false;                // H contains the homotopy parameter eps (quadratic smoothing)
  std::vector<GiNaC::ex> state_odes;    // dH/dlambda, one per state
  std::vector<GiNaC::ex> costate_odes;  // -dH/dx, one per state
  ControlLaw control;
  std::vector<InitialValue> initial_values;
  std::vector<EndpointConditions> constraints;
  std::vector<EventConditions> events;
  std::vector<HamiltonianValue> hamiltonian_values;
  Shooting shooting;
};

// Derives the necessary conditions of `problem`. Throws std::invalid_argument for what the
// builtin engine cannot formulate, std::logic_error when one of its own checks fails.
Derivation derive_conditions(const Problem& problem);

// The derivation artifact (schemas/derivation.schema.json) of `derivation`.
io::json derivation_json(const Derivation& derivation);

}  // namespace helios::pmp

#pragma once
// The necessary conditions of a problem (Pontryagin) as a typed result:
// the Hamiltonian, the canonical system, the control law, the boundary, jump, stationarity and
// transversality conditions, and the shooting system built from them. Expressions are GiNaC
// expressions in the symbols of `problem.symbols`; pmp::derivation_json writes the artifact.
#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "helios/derivation/sections.hpp"
#include "helios/io/json_io.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp {

// The sections the readers share (derivation/sections.hpp), with GiNaC expressions: the control
// law (a thrust direction, a sail's normal, a throttle), the initial values, the values of H the
// runtime evaluates and the shooting system.
using DirectionLaw = derivation::sections::DirectionLaw<GiNaC::ex>;
using SailLaw = derivation::sections::SailLaw<GiNaC::ex>;
using ThrottleLaw = derivation::sections::ThrottleLaw<GiNaC::ex>;
using ControlLaw = derivation::sections::ControlLaw<GiNaC::ex>;
using InitialValue = derivation::sections::InitialValue<GiNaC::ex>;
using derivation::sections::EventValue;
using Inequality = derivation::sections::Inequality<GiNaC::ex>;
using derivation::sections::ShootingVariable;
using ShootingEquation = derivation::sections::ShootingEquation<GiNaC::ex>;
using Shooting = derivation::sections::Shooting<GiNaC::ex>;

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
  std::vector<EventValue> hamiltonian_values;  // H_<at> for the conditions of a free time
  Shooting shooting;
};

// Derives the necessary conditions of `problem`. Throws std::invalid_argument for what the
// builtin engine cannot formulate, std::logic_error when one of its own checks fails.
Derivation derive_conditions(const Problem& problem);

// The derivation artifact (schemas/derivation.schema.json) of `derivation`.
io::json derivation_json(const Derivation& derivation);

}  // namespace helios::pmp

#pragma once
// The sections of the derivation artifact (schemas/derivation.schema.json) that its writer and its
// readers share, defined once: the control law, the initial values, the event values and the
// shooting system, the intermediates of the dynamics, the endpoint constraints and the interior
// events. Each struct is a template over how an expression is held:
// helios-derive fills it with GiNaC expressions (pmp::Derivation, E = GiNaC::ex), the readers with the text and JSON
// pointer of each expression (derivation::Document, E = Expression). One to_json writes either;
// one read_* reads the JSON back into the Expression form, strictly: a field missing or of the
// wrong type throws std::invalid_argument "field <pointer> must be ..., got <value>", to which
// the Document adds the file's name.
//
// A member is the JSON member of the same name; one the readers do not require is not written
// when empty (an empty string or list, an empty optional). A new section is one struct here, its
// to_json and read_* in document.cpp, and a member each of pmp::Derivation and of Document.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::derivation {

// An expression of the artifact: its text and its JSON pointer (e.g. /costate_odes/3/rhs).
struct Expression {
  std::string text, pointer;
};

namespace sections {

// intermediates[]: a named quantity of the dynamics (a solar-electric thruster's input power, its
// thrust and mass flow at that power), a function of the time, the states, the parameters and the
// earlier intermediates only, in order. Any other expression of the artifact may use its name:
// a reader evaluates the intermediates first, and differentiates through them by the chain rule
// (symbolic/chain_rule.hpp). They keep the expressions of an engine given by fits from expanding
// into the powers of its power law.
template <class E>
struct Intermediate {
  std::string name, meaning, unit;
  E expression;
};

// A named intermediate expression of a direction or sail law.
template <class E>
struct Definition {
  std::string name;
  E expression;
};

// control_law.direction: a unit thrust direction a that enters H linearly, a* = -g/|g| with
// g = dH/da; the controls it is for, named intermediate expressions and a* by control.
template <class E>
struct DirectionLaw {
  std::vector<std::string> controls;
  std::vector<Definition<E>> definitions;
  std::vector<E> law;
  std::vector<E> dH_da;
  std::string reason;
};

// control_law.sail: a flat sail's unit normal n (n.rhat >= 0) through its cone angle; n* by
// control in terms of the definitions (sail_A, sail_B, sail_alpha, in order).
template <class E>
struct SailLaw {
  std::vector<std::string> controls;
  std::vector<Definition<E>> definitions;
  E cone_angle;
  std::vector<E> law;
  std::string stationarity;  // dh/dalpha = 0 as a polynomial in tan(alpha), as text
  std::string admissible, reason;
};

// control_law.throttle: a throttle u in [0, 1] that enters H at most quadratically.
template <class E>
struct ThrottleLaw {
  std::string control;
  std::vector<double> bounds = {0, 1};
  E switching_function;              // dH/du at u = 0 and eps = 0: u* = 1 where it is negative
  E dH_du_at_lower, dH_du_at_upper;  // dH/du at u = 0 and u = 1
  std::optional<E> d2H_du2;
  E interior;             // the root of dH/du = 0 (0 when dH/du does not depend on u)
  std::string smoothing;  // "quadratic" or "none"
  std::string law;
};

template <class E>
struct ControlLaw {
  std::optional<DirectionLaw<E>> direction;
  std::optional<SailLaw<E>> sail;
  std::optional<ThrottleLaw<E>> throttle;
  std::vector<std::string> other;  // members of another name: laws of controls no reader knows (not written)
};

// initial_values[]: a state's value at t0, solved from psi(x(t0)) = 0 or a shooting variable.
template <class E>
struct InitialValue {
  std::string state;
  E value;
};

// A condition g > 0 a constraint's rows leave to the runtime (must_be_positive): they also hold
// on the target's mirror (an orbit run the other way), where an extremal is not returned.
template <class E>
struct SideCondition {
  E expression;
  std::string meaning;
};

// constraints[]: an endpoint constraint psi = 0 at t0 or tf with the multipliers nu of its rows,
// the conditions it gives in words (at tf the transversality rows "... = 0"), the rows that
// determine its equality multipliers (at tf), and what it adds to a free time's condition.
template <class E>
struct Constraint {
  std::string id, kind, at;
  io::json target;  // where it takes its target from, as written (null when absent: not written)
  std::vector<E> psi;
  std::vector<std::string> multipliers;
  std::vector<SideCondition<E>> must_be_positive;
  std::optional<std::vector<std::string>> conditions, eliminated_multipliers;
  std::string time_condition;
};

// One state's value after an interior event.
template <class E>
struct StateMapEntry {
  std::string state;
  E expression;
};

// One costate just after an interior event: a new shooting variable or an expression.
template <class E>
struct CostateMapEntry {
  std::string costate;
  std::optional<std::string> variable;
  std::optional<E> expression;
};

// events[]: an interior event at the epoch time_symbol = time_expression in its window (a stay of
// `duration`), its interior constraint psi with multipliers, the conditions in words, and the maps
// of the states and costates across it.
template <class E>
struct Event {
  std::string id, kind;
  io::json target;  // null when absent (not written)
  std::string time_symbol;
  std::vector<double> window;
  E time_expression;
  double duration = 0;
  std::vector<E> psi;
  std::vector<std::string> multipliers;
  std::vector<SideCondition<E>> must_be_positive;  // in the state just before the event
  std::vector<std::string> conditions;
  std::vector<StateMapEntry<E>> state_map;
  std::vector<CostateMapEntry<E>> costate_map;
};

// event_values[]: a value the runtime evaluates (H just before or after an event, H at tf, ...).
struct EventValue {
  std::string name, meaning;
  std::optional<std::string> kind, at;
};

// A bound psi <= 0 of the shooting system (two passes): while inactive its row is the
// multiplier = 0 (inactive_expression); active, psi = 0 and the multiplier >= 0.
template <class E>
struct Inequality {
  std::string sense, multiplier;
  E inactive_expression;
  io::json rule;  // as written, null when absent
  // Active, the bound holds a variable (an event's time fraction) at a value (the window's edge).
  struct Held {
    std::string variable;
    double value = 0;
  };
  std::optional<Held> held_when_active = std::nullopt;
};

struct ShootingVariable {
  std::string name, meaning;
  std::string role;  // "" (a costate at t0 or lambda0), multiplier, time_fraction, parameter, initial_state
  std::string init;
  std::vector<double> range = {};  // empty when not given
  double scale = 1;
};

template <class E>
struct ShootingEquation {
  std::string name;
  E expression;
  std::string meaning, source;
  std::optional<Inequality<E>> inequality = std::nullopt;
  // The equation that replaces this one while a leg is solved alone.
  std::optional<E> alone_expression = std::nullopt;
  double scale = 1;
};

template <class E>
struct Shooting {
  std::vector<ShootingVariable> variables;
  std::vector<ShootingEquation<E>> equations;
  // The equation so named; null when none is.
  const ShootingEquation<E>* equation(const std::string& name) const {
    for (const auto& e : equations)
      if (e.name == name) return &e;
    return nullptr;
  }
};

// The JSON of each section, for E = GiNaC::ex and E = Expression.
template <class E>
io::json to_json(const std::vector<Intermediate<E>>& intermediates);
template <class E>
io::json to_json(const ControlLaw<E>& law);
template <class E>
io::json to_json(const std::vector<InitialValue<E>>& values);
io::json to_json(const std::vector<EventValue>& values);
template <class E>
io::json to_json(const Shooting<E>& shooting);
template <class E>
io::json to_json(const std::vector<Constraint<E>>& constraints);
template <class E>
io::json to_json(const std::vector<Event<E>>& events);

// Each section read from the artifact `d` (the whole document); an optional section absent reads empty.
std::vector<Intermediate<Expression>> read_intermediates(const io::json& d);
ControlLaw<Expression> read_control_law(const io::json& d);
std::vector<InitialValue<Expression>> read_initial_values(const io::json& d);
std::vector<EventValue> read_event_values(const io::json& d);
Shooting<Expression> read_shooting(const io::json& d);
std::vector<Constraint<Expression>> read_constraints(const io::json& d);
std::vector<Event<Expression>> read_events(const io::json& d);

}  // namespace sections

using Intermediate = sections::Intermediate<Expression>;
using Definition = sections::Definition<Expression>;
using SideCondition = sections::SideCondition<Expression>;
using Constraint = sections::Constraint<Expression>;
using StateMapEntry = sections::StateMapEntry<Expression>;
using CostateMapEntry = sections::CostateMapEntry<Expression>;
using Event = sections::Event<Expression>;
using DirectionLaw = sections::DirectionLaw<Expression>;
using SailLaw = sections::SailLaw<Expression>;
using ThrottleLaw = sections::ThrottleLaw<Expression>;
using ControlLaw = sections::ControlLaw<Expression>;
using InitialValue = sections::InitialValue<Expression>;
using sections::EventValue;
using Inequality = sections::Inequality<Expression>;
using sections::ShootingVariable;
using ShootingEquation = sections::ShootingEquation<Expression>;
using Shooting = sections::Shooting<Expression>;

}  // namespace helios::derivation

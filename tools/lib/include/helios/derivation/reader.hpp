#pragma once
// One reader of a derivation artifact (schemas/derivation.schema.json) shared by the code
// generator and the verifier: the names it declares, a symbol table with all of them registered,
// the normalization units and each state's and parameter's unit as an expression over the base
// units. It reads; it does not derive (no Hamiltonian, no condition is formed here), so the
// verifier stays independent of helios-derive's mathematics.
#include <map>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::derivation {

// A unit as powers of the base units of the normalization (length, time, mass), e.g.
// "initial mass*AU/Julian year^2" = length^1 time^-2 mass^1; "1" is dimensionless.
struct Unit {
  int length = 0, time = 0, mass = 0;
  bool operator==(const Unit& o) const { return length == o.length && time == o.time && mass == o.mass; }
  bool operator!=(const Unit& o) const { return !(*this == o); }
};

// The normalization units of derivation.json "units": the names of the length and time units and
// the sizes of the three base units. The mass unit is named by what sets it: "initial mass" or
// "final mass" (the final mass when the initial one is the unknown of a minimum-initial-mass problem).
struct Units {
  std::string length, time;
  double length_km = 1, time_s = 1, mass_kg = 1;

  // Parses a unit written over these base units: factors joined by '*' and '/' (left to right),
  // each a base unit's name or "1", optionally with an integer power "^n". Throws input_error
  // "<where>: cannot read the unit '<text>' ..." naming the unknown factor.
  Unit parse(const std::string& text, const std::string& where) const;
  // The size of one `u` when the base units are `length`, `time` and `mass` big (in some target
  // units): the positive powers multiplied, divided by the negative powers.
  static double factor(const Unit& u, double length, double time, double mass);
  // `value` of unit `u` in SI units (m, s, kg): each base unit's size applied in turn (a length
  // in km, then km -> m; a time in s; a mass in kg), so a speed is value * length_km * 1e3 / time_s.
  double to_si(double value, const Unit& u) const;
  // The size of one `u` in SI units.
  double si_factor(const Unit& u) const { return to_si(1.0, u); }
};

// What a parameter is to the tools that read it: the runtime evaluates it (it has a source), it is
// the exhaust velocity (the report's and the runtime's propellant), it scales the thrust (with the
// others of that role: the thrust continuation multiplies them), or a constant of the problem.
// The artifact states the role (a parameter's "role"); a derivation without one is read from the
// source and the meaning ("exhaust velocity ...", the words pmp wrote before roles).
enum class Role { Constant, ExhaustVelocity, RuntimeEvaluated, ThrustScale };

// A state or parameter: its name, meaning, unit as written ("" when not given: dimensionless) and as
// parsed, and (a parameter) value.
struct Quantity {
  std::string name, meaning, unit_text;
  Unit unit;
  double value = 0;            // a parameter's normalized value (0 for a state)
  std::string source;          // a parameter the runtime evaluates: its source ("ephemeris:Mars:tf"), else ""
  Role role = Role::Constant;  // a parameter's (a state's is Constant)
  bool runtime_evaluated() const { return role == Role::RuntimeEvaluated; }
};

class Reader {
 public:
  // Reads `derivation` strictly (it need not have passed its schema: the verifier reads what a
  // model wrote); `file` names it in error messages. Throws input_error "<file>: field <pointer> ..."
  // for a missing or mistyped field, a control of unknown kind, two throttles, or a unit it cannot read.
  // With parse_units false the units stay text (Quantity::unit is dimensionless): the verifier
  // checks the mathematics of a derivation, not how it names its units.
  explicit Reader(const io::json& derivation, const std::string& file = "derivation", bool parse_units = true);

  Units units;
  std::vector<Quantity> state_quantities, parameter_quantities;
  std::vector<std::string> states, costates, controls, parameters;
  std::vector<std::string> control_kinds;      // by control: throttle, direction or sail_normal
  std::vector<std::string> runtime_evaluated;  // parameters with a source, in order
  std::vector<std::string> events;             // interior events' ids
  std::vector<std::string> variables;          // the shooting variables, in x's order
  std::vector<std::string> definitions;        // control_law.direction/sail definitions' names
  std::vector<std::string> intermediates;      // intermediates' names, in order
  std::vector<std::string> event_values;       // event_values' names
  std::string multiplier, homotopy;
  int throttle_index = -1;  // index of the throttle among the controls
  // Every name above, with <x>_t0 / <x>_tf of the states and costates, t_<event> and the states
  // and costates just before / after each event (<x>_<event>_m / _p), and t.
  symbolic::SymbolTable symbols;

  const Quantity& parameter(const std::string& name) const;
  // The parameter of role ExhaustVelocity, checked to be a speed; null when the problem has none
  // (a sail).
  const Quantity* exhaust_velocity() const;

 protected:
  const io::json& d;  // the artifact as read: only the reading (Reader, Document) walks it

 private:
  void read_names(const std::string& file);
  void register_symbols();
};

}  // namespace helios::derivation

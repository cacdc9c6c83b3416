#pragma once
// Conditions on the final state written as equations of it ("At the final time r·v = 0 and
// |r| = 42165 km."): each becomes one row psi_j(x) = 0 of the endpoint constraint, so the
// minimum principle's conditions follow from psi by differentiation as for any other constraint.
//
// An expression uses the state in the spec's units: x, y, z and r = |r| [km], vx, vy, vz and
// v = |v| [km/s], hx, hy, hz and h = |r x v| [km^2/s], m [kg], and the central body's mu
// [km^3/s^2]. Its dimension is found by scaling (it must be a power law in the length, time and
// mass units: "r + v" is refused), and the value it equals is written in that dimension's unit
// made of km, s and kg.
#include <string>

#include <ginac/ginac.h>

#include "helios/io/json_io.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::spec {

inline constexpr const char* kStateConditionVariables[] = {"x", "y",  "z",  "r",  "vx", "vy", "vz",
                                                           "v", "hx", "hy", "hz", "h",  "m",  "mu"};

// The exponents of km, s and kg in an expression's unit.
struct UnitDimension {
  double length = 0, time = 0, mass = 0;
  bool operator==(const UnitDimension& o) const;
};

// The table of kStateConditionVariables.
symbolic::SymbolTable state_condition_symbols();

// The dimension of `f` (an expression in state_condition_symbols()); throws std::invalid_argument
// "<where>: ..." when it is not a power law in the units, or involves no state at all.
UnitDimension expression_dimension(const GiNaC::ex& f, const symbolic::SymbolTable& vars, const std::string& where);

// The unit of `d` in km, s and kg ("km^2/s", "km", "1" for none).
std::string unit_text(const UnitDimension& d);

// A unit written as a product of km, m, AU, s, min, h, day, kg and g with integer powers
// ("km^2/s", "m/s", "km^3/s^2"): its dimension and the factor taking it to km, s and kg. Throws
// std::invalid_argument naming the part it cannot read.
struct ParsedUnit {
  UnitDimension dimension;
  double factor = 1;
};
ParsedUnit parse_unit(const std::string& unit);

// Refuses a condition's value `stated` that another unit takes out of the range of a double:
// `in_unit`, the same value there, is infinite, or zero or subnormal while `stated` is not (1e300
// AU^40 in km^40; 1e300 km^40 in a derivation's normalized units, AU^40 being beyond 1e308).
// Throws std::invalid_argument "<what> is beyond the range of a double ...".
void require_in_range(double stated, double in_unit, const std::string& what);

// The notations a user writes rewritten into the expression language: "r·v" (also "r . v",
// "dot(r, v)") the dot product, "|r|", "|v|", "|h|" and "|r x v|" the norms.
std::string state_expression_text(const std::string& written);

// One condition as the spec holds it: {"expression": E, "equals": V, "unit": U}: E = V, V in
// U = unit_text(E's dimension). `lhs` and `rhs` as written; rhs a number with an optional unit
// (required unless the number is 0 or E has no dimension) or an expression of the state (then
// E = lhs - rhs and V = 0). Throws std::invalid_argument naming what is wrong.
io::json state_condition(const std::string& lhs, const std::string& rhs);

}  // namespace helios::spec

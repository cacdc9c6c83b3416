// Conditions on the final state written as equations (state_conditions.hpp): the notation a user
// writes, the dimension of an expression by scaling, and composite units.
#include "helios/spec/state_conditions.hpp"

#include <cmath>
#include <map>
#include <random>
#include <regex>
#include <stdexcept>

#include "grammar.hpp"
#include "helios/astro/constants.hpp"
#include "helios/io/json_io.hpp"

namespace helios::spec {
namespace {

// The dimension of each variable: (km, s, kg) exponents.
const std::map<std::string, UnitDimension>& variable_dimensions() {
  static const std::map<std::string, UnitDimension> d = {
      {"x", {1, 0, 0}},   {"y", {1, 0, 0}},   {"z", {1, 0, 0}},  {"r", {1, 0, 0}},   {"vx", {1, -1, 0}},
      {"vy", {1, -1, 0}}, {"vz", {1, -1, 0}}, {"v", {1, -1, 0}}, {"hx", {2, -1, 0}}, {"hy", {2, -1, 0}},
      {"hz", {2, -1, 0}}, {"h", {2, -1, 0}},  {"m", {0, 0, 1}},  {"mu", {3, -2, 0}}};
  return d;
}

// f at the point `values`, the units scaled by (length, time, mass): NaN where it is not real.
double value_at(const GiNaC::ex& f, const symbolic::SymbolTable& vars, const std::map<std::string, double>& values,
                double length, double time, double mass) {
  GiNaC::exmap at;
  for (const auto& [name, d] : variable_dimensions())
    at[vars.symtab().at(name)] =
        values.at(name) * std::pow(length, d.length) * std::pow(time, d.time) * std::pow(mass, d.mass);
  const GiNaC::ex e = f.subs(at).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(e)) return NAN;
  const GiNaC::numeric n = GiNaC::ex_to<GiNaC::numeric>(e);
  return n.is_real() ? n.to_double() : NAN;
}

std::string exponent_text(const std::string& unit, double power) {
  const double p = std::fabs(power);
  return p == 1 ? unit : unit + "^" + io::short_number(p);
}

}  // namespace

bool UnitDimension::operator==(const UnitDimension& o) const {
  return std::fabs(length - o.length) < 1e-9 && std::fabs(time - o.time) < 1e-9 && std::fabs(mass - o.mass) < 1e-9;
}

symbolic::SymbolTable state_condition_symbols() {
  symbolic::SymbolTable vars;
  for (const char* v : kStateConditionVariables) vars.get(v);
  return vars;
}

UnitDimension expression_dimension(const GiNaC::ex& f, const symbolic::SymbolTable& vars, const std::string& where) {
  bool state = false;
  for (const auto& [name, s] : vars.symtab())
    if (name != "mu" && f.has(s)) state = true;
  if (!state) throw std::invalid_argument(where + ": '" + symbolic::to_text(f) + "' involves no state");
  // f(units scaled by k) = k^a f: a from k = 2, checked at k = 3, at two points where f is real
  // and not zero.
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> draw(0.5, 1.5);
  std::vector<UnitDimension> found;
  for (int attempt = 0; attempt < 40 && found.size() < 2; ++attempt) {
    std::map<std::string, double> values;
    for (const auto& [name, d] : variable_dimensions()) values[name] = draw(rng);
    const double f0 = value_at(f, vars, values, 1, 1, 1);
    if (!std::isfinite(f0) || std::fabs(f0) < 1e-12) continue;
    const auto power = [&](int axis) {
      const auto scaled = [&](double k) {
        return value_at(f, vars, values, axis == 0 ? k : 1, axis == 1 ? k : 1, axis == 2 ? k : 1) / f0;
      };
      const double two = scaled(2), three = scaled(3);
      const double a = std::log(two) / std::log(2.0);
      if (!(two > 0) || !(std::fabs(std::log(three) / std::log(3.0) - a) < 1e-9))
        throw std::invalid_argument(where + ": '" + symbolic::to_text(f) +
                                    "' mixes units (e.g. a length and a speed added): write each side in one unit");
      return std::round(a * 1e6) / 1e6;
    };
    found.push_back({power(0), power(1), power(2)});
  }
  if (found.empty())
    throw std::invalid_argument(where + ": '" + symbolic::to_text(f) + "' is zero or not real at every state tried");
  if (found.size() == 2 && !(found[0] == found[1]))
    throw std::invalid_argument(where + ": '" + symbolic::to_text(f) + "' mixes units");
  return found[0];
}

std::string unit_text(const UnitDimension& d) {
  std::string up, down;
  for (const auto& [unit, power] : {std::pair<const char*, double>{"kg", d.mass}, {"km", d.length}, {"s", d.time}}) {
    if (power == 0) continue;
    std::string& side = power > 0 ? up : down;
    side += (side.empty() ? "" : "*") + exponent_text(unit, power);
  }
  if (up.empty() && down.empty()) return "1";
  return (up.empty() ? "1" : up) + (down.empty() ? "" : "/" + down);
}

ParsedUnit parse_unit(const std::string& unit) {
  static const std::map<std::string, std::pair<UnitDimension, double>> base = {
      {"km", {{1, 0, 0}, 1.0}},    {"m", {{1, 0, 0}, 1e-3}},      {"AU", {{1, 0, 0}, astro::AU_KM}},
      {"s", {{0, 1, 0}, 1.0}},     {"min", {{0, 1, 0}, 60.0}},    {"h", {{0, 1, 0}, 3600.0}},
      {"d", {{0, 1, 0}, 86400.0}}, {"day", {{0, 1, 0}, 86400.0}}, {"days", {{0, 1, 0}, 86400.0}},
      {"kg", {{0, 0, 1}, 1.0}},    {"g", {{0, 0, 1}, 1e-3}}};
  static const std::regex factor(R"(\s*([*/·]?)\s*([A-Za-z]+)(?:\^(-?[0-9]+))?\s*)");
  ParsedUnit out;
  std::string rest = unit;
  bool first = true;
  std::smatch m;
  while (!rest.empty()) {
    if (!std::regex_search(rest, m, factor, std::regex_constants::match_continuous) || m.length(0) == 0 ||
        (first != m[1].str().empty()))
      throw std::invalid_argument("cannot read the unit '" + unit + "' (write e.g. km, km/s, km^2/s or km^3/s^2)");
    const auto it = base.find(m[2].str());
    if (it == base.end())
      throw std::invalid_argument("the unit '" + unit + "' has '" + m[2].str() +
                                  "', which is not one of km, m, AU, s, min, h, day, kg, g");
    const double power = (m[3].matched ? grammar::number(m[3].str()) : 1.0) * (m[1].str() == "/" ? -1 : 1);
    out.dimension.length += it->second.first.length * power;
    out.dimension.time += it->second.first.time * power;
    out.dimension.mass += it->second.first.mass * power;
    out.factor *= std::pow(it->second.second, power);
    rest = m.suffix().str();
    first = false;
  }
  if (first) throw std::invalid_argument("the unit is empty");
  return out;
}

void require_in_range(double stated, double in_unit, const std::string& what) {
  if (!std::isfinite(in_unit) || (stated != 0 && !std::isnormal(in_unit)))
    throw std::invalid_argument(what +
                                " is beyond the range of a double (magnitudes 2.2e-308 to 1.8e308), state the "
                                "condition with a lower power (e.g. 'r = Q' for 'r^40 = Q^40')");
}

std::string state_expression_text(const std::string& written) {
  // The dot products first (a bare r or v beside a dot), then the norms, then any dot left is a
  // product ("|r|·|v|^2").
  static const std::string dot = R"((?:\xC2\xB7|\xE2\x8B\x85|\.))";
  static const std::vector<std::pair<std::regex, std::string>> rewrites = {
      {std::regex("\xE2\x88\x92"), "-"},  // the minus sign
      {std::regex("\xC2\xB2"), "^2"},
      {std::regex("\xC2\xB3"), "^3"},
      {std::regex(R"(\|\s*r\s*(?:x|\xC3\x97)\s*v\s*\|)"), "h"},  // |r x v|, |r × v|
      {std::regex(R"(\bdot\s*\(\s*r\s*,\s*v\s*\)|\bdot\s*\(\s*v\s*,\s*r\s*\))"), "(x*vx+y*vy+z*vz)"},
      {std::regex(R"(\b(?:r\s*)" + dot + R"(\s*v|v\s*)" + dot + R"(\s*r)\b)"), "(x*vx+y*vy+z*vz)"},
      {std::regex(R"(\br\s*)" + dot + R"(\s*r\b)"), "r^2"},
      {std::regex(R"(\bv\s*)" + dot + R"(\s*v\b)"), "v^2"},
      {std::regex(R"(\|\s*(r|v|h)\s*\|)"), "$1"},
      {std::regex("\xC2\xB7|\xE2\x8B\x85"), "*"},  // not '.', which is also a decimal point
  };
  std::string text = written;
  for (const auto& [pattern, with] : rewrites) text = std::regex_replace(text, pattern, with);
  return text;
}

io::json state_condition(const std::string& lhs_written, const std::string& rhs_written) {
  const auto trim = [](const std::string& t) {
    const auto first = t.find_first_not_of(' '), last = t.find_last_not_of(' ');
    return first == std::string::npos ? std::string() : t.substr(first, last - first + 1);
  };
  const std::string lhs = trim(lhs_written), rhs = trim(rhs_written);
  static const std::regex number_with_unit(R"(\s*([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*)");
  const symbolic::SymbolTable vars = state_condition_symbols();
  const std::string left = trim(state_expression_text(lhs));
  const std::string variables =
      " (the state: x, y, z, r [km], vx, vy, vz, v [km/s], hx, hy, hz, h [km^2/s], m [kg]; mu [km^3/s^2]; "
      "r·v, |r|, |v|, |r x v|)";
  const auto parse = [&](const std::string& text, const std::string& side) {
    try {
      return vars.parse(text, side);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(e.what() + variables);
    }
  };
  const GiNaC::ex f = parse(left, "the left side '" + lhs + "'");
  std::smatch m;
  if (std::regex_match(rhs, m, number_with_unit)) {
    const UnitDimension d = expression_dimension(f, vars, "'" + lhs + "'");
    const double written = grammar::number(m[1].str());
    double value = written;
    if (!m[2].str().empty()) {
      const ParsedUnit u = parse_unit(m[2].str());
      if (!(u.dimension == d))
        throw std::invalid_argument("'" + rhs + "' is in " + unit_text(u.dimension) + ", but '" + lhs + "' is in " +
                                    unit_text(d));
      value *= u.factor;
    } else if (value != 0 && !(d == UnitDimension{})) {
      throw std::invalid_argument("'" + rhs + "' needs a unit: '" + lhs + "' is in " + unit_text(d));
    }
    require_in_range(written, value, "'" + rhs + "' in " + unit_text(d));
    return {{"expression", left}, {"equals", value}, {"unit", unit_text(d)}};
  }
  const std::string right = trim(state_expression_text(rhs));
  parse(right, "the right side '" + rhs + "'");
  const std::string both = "(" + left + ") - (" + right + ")";
  const UnitDimension d =
      expression_dimension(parse(both, "'" + lhs + " = " + rhs + "'"), vars, "'" + lhs + " = " + rhs + "'");
  return {{"expression", both}, {"equals", 0.0}, {"unit", unit_text(d)}};
}

}  // namespace helios::spec

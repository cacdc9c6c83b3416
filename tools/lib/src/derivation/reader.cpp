#include "helios/derivation/reader.hpp"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include "helios/derivation/names.hpp"
#include "helios/io/error.hpp"

namespace helios::derivation {
namespace {

using io::json;

std::string trimmed(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

// The power of a factor "name^n" (1 without '^'); `name` is left without it.
int split_power(std::string& name, const std::string& where, const std::string& text) {
  const auto hat = name.rfind('^');
  if (hat == std::string::npos) return 1;
  const std::string digits = trimmed(name.substr(hat + 1));
  char* end = nullptr;
  const long n = std::strtol(digits.c_str(), &end, 10);
  if (digits.empty() || *end != '\0')
    throw input_error(where + ": cannot read the unit '" + text + "': the power '" + digits + "' is not an integer");
  name = trimmed(name.substr(0, hat));
  return static_cast<int>(n);
}

// A state (value_required false) or a parameter of `file`; `where` is its JSON pointer. Its unit is parsed
// over `units` unless that is null.
Quantity quantity(const json& q, const Units* units, const std::string& file, const std::string& where,
                  bool value_required) {
  Quantity out;
  out.name = io::require_string(q, "name", where);
  out.meaning = q.value("meaning", "");
  out.unit_text = q.value("unit", "");
  if (units) out.unit = units->parse(q.contains("unit") ? out.unit_text : "1", file + ": field " + where + "/unit");
  out.value = value_required ? io::require_number(q, "value", where) : q.value("value", 0.0);
  out.source = q.contains("source") && q.at("source").is_string() ? q.at("source").get<std::string>() : "";
  // The role a parameter states ("role"); a derivation that states none (a model's, written before
  // roles) is read by the meaning pmp once wrote ("exhaust velocity ...").
  const std::string role = q.contains("role") && q.at("role").is_string() ? q.at("role").get<std::string>() : "";
  if (!role.empty() && role != "thrust_scale" && role != "exhaust_velocity")
    throw input_error(file + ": field " + where + "/role: '" + role + "' is no role (thrust_scale, exhaust_velocity)");
  if (!out.source.empty())
    out.role = Role::RuntimeEvaluated;
  else if (role == "exhaust_velocity" ||
           (value_required && role.empty() && out.meaning.rfind("exhaust velocity", 0) == 0))
    out.role = Role::ExhaustVelocity;
  else if (role == "thrust_scale")
    out.role = Role::ThrustScale;
  return out;
}

// The array `key` of `obj` (an empty one when absent); an error when it is something else.
const json& array_or_empty(const json& obj, const char* key, const std::string& where) {
  static const json kEmpty = json::array();
  if (!obj.is_object() || !obj.contains(key)) return kEmpty;
  if (!obj.at(key).is_array()) throw std::invalid_argument("field " + where + "/" + key + " must be an array");
  return obj.at(key);
}

}  // namespace

Unit Units::parse(const std::string& text, const std::string& where) const {
  Unit u;
  int sign = 1;  // of the factor being read: after '/' its powers count negatively
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != '*' && text[i] != '/') continue;
    std::string name = trimmed(text.substr(start, i - start));
    const int power = sign * split_power(name, where, text);
    if (name == length)
      u.length += power;
    else if (name == time)
      u.time += power;
    else if (name == "initial mass" || name == "final mass")
      u.mass += power;
    else if (name != "1")
      throw input_error(where + ": cannot read the unit '" + text + "': '" + name + "' is none of the base units " +
                        length + ", " + time + ", initial mass, final mass (or 1)");
    if (i < text.size()) sign = text[i] == '/' ? -1 : 1;
    start = i + 1;
  }
  return u;
}

double Units::factor(const Unit& u, double length, double time, double mass) {
  double up = 1, down = 1;
  for (const auto& [size, power] : {std::pair{length, u.length}, {time, u.time}, {mass, u.mass}})
    for (int k = 0; k < std::abs(power); ++k) (power > 0 ? up : down) *= size;
  return up / down;
}

double Units::to_si(double value, const Unit& u) const {
  for (int k = 0; k < std::abs(u.length); ++k) value = u.length > 0 ? value * length_km * 1e3 : value / length_km / 1e3;
  for (int k = 0; k < std::abs(u.time); ++k) value = u.time > 0 ? value * time_s : value / time_s;
  for (int k = 0; k < std::abs(u.mass); ++k) value = u.mass > 0 ? value * mass_kg : value / mass_kg;
  return value;
}

Reader::Reader(const json& derivation, const std::string& file, bool parse_units) : d(derivation) {
  const Units* unit_base = parse_units ? &units : nullptr;
  try {
    read_names(file);
    const json& state_list = d.at("states");
    for (std::size_t i = 0; i < state_list.size(); ++i)
      state_quantities.push_back(quantity(state_list[i], unit_base, file, "/states/" + std::to_string(i), false));
    const json& parameter_list = d.at("parameters");
    for (std::size_t i = 0; i < parameter_list.size(); ++i)
      parameter_quantities.push_back(
          quantity(parameter_list[i], unit_base, file, "/parameters/" + std::to_string(i), true));
  } catch (const std::invalid_argument& e) {  // io::require*: "field <pointer> is missing" and the like
    throw input_error(file + ": " + e.what());
  }
  register_symbols();
}

void Reader::read_names(const std::string& file) {
  if (!d.is_object()) throw input_error(file + ": not a JSON object");
  const json& u = io::require(d, "units", "");
  units.length = io::require_string(u, "length", "/units");
  units.time = io::require_string(u, "time", "/units");
  units.length_km = io::require_number(u, "length_km", "/units");
  units.time_s = io::require_number(u, "time_s", "/units");
  units.mass_kg = io::require_number(u, "mass_kg", "/units");
  const json& state_list = io::require(d, "states", "");
  if (!state_list.is_array() || state_list.empty())
    throw input_error(file + ": field states must be a non-empty array");
  for (std::size_t i = 0; i < state_list.size(); ++i) {
    const std::string where = "/states/" + std::to_string(i);
    states.push_back(io::require_string(state_list[i], "name", where));
    costates.push_back(io::require_string(state_list[i], "costate", where));
  }
  const json& control_list = io::require(d, "controls", "");
  for (std::size_t i = 0; i < control_list.size(); ++i) {
    const std::string where = "/controls/" + std::to_string(i);
    const std::string name = io::require_string(control_list[i], "name", where);
    const std::string kind = io::require_string(control_list[i], "kind", where);
    if (kind != "throttle" && kind != "direction" && kind != "sail_normal")
      throw input_error(file + ": control " + name + " has unknown kind '" + kind + "'");
    if (kind == "throttle" && throttle_index >= 0)
      throw input_error(file + ": more than one throttle control (" + controls[std::size_t(throttle_index)] + ", " +
                        name + ")");
    if (kind == "throttle") throttle_index = static_cast<int>(controls.size());
    controls.push_back(name);
    control_kinds.push_back(kind);
  }
  for (const auto& p : array_or_empty(d, "parameters", "")) {
    parameters.push_back(io::require_string(p, "name", "/parameters"));
    if (p.contains("source") && p.at("source").is_string()) runtime_evaluated.push_back(parameters.back());
  }
  multiplier = io::require_string(d, "multiplier", "");
  homotopy = io::require_string(io::require(d, "homotopy", ""), "symbol", "/homotopy");
  for (const auto& e : array_or_empty(d, "event_values", ""))
    event_values.push_back(io::require_string(e, "name", "/event_values"));
  if (d.contains("shooting"))
    for (const auto& v : array_or_empty(d.at("shooting"), "variables", "/shooting"))
      variables.push_back(io::require_string(v, "name", "/shooting/variables"));
  if (d.contains("control_law") && d.at("control_law").is_object())
    for (const char* kind : {"direction", "sail"})
      if (d.at("control_law").contains(kind))
        for (const auto& def : array_or_empty(d.at("control_law").at(kind), "definitions", "/control_law"))
          definitions.push_back(io::require_string(def, "name", "/control_law/" + std::string(kind) + "/definitions"));
  for (const auto& e : array_or_empty(d, "events", "")) events.push_back(io::require_string(e, "id", "/events"));
  for (const auto& q : array_or_empty(d, "intermediates", ""))
    intermediates.push_back(io::require_string(q, "name", "/intermediates"));
}

void Reader::register_symbols() {
  // The symbols, in a fixed order: GiNaC orders the terms of a printed expression by the order in
  // which its symbols were made, so the generated code depends on it.
  symbols.get("t");
  for (const auto* of : {&event_values, &variables, &definitions, &states, &costates, &controls, &parameters})
    for (const auto& n : *of) symbols.get(n);
  symbols.get(multiplier);
  symbols.get(homotopy);
  for (const auto* of : {&states, &costates})
    for (const auto& n : *of) {
      symbols.get(names::at_tf(n));
      symbols.get(names::at_t0(n));
    }
  for (const auto& id : events) {
    symbols.get(names::event_time(id));
    for (const auto* of : {&states, &costates})
      for (const auto& n : *of) {
        symbols.get(names::before(n, id));
        symbols.get(names::after(n, id));
      }
  }
  // Last, so that a derivation without intermediates makes its symbols as before.
  for (const auto& n : intermediates) symbols.get(n);
}

const Quantity& Reader::parameter(const std::string& name) const {
  for (const auto& q : parameter_quantities)
    if (q.name == name) return q;
  throw std::out_of_range("derivation: no parameter " + name);
}

const Quantity* Reader::exhaust_velocity() const {
  const Quantity* found = nullptr;
  for (const auto& q : parameter_quantities)
    if (q.role == Role::ExhaustVelocity) {
      if (found)
        throw input_error("derivation: two parameters are the exhaust velocity (" + found->name + ", " + q.name + ")");
      if (q.unit != Unit{1, -1, 0})
        throw input_error("derivation: parameter " + q.name + " is the exhaust velocity but its unit '" + q.unit_text +
                          "' is not a speed (" + units.length + "/" + units.time + ")");
      found = &q;
    }
  return found;
}

}  // namespace helios::derivation

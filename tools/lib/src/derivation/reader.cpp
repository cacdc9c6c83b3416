#include "helios/derivation/reader.hpp"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

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

Quantity quantity(const json& q, const Units& units, const std::string& where) {
  Quantity out;
  out.name = q.at("name").get<std::string>();
  out.meaning = q.value("meaning", "");
  out.unit_text = q.value("unit", "1");
  out.unit = units.parse(out.unit_text, where + "/unit");
  out.value = q.value("value", 0.0);
  out.source = q.contains("source") && q.at("source").is_string() ? q.at("source").get<std::string>() : "";
  return out;
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

Reader::Reader(const json& derivation, const std::string& file) : d(derivation) {
  const json& u = d.at("units");
  units.length = u.at("length").get<std::string>();
  units.time = u.at("time").get<std::string>();
  units.length_km = u.at("length_km").get<double>();
  units.time_s = u.at("time_s").get<double>();
  units.mass_kg = u.at("mass_kg").get<double>();
  const std::string at = file + ": field ";
  for (std::size_t i = 0; i < d.at("states").size(); ++i) {
    const json& s = d.at("states")[i];
    state_quantities.push_back(quantity(s, units, at + "/states/" + std::to_string(i)));
    states.push_back(s.at("name"));
    costates.push_back(s.at("costate"));
  }
  for (const auto& c : d.at("controls")) {
    controls.push_back(c.at("name"));
    if (c.at("kind") == "throttle") throttle_index = static_cast<int>(controls.size()) - 1;
  }
  for (std::size_t i = 0; i < d.at("parameters").size(); ++i) {
    parameter_quantities.push_back(quantity(d.at("parameters")[i], units, at + "/parameters/" + std::to_string(i)));
    parameters.push_back(parameter_quantities.back().name);
    if (parameter_quantities.back().runtime_evaluated()) runtime_evaluated.push_back(parameters.back());
  }
  multiplier = d.at("multiplier").get<std::string>();
  homotopy = d.at("homotopy").at("symbol").get<std::string>();
  for (const auto& e : d.value("event_values", json::array())) event_values.push_back(e.at("name"));
  for (const auto& v : d.at("shooting").at("variables")) variables.push_back(v.at("name"));
  for (const char* kind : {"direction", "sail"})
    if (d.at("control_law").contains(kind))
      for (const auto& def : d.at("control_law").at(kind).value("definitions", json::array()))
        definitions.push_back(def.at("name"));
  for (const auto& e : d.value("events", json::array())) events.push_back(e.at("id"));

  // The symbols, in a fixed order: GiNaC orders the terms of a printed expression by the order in
  // which its symbols were made, so the generated code depends on it.
  symbols.get("t");
  for (const auto* names : {&event_values, &variables, &definitions, &states, &costates, &controls, &parameters})
    for (const auto& n : *names) symbols.get(n);
  symbols.get(multiplier);
  symbols.get(homotopy);
  for (const auto* names : {&states, &costates})
    for (const auto& n : *names) {
      symbols.get(n + "_tf");
      symbols.get(n + "_t0");
    }
  for (const auto& id : events) {
    symbols.get("t_" + id);
    for (const auto* names : {&states, &costates})
      for (const auto& n : *names) {
        symbols.get(n + "_" + id + "_m");
        symbols.get(n + "_" + id + "_p");
      }
  }
}

const Quantity& Reader::parameter(const std::string& name) const {
  for (const auto& q : parameter_quantities)
    if (q.name == name) return q;
  throw std::out_of_range("derivation: no parameter " + name);
}

const Quantity* Reader::exhaust_velocity() const {
  const Quantity* found = nullptr;
  for (const auto& q : parameter_quantities)
    if (q.meaning.rfind("exhaust velocity", 0) == 0) {
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

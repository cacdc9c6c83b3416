// Units of the problem language, read compositionally: a unit is a product of symbols with powers
// ("km^3/s^2", "km3/s2", "AU/yr", "km/sec"), each symbol an SI symbol with an optional prefix
// (m, k, M), a named unit (AU, d, h, min, yr, t, lb, deg, rad) or a word (newtons, kilometres,
// weeks). Symbols are read with their case, since the case decides the prefix (MN is a meganewton,
// mN a millinewton); words are read without case.
#include "helios/spec/units.hpp"

#include <array>
#include <map>
#include <optional>
#include <stdexcept>

#include "helios/astro/constants.hpp"

namespace helios::spec {
namespace {

using astro::AU_KM;
using astro::DAY_S;
using astro::DEG_TO_RAD;
using astro::JULIAN_YEAR_DAYS;

// A unit's size in SI (m, s, kg; rad for angles) and its powers of length, time and mass.
struct Measure {
  double si = 1.0;
  std::array<int, 3> powers{};  // length, time, mass
  bool angle = false;
};

Measure length(double m) {
  return {m, {1, 0, 0}};
}
Measure duration(double s) {
  return {s, {0, 1, 0}};
}
Measure mass(double kg) {
  return {kg, {0, 0, 1}};
}
Measure force(double n) {
  return {n, {1, -2, 1}};
}
Measure power(double w) {
  return {w, {2, -3, 1}};
}
Measure angle(double rad) {
  return {rad, {}, true};
}

constexpr double kLb = 0.45359237;
constexpr double kWeekDays = 7.0;

// Symbols taking a prefix: metre, second, gram, newton.
const std::map<std::string, Measure>& prefixable() {
  static const std::map<std::string, Measure> t = {
      {"m", length(1.0)}, {"s", duration(1.0)}, {"g", mass(1e-3)}, {"N", force(1.0)}, {"W", power(1.0)}};
  return t;
}

// Symbols that take no prefix.
const std::map<std::string, Measure>& plain_symbols() {
  static const std::map<std::string, Measure> t = {{"AU", length(AU_KM * 1e3)},
                                                   {"au", length(AU_KM * 1e3)},
                                                   {"min", duration(60.0)},
                                                   {"h", duration(3600.0)},
                                                   {"d", duration(DAY_S)},
                                                   {"yr", duration(JULIAN_YEAR_DAYS * DAY_S)},
                                                   {"t", mass(1e3)},
                                                   {"lb", mass(kLb)},
                                                   {"lbs", mass(kLb)},
                                                   {"deg", angle(DEG_TO_RAD)},
                                                   {"rad", angle(1.0)}};
  return t;
}

// Words, matched without case.
const std::map<std::string, Measure>& words() {
  static const std::map<std::string, Measure> t = [] {
    std::map<std::string, Measure> w;
    const auto add = [&](std::initializer_list<const char*> names, Measure m) {
      for (const char* n : names) w[n] = m;
    };
    add({"newton", "newtons"}, force(1.0));
    add({"millinewton", "millinewtons"}, force(1e-3));
    add({"kilonewton", "kilonewtons"}, force(1e3));
    add({"watt", "watts"}, power(1.0));
    add({"kilowatt", "kilowatts"}, power(1e3));
    add({"metre", "metres", "meter", "meters"}, length(1.0));
    add({"kilometre", "kilometres", "kilometer", "kilometers"}, length(1e3));
    add({"second", "seconds", "sec", "secs"}, duration(1.0));
    add({"minute", "minutes", "mins"}, duration(60.0));
    add({"hour", "hours", "hr", "hrs"}, duration(3600.0));
    add({"day", "days"}, duration(DAY_S));
    add({"week", "weeks"}, duration(kWeekDays * DAY_S));
    add({"year", "years", "yrs"}, duration(JULIAN_YEAR_DAYS * DAY_S));
    add({"kilogram", "kilograms", "kilogramme", "kilogrammes"}, mass(1.0));
    add({"gram", "grams", "gramme", "grammes"}, mass(1e-3));
    add({"tonne", "tonnes"}, mass(1e3));
    add({"degree", "degrees"}, angle(DEG_TO_RAD));
    add({"radian", "radians"}, angle(1.0));
    return w;
  }();
  return t;
}

std::optional<Measure> symbol(const std::string& s) {
  if (const auto it = plain_symbols().find(s); it != plain_symbols().end()) return it->second;
  if (const auto it = prefixable().find(s); it != prefixable().end()) return it->second;
  static const std::map<char, double> prefixes = {{'m', 1e-3}, {'k', 1e3}, {'M', 1e6}};
  if (s.size() > 1 && prefixes.count(s[0]))
    if (const auto it = prefixable().find(s.substr(1)); it != prefixable().end()) {
      Measure m = it->second;
      m.si *= prefixes.at(s[0]);
      return m;
    }
  if (const auto it = words().find(lowercase(s)); it != words().end()) return it->second;
  return std::nullopt;
}

// One factor of a unit: a symbol with a power written "^3", "^-2" or "3" ("km3/s2").
std::optional<Measure> factor(const std::string& text) {
  std::string name = text;
  int power = 1;
  const std::size_t caret = text.find('^');
  if (caret != std::string::npos) {
    name = text.substr(0, caret);
    const std::string p = text.substr(caret + 1);
    // (at most 3 characters: a power beyond +-9 is refused below, and stoi would throw beyond an int)
    if (p.empty() || p.size() > 3 || p.find_first_not_of("-0123456789") != std::string::npos || p == "-")
      return std::nullopt;
    power = std::stoi(p);
  } else {
    const std::size_t digits = text.find_last_not_of("0123456789");
    if (digits != std::string::npos && digits + 1 < text.size()) {
      if (text.size() - digits - 1 > 3) return std::nullopt;
      name = text.substr(0, digits + 1);
      power = std::stoi(text.substr(digits + 1));
    }
  }
  if (name.empty() || power == 0 || power > 9 || power < -9) return std::nullopt;
  const auto m = symbol(name);
  if (!m || (m->angle && power != 1)) return std::nullopt;
  Measure out = *m;
  out.si = 1.0;
  for (int k = 0; k < std::abs(power); ++k) out.si *= m->si;
  if (power < 0) out.si = 1.0 / out.si;
  for (auto& p : out.powers) p *= power;
  return out;
}

// The whole unit: factors joined by '/', each after the first dividing.
std::optional<Measure> measure(const std::string& unit) {
  Measure out;
  std::size_t from = 0;
  for (bool first = true;; first = false) {
    const std::size_t slash = unit.find('/', from);
    const auto f = factor(unit.substr(from, slash == std::string::npos ? std::string::npos : slash - from));
    if (!f || (f->angle && !first)) return std::nullopt;
    out.si = first ? f->si : out.si / f->si;
    for (std::size_t k = 0; k < 3; ++k) out.powers[k] += first ? f->powers[k] : -f->powers[k];
    out.angle = out.angle || f->angle;
    if (slash == std::string::npos) return out;
    from = slash + 1;
  }
}

struct SpecUnit {
  std::string name, examples;
  Measure measure;
};

const SpecUnit& spec_of(Dimension d) {
  static const std::map<Dimension, SpecUnit> t = {
      {Dimension::Length, {"km", "m, km, AU", length(1e3)}},
      {Dimension::Speed, {"km/s", "m/s, km/s, AU/yr", {1e3, {1, -1, 0}}}},
      {Dimension::Force, {"N", "N, mN, kN", force(1.0)}},
      {Dimension::Time, {"days", "s, min, h, days, weeks, years", duration(DAY_S)}},
      {Dimension::Duration, {"s", "s, days", duration(1.0)}},
      {Dimension::Mass, {"kg", "kg, g, t, lb", mass(1.0)}},
      {Dimension::GravParam, {"km^3/s^2", "km^3/s^2, m^3/s^2", {1e9, {3, -2, 0}}}},
      {Dimension::Acceleration, {"mm/s^2", "mm/s^2, m/s^2, km/s^2", {1e-3, {1, -2, 0}}}},
      {Dimension::Angle, {"deg", "deg, rad", angle(DEG_TO_RAD)}},
      {Dimension::Power, {"W", "W, kW, MW", power(1.0)}},
      {Dimension::MassFlow, {"kg/s", "mg/s, g/s, kg/s", {1.0, {0, -1, 1}}}},
  };
  return t.at(d);
}

std::string dimension_name(Dimension d) {
  switch (d) {
    case Dimension::Length:
      return "length";
    case Dimension::Speed:
      return "speed";
    case Dimension::Force:
      return "force";
    case Dimension::Acceleration:
      return "acceleration";
    case Dimension::Time:
    case Dimension::Duration:
      return "time";
    case Dimension::Mass:
      return "mass";
    case Dimension::GravParam:
      return "gravitational parameter";
    case Dimension::Angle:
      return "angle";
    case Dimension::Power:
      return "power";
    case Dimension::MassFlow:
      return "mass flow";
  }
  return "?";
}

}  // namespace

std::string lowercase(const std::string& text) {
  std::string out;
  for (char c : text) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string spec_unit(Dimension d) {
  return spec_of(d).name;
}

double to_spec_unit(Dimension d, const std::string& unit) {
  const SpecUnit& want = spec_of(d);
  const auto fits = [&](const std::optional<Measure>& m) {
    return m && m->powers == want.measure.powers && m->angle == want.measure.angle;
  };
  auto m = measure(unit);
  // A unit is read without case only where case cannot change it: m/M is milli or mega, and a
  // single letter is a symbol of its own in either case (T, G, S).
  if (!m && unit.size() > 1 && unit.find_first_of("mM") == std::string::npos) m = measure(lowercase(unit));
  if (fits(m)) return m->si / want.measure.si;
  const std::string name = dimension_name(d);
  const std::string article = std::string("aeiou").find(name[0]) == std::string::npos ? "a " : "an ";
  throw std::invalid_argument("unit '" + unit + "' is not " + article + name + " unit (use " + want.examples + ")");
}

}  // namespace helios::spec

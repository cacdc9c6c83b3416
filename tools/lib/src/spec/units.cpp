#include "helios/spec/units.hpp"

#include <map>
#include <stdexcept>

#include "helios/astro/constants.hpp"

namespace helios::spec {
namespace {

struct Table {
  std::string spec_unit;
  std::string accepted;
  std::map<std::string, double> factor;
};

const Table& table(Dimension d) {
  using namespace helios::astro;
  static const std::map<Dimension, Table> tables = {
      {Dimension::Length, {"km", "m, km, AU", {{"m", 1e-3}, {"km", 1.0}, {"au", AU_KM}}}},
      {Dimension::Speed, {"km/s", "m/s, km/s", {{"m/s", 1e-3}, {"km/s", 1.0}}}},
      {Dimension::Force,
       {"N",
        "N, mN",
        {{"n", 1.0}, {"mn", 1e-3}, {"newton", 1.0}, {"newtons", 1.0}, {"millinewton", 1e-3}, {"millinewtons", 1e-3}}}},
      {Dimension::Time,
       {"days",
        "s, days, years",
        {{"s", 1.0 / DAY_S},
         {"seconds", 1.0 / DAY_S},
         {"day", 1.0},
         {"days", 1.0},
         {"d", 1.0},
         {"h", 1.0 / 24},
         {"hour", 1.0 / 24},
         {"hours", 1.0 / 24},
         {"sec", 1.0 / DAY_S},
         {"yr", JULIAN_YEAR_DAYS},
         {"year", JULIAN_YEAR_DAYS},
         {"years", JULIAN_YEAR_DAYS}}}},
      {Dimension::Duration,
       {"s", "s, days", {{"s", 1.0}, {"sec", 1.0}, {"seconds", 1.0}, {"day", DAY_S}, {"days", DAY_S}, {"d", DAY_S}}}},
      {Dimension::Mass,
       {"kg",
        "kg",
        {{"kg", 1.0},
         {"kilogram", 1.0},
         {"kilograms", 1.0},
         {"t", 1e3},
         {"tonne", 1e3},
         {"tonnes", 1e3},
         {"lb", 0.45359237},
         {"lbs", 0.45359237}}}},
      {Dimension::GravParam,
       {"km^3/s^2", "km^3/s^2, m^3/s^2", {{"km^3/s^2", 1.0}, {"m^3/s^2", 1e-9}, {"km3/s2", 1.0}, {"m3/s2", 1e-9}}}},
      {Dimension::Acceleration,
       {"mm/s^2", "mm/s^2, m/s^2, km/s^2", {{"mm/s^2", 1.0}, {"m/s^2", 1e3}, {"km/s^2", 1e6}}}},
      {Dimension::Angle,
       {"deg",
        "deg, rad",
        {{"deg", 1.0},
         {"degree", 1.0},
         {"degrees", 1.0},
         {"rad", 1.0 / DEG_TO_RAD},
         {"radian", 1.0 / DEG_TO_RAD},
         {"radians", 1.0 / DEG_TO_RAD}}}},
  };
  return tables.at(d);
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
  return table(d).spec_unit;
}

double to_spec_unit(Dimension d, const std::string& unit) {
  const Table& t = table(d);
  const auto it = t.factor.find(lowercase(unit));
  if (it == t.factor.end()) {
    const std::string name = dimension_name(d);
    const std::string article = std::string("aeiou").find(name[0]) == std::string::npos ? "a " : "an ";
    throw std::invalid_argument("unit '" + unit + "' is not " + article + name + " unit (use " + t.accepted + ")");
  }
  return it->second;
}

}  // namespace helios::spec

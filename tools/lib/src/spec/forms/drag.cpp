// "Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential
// atmosphere of density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km[, at rest |
// rotating at Q rad/s]." (also "The spacecraft feels atmospheric drag ...", "Include atmospheric drag
// ...") -> a drag perturbation. The atmosphere turns with the central body unless said to be at rest
// or given its own rate. "Neglect atmospheric drag." (or "Drag is negligible.") adds nothing.
#include <cmath>
#include <optional>
#include <regex>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const char* kExample =
    "e.g. 'Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential atmosphere "
    "of density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km.'";

// The number after the first of `labels` in `clause` with its unit (the unit's group may be empty).
std::optional<std::pair<double, std::string>> labelled(const std::string& clause, const std::string& labels,
                                                       const std::string& unit = "") {
  const std::regex pattern("(?:" + labels + R"()\s*(?:=|of|is)?\s*()" + kNum + R"()\s*()" + unit + ")",
                           std::regex::icase);
  std::smatch m;
  if (!std::regex_search(clause, m, pattern)) return std::nullopt;
  return std::make_pair(number(m[1].str()), lowercase(m[2].str()));
}

// A density in kg/m^3 or g/cm^3, an area in m^2 or cm^2, a rate in rad/s or deg/s, in the spec's units.
double density_kg_m3(const std::pair<double, std::string>& q) {
  return q.second == "g/cm^3" ? q.first * 1e3 : q.first;
}
double area_m2(const std::pair<double, std::string>& q) {
  return q.second == "cm^2" ? q.first * 1e-4 : q.first;
}
double rate_rad_s(const std::pair<double, std::string>& q) {
  return q.second == "deg/s" ? q.first * 3.14159265358979323846 / 180 : q.first;
}

void read(Builder& b, const std::smatch& m) {
  const std::string head = lowercase(m[1].str()), clause = m[2].str();
  static const std::regex negligible(R"(^(?:neglect|ignore)|^(?:there is )?no\b|^without\b)");
  static const std::regex negligible_after(R"(^\s*(?:is|are)\s+(?:neglected|ignored|negligible)\b)", std::regex::icase);
  if (std::regex_search(head, negligible) || std::regex_search(clause, negligible_after)) return;
  b.once("atmospheric drag");
  const auto cd = labelled(clause, R"(drag coefficient|\bC_?D\b)");
  const auto area = labelled(clause, R"((?:reference |cross[- ]sectional |frontal |drag )?area)", R"(m\^?2|cm\^?2)");
  const auto density = labelled(clause, R"(density)", R"(kg/m\^?3|g/cm\^?3)");
  const auto scale = labelled(clause, R"(scale height)", kUnit);
  std::smatch at;
  static const std::regex altitude(R"(\b(?:at|above)\s+(?:an?\s+)?(?:reference\s+)?(?:altitude|height)?\s*(?:of\s+)?)" +
                                       kQuantity + R"((?:\s+(?:altitude|height))?)",
                                   std::regex::icase);
  const bool has_altitude = std::regex_search(clause, at, altitude);
  std::vector<std::string> missing;
  if (!cd) missing.push_back("its drag coefficient");
  if (!area) missing.push_back("its area (m^2)");
  if (!density) missing.push_back("the density (kg/m^3)");
  if (!has_altitude) missing.push_back("the altitude of that density");
  if (!scale) missing.push_back("the scale height");
  if (!missing.empty()) {
    std::string list;
    for (std::size_t i = 0; i < missing.size(); ++i)
      list += (i == 0 ? "" : i + 1 == missing.size() ? " and " : ", ") + missing[i];
    throw sentence_error("atmospheric drag needs " + list + ", " + kExample);
  }
  std::smatch sm;
  const std::string scale_text = std::to_string(scale->first) + " " + scale->second;
  std::regex_match(scale_text, sm, re(kQuantity));
  json drag = {{"kind", "drag"},
               {"drag_coefficient", cd->first},
               {"area_m2", area_m2(*area)},
               {"density_kg_m3", density_kg_m3(*density)},
               {"reference_altitude_km", quantity(at, 1, Dimension::Length)},
               {"scale_height_km", quantity(sm, 1, Dimension::Length)}};
  if (!(cd->first > 0) || !(drag["area_m2"] > 0) || !(drag["density_kg_m3"] > 0) || !(drag["scale_height_km"] > 0) ||
      drag["reference_altitude_km"] < 0)
    throw sentence_error(
        "atmospheric drag: its coefficient, area, density and scale height must be positive and the "
        "altitude not negative");
  static const std::regex at_rest(R"(\b(?:at rest|non-?rotating|not rotating|does not rotate)\b)", std::regex::icase);
  if (std::regex_search(clause, at_rest))
    drag["atmosphere_rotation_rad_s"] = 0.0;
  else if (const auto rate = labelled(clause, R"(rotat(?:es|ing) at|rotation rate)", R"(rad/s|deg/s)"))
    drag["atmosphere_rotation_rad_s"] = rate_rad_s(*rate);
  b.perturbations.push_back(drag);
}

}  // namespace

std::vector<Form> drag() {
  return {
      {"atmospheric drag",
       65,
       R"((.*?\b(?:atmospheric |air |aerodynamic )?drag\b)(.*))",
       read,
       {{"Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential atmosphere "
         "of density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km.",
         "earth",
         R"~({"/dynamics/perturbations": [{"kind": "drag", "drag_coefficient": 2.2, "area_m2": 4,
                 "density_kg_m3": 3.6e-12, "reference_altitude_km": 400, "scale_height_km": 58}]})~"},
        {"The spacecraft feels atmospheric drag with Cd = 2 and a cross-sectional area of 20000 cm^2 in a "
         "non-rotating atmosphere of density 1e-11 kg/m^3 at an altitude of 300 km and a scale height of 50 km.",
         "earth",
         R"~({"/dynamics/perturbations": [{"kind": "drag", "drag_coefficient": 2, "area_m2": 2,
                 "density_kg_m3": 1e-11, "reference_altitude_km": 300, "scale_height_km": 50,
                 "atmosphere_rotation_rad_s": 0}]})~"},
        {"Neglect atmospheric drag.", "earth", R"~({"/dynamics/model": "two_body"})~"},
        {"Atmospheric drag acts on the spacecraft with a drag coefficient of 2.2 and an area of 4 m^2.", "earth",
         R"~({"error": "atmospheric drag needs the density (kg/m^3), the altitude of that density and the scale height"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

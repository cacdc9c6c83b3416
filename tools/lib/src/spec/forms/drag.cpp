// "Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential
// atmosphere of density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km[, at rest |
// rotating at Q rad/s]." (also "The spacecraft feels atmospheric drag ...", "Include atmospheric drag
// ...") -> a drag perturbation. The atmosphere turns with the central body unless said to be at rest
// or given its own rate. "Neglect atmospheric drag." (or "Drag is negligible.") adds nothing.
#include <optional>
#include <regex>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const char* kExample =
    "e.g. 'Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential atmosphere "
    "of density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km.'";

// The number (group 1) after the first of `labels` in `clause`, with its unit (group 2, may be
// empty); the match refers to `clause`.
std::optional<std::smatch> labelled(const std::string& clause, const std::string& labels,
                                    const std::string& unit = "") {
  const std::regex pattern("(?:" + labels + R"()\s*(?:=|of|is)?\s*()" + kNum + R"()\s*()" + unit + ")",
                           std::regex::icase);
  std::smatch m;
  if (!std::regex_search(clause, m, pattern)) return std::nullopt;
  return m;
}

// The number of a labelled match, scaled by `factor` where its unit begins with `prefix` (without case).
double scaled(const std::smatch& m, const std::string& prefix, double factor) {
  return number(m[1].str()) * (lowercase(m[2].str()).rfind(prefix, 0) == 0 ? factor : 1.0);
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
  // A density in kg/m^3 or g/cm^3, an area in m^2 or cm^2, in the spec's units.
  const double coefficient = number((*cd)[1].str());
  json drag = {{"kind", "drag"},
               {"drag_coefficient", coefficient},
               {"area_m2", scaled(*area, "cm", 1e-4)},
               {"density_kg_m3", scaled(*density, "g/", 1e3)},
               {"reference_altitude_km", quantity(at, 1, Dimension::Length)},
               {"scale_height_km", quantity(*scale, 1, Dimension::Length)}};
  if (!(coefficient > 0) || !(drag["area_m2"] > 0) || !(drag["density_kg_m3"] > 0) || !(drag["scale_height_km"] > 0) ||
      drag["reference_altitude_km"] < 0)
    throw sentence_error(
        "atmospheric drag: its coefficient, area, density and scale height must be positive and the "
        "altitude not negative");
  static const std::regex at_rest(R"(\b(?:at rest|non-?rotating|not rotating|does not rotate)\b)", std::regex::icase);
  if (std::regex_search(clause, at_rest))
    drag["atmosphere_rotation_rad_s"] = 0.0;
  else if (const auto rate = labelled(clause, R"(rotat(?:es|ing) at|rotation rate)", R"(rad/s|deg/s)"))
    drag["atmosphere_rotation_rad_s"] = scaled(*rate, "deg", 3.14159265358979323846 / 180);
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
        {"Atmospheric drag acts on the spacecraft: Cd = 2.2, an area of 35000 cm2, in an exponential atmosphere of "
         "density 2.5e-15 g/cm3 at 350 km altitude with scale height 56.123456789 km, rotating at 0.0042 deg/s.",
         "earth",
         R"~({"/dynamics/perturbations": [{"kind": "drag", "drag_coefficient": 2.2, "area_m2": 3.5,
             "density_kg_m3": 2.5e-12, "reference_altitude_km": 350, "scale_height_km": 56.123456789,
             "atmosphere_rotation_rad_s": 7.330382858376184e-05}]})~"},
        {"Neglect atmospheric drag.", "earth", R"~({"/dynamics/model": "two_body"})~"},
        {"Atmospheric drag acts on the spacecraft with a drag coefficient of 2.2 and an area of 4 m^2.", "earth",
         R"~({"error": "atmospheric drag needs the density (kg/m^3), the altitude of that density and the scale height"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

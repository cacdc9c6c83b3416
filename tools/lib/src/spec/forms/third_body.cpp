// "The Moon perturbs the spacecraft as a point mass of mu = 4902.8 km^3/s^2 on a circular orbit
// of radius 384400 km[, inclination Q][, node Q][, phase Q]." -> a third_body perturbation: a
// point mass on a circular orbit about the central body (the angles default to 0: the orbit in
// the reference plane, the body on its x axis at the time origin).
#include <optional>
#include <regex>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const char* kExample =
    "e.g. 'The Moon perturbs the spacecraft as a point mass of mu = 4902.8 km^3/s^2 on a circular orbit of radius "
    "384400 km, inclination 5.1 deg, node 0 deg, phase 0 deg.'";

// The quantity after the first of `labels` in `clause` (in the spec unit of d), if stated.
std::optional<double> labelled(const std::string& clause, const std::string& labels, Dimension d) {
  const std::regex pattern("(?:" + labels + R"()\s*(?:=|of|is)?\s*)" + kQuantity, std::regex::icase);
  std::smatch m;
  if (!std::regex_search(clause, m, pattern)) return std::nullopt;
  return quantity(m, 1, d);
}

void read(Builder& b, const std::smatch& m) {
  const std::string name = m[1].str(), clause = m[2].str();
  if (b.central_body.is_object() && b.central_body.contains("name") &&
      lowercase(b.central_body.at("name").get<std::string>()) == lowercase(name))
    throw sentence_error(name + " is the central body; a third body is another one, " + kExample);
  b.once("the third body " + name);
  const auto mu = labelled(clause, R"(\bmu3?|gravitational parameter)", Dimension::GravParam);
  const auto radius = labelled(clause, R"(orbit of radius|\bradius)", Dimension::Length);
  if (!mu || !radius) {
    const std::string mu_text = "its gravitational parameter mu", radius_text = "the radius of its circular orbit";
    throw sentence_error("the third body " + name + " needs " +
                         (!mu && !radius ? mu_text + " and " + radius_text
                          : !mu          ? mu_text
                                         : radius_text) +
                         ", " + kExample);
  }
  if (!(*mu > 0) || !(*radius > 0))
    throw sentence_error("the third body " + name + ": its mu and orbit radius must be positive");
  json body = {{"kind", "third_body"}, {"name", name}, {"mu_km3_s2", *mu}, {"orbit_radius_km", *radius}};
  const std::pair<const char*, const char*> angles[] = {{"inclination_deg", R"(\binclination)"},
                                                        {"raan_deg", R"((?:ascending )?\bnode|\bRAAN)"},
                                                        {"phase_deg", R"(\bphase|argument of latitude)"}};
  for (const auto& [key, labels] : angles)
    if (const auto v = labelled(clause, labels, Dimension::Angle)) body[key] = *v;
  b.perturbations.push_back(body);
  b.stated_radii.push_back({*radius, "the orbit of " + name, b.here});
}

}  // namespace

std::vector<Form> third_body() {
  return {{"a third body",
           60,
           R"((?:The )?([A-Z][A-Za-z0-9]*) perturbs the spacecraft\b(.*))",
           read,
           {{"The Moon perturbs the spacecraft as a point mass of mu = 4902.8 km^3/s^2 on a circular orbit of radius "
             "384400 km, inclination 5.1 deg.",
             "earth",
             R"~({"/dynamics/perturbations": [{"kind": "third_body", "name": "Moon", "mu_km3_s2": 4902.8,
                 "orbit_radius_km": 384400, "inclination_deg": 5.1}]})~"},
            {"The Moon perturbs the spacecraft as a point mass of mu = 4902.8 km^3/s^2 on a circular orbit of radius "
             "384400 m.",
             "earth", R"~({"error": "the orbit of Moon is 384.4 km from the centre of the Earth"})~"},
            {"The Moon perturbs the spacecraft as a point mass of mu = 4902.8 km^3/s^2.", "earth",
             R"~({"error": "the third body Moon needs the radius of its circular orbit"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

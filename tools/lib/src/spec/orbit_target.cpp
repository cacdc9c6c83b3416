// An endpoint that is an orbit, not a point: "At the final time the spacecraft is on the circular
// equatorial orbit of radius 42165 km", "The spacecraft transfers into geostationary orbit", "...
// an orbit with semi-major axis 24500 km, eccentricity 0.72 and inclination 7 deg". The elements
// named are met; the others and the position on the orbit stay free. A departure ("The spacecraft
// departs from the circular orbit of radius 7000 km inclined 28.5 deg with node 40 deg") names
// every element that fixes its orbit: only the position on it is free.
#include <algorithm>
#include <cmath>
#include <set>

#include "grammar.hpp"
#include "helios/astro/constants.hpp"
#include "helios/spec/state_conditions.hpp"

namespace helios::spec::grammar {
namespace {

// The forms an orbit is read in, for a phrase that cannot be placed.
const char* const kOrbitForms =
    "an orbit reads e.g. 'the circular equatorial orbit of radius 42165 km', 'geostationary orbit', 'a circular "
    "orbit of 7500 km radius inclined 28.5 deg' or 'an orbit with semi-major axis 24500 km, eccentricity 0.72, "
    "inclination 7 deg, node 30 deg and argument of periapsis 90 deg'";

// The Earth's sidereal day [s]: the period of a geostationary orbit.
constexpr double kSiderealDayS = 86164.0905;

// Removes every match of `pattern` from `text`, calling `take` with each.
template <typename Take>
void take_all(std::string& text, const std::regex& pattern, Take take) {
  std::smatch m;
  while (std::regex_search(text, m, pattern)) {
    take(m);
    text = m.prefix().str() + " " + m.suffix().str();
  }
}

// `pattern` as whole words, without case.
std::regex words(const std::string& pattern) {
  return std::regex(R"((?:^|\b)(?:)" + pattern + R"()(?=[^A-Za-z0-9_]|$))", std::regex::icase);
}

}  // namespace

json parse_orbit_target(const std::string& phrase) {
  json t = {{"kind", "orbital_elements"}};
  std::string rest = phrase;
  const auto set = [&](const char* key, double value, const std::string& written) {
    if (t.contains(key) && t[key].get<double>() != value)
      throw sentence_error("the orbit's " + std::string(key) + " is given twice ('" + written + "')");
    t[key] = value;
  };
  const auto length = [](const std::smatch& m, std::size_t i) { return quantity(m, i, Dimension::Length); };
  const auto angle = [](const std::smatch& m, std::size_t i) {
    return m[i + 1].str() == "°" ? number(m[i].str()) : quantity(m, i, Dimension::Angle);
  };
  const std::string q = kQuantity;
  const std::string deg = "(" + kNum + R"()\s*(deg|degrees?|°))";
  take_all(rest, words("geostationary|GEO"), [&](const std::smatch&) { t["geostationary"] = true; });
  take_all(rest, words("circular"), [&](const std::smatch& m) { set("eccentricity", 0, m.str()); });
  take_all(rest, words("equatorial"), [&](const std::smatch& m) { set("inclination_deg", 0, m.str()); });
  take_all(rest, words("polar"), [&](const std::smatch& m) { set("inclination_deg", 90, m.str()); });
  // The radius of a circular orbit makes it circular.
  const auto radius = [&](const std::smatch& m, std::size_t i) {
    set("semi_major_axis_km", length(m, i), m.str());
    set("eccentricity", 0, m.str());
  };
  take_all(rest, words("(?:of |with )?(?:a )?radius (?:of )?" + q), [&](const std::smatch& m) { radius(m, 1); });
  take_all(rest, words("(?:of )?" + q + " radius"), [&](const std::smatch& m) { radius(m, 1); });
  take_all(rest, words("(?:a )?semi-?major axis (?:of |= ?)?" + q),
           [&](const std::smatch& m) { set("semi_major_axis_km", length(m, 1), m.str()); });
  take_all(rest, words("(?:an )?eccentricity (?:of |= ?)?(" + kNum + ")"),
           [&](const std::smatch& m) { set("eccentricity", number(m[1].str()), m.str()); });
  take_all(rest, words("(?:an )?inclination (?:of |= ?)?" + deg + "|inclined (?:at |by )?" + deg),
           [&](const std::smatch& m) {
             const std::size_t i = m[1].matched ? 1 : 3;
             set("inclination_deg", angle(m, i), m.str());
           });
  take_all(rest,
           words("(?:a |an )?(?:right ascension of the ascending node|ascending node|RAAN|node) (?:of |= ?)?" + deg),
           [&](const std::smatch& m) { set("raan_deg", angle(m, 1), m.str()); });
  take_all(
      rest,
      words("(?:an )?(?:argument of (?:periapsis|perigee|pericenter|pericentre|perihelion)|argp) (?:of |= ?)?" + deg),
      [&](const std::smatch& m) { set("argp_deg", angle(m, 1), m.str()); });
  // What leaves the rest free, said in words: the node and the argument of periapsis are kept as
  // "free" (a departure orbit states them or says so; a target's unstated elements are free).
  const std::string node_words = "(?:right ascension of the ascending node|ascending node|RAAN|node)";
  const std::string argp_words = "(?:argument of (?:periapsis|perigee|pericenter|pericentre|perihelion)|argp)";
  std::set<std::string> free;
  take_all(rest, words("(?:with |at )?any " + node_words + "|(?:with )?(?:the )?" + node_words + " free"),
           [&](const std::smatch&) { free.insert("raan"); });
  take_all(rest, words("(?:with |at )?any " + argp_words + "|(?:with )?(?:the )?" + argp_words + " free"),
           [&](const std::smatch&) { free.insert("argp"); });
  take_all(rest, words("(?:with |at )?any (?:true |mean )?(?:anomaly|longitude|position(?: on it)?)"),
           [](const std::smatch&) {});
  take_all(rest, words("(?:with )?(?:the )?(?:true |mean )?(?:anomaly|longitude) free"), [](const std::smatch&) {});
  // What is left must be the words around the elements.
  static const std::regex filler = words("the|a|an|orbit|of|with|and|about|around|the central body|earth|,|;");
  std::string left = std::regex_replace(rest, filler, " ");
  left = trimmed(std::regex_replace(left, std::regex(R"([\s,;]+)"), " "));
  if (!left.empty()) throw sentence_error("cannot place '" + left + "' in the target orbit; " + kOrbitForms);
  if (t.size() == 1) throw sentence_error("the orbit names none of its elements; " + std::string(kOrbitForms));
  if (t.contains("raan_deg") && !t.contains("inclination_deg"))
    throw sentence_error("the orbit gives its node but not its inclination; " + std::string(kOrbitForms));
  if (t.contains("eccentricity") && !(t["eccentricity"].get<double>() < 1))
    throw sentence_error("the orbit's eccentricity must be below 1 (a closed orbit)");
  if (t.contains("argp_deg") && !(t.value("eccentricity", 0.0) > 0))
    throw sentence_error("the orbit gives an argument of periapsis but no eccentricity above 0; " +
                         std::string(kOrbitForms));
  if (free.count("raan") && t.contains("raan_deg"))
    throw sentence_error("the orbit gives its node and says it is free: say one");
  if (free.count("argp") && t.contains("argp_deg"))
    throw sentence_error("the orbit gives its argument of periapsis and says it is free: say one");
  json ordered = {{"kind", "orbital_elements"}};  // the elements in one order, however they were written
  for (const char* key :
       {"geostationary", "semi_major_axis_km", "eccentricity", "inclination_deg", "raan_deg", "argp_deg"})
    if (t.contains(key)) ordered[key] = t[key];
  if (!free.empty()) ordered["free"] = free;
  return ordered;
}

// "geostationary": circular and equatorial about the Earth, with the radius of a sidereal day's
// period, a = (mu T^2 / (4 pi^2))^(1/3).
json Builder::geostationary(json target, const Where& w) const {
  if (!target.contains("geostationary")) return target;
  target.erase("geostationary");
  if (lowercase(central_body.value("name", "")) != "earth")
    fail(w, "a geostationary orbit is about the Earth; about " + central_body.value("name", std::string("this body")) +
                " state the orbit's radius ('the circular equatorial orbit of radius Q km')");
  const double mu = central_body.at("mu_km3_s2").get<double>();
  const double a = std::cbrt(mu * kSiderealDayS * kSiderealDayS / (4 * M_PI * M_PI));
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"semi_major_axis_km", a}, {"eccentricity", 0.0}, {"inclination_deg", 0.0}})
    if (target.contains(key) && std::abs(target[key].get<double>() - value) > 1e-9 * std::max(1.0, value))
      fail(w, std::string("a geostationary orbit has its own ") + key + ": remove the one stated");
  target["semi_major_axis_km"] = a;
  target["eccentricity"] = 0.0;
  target["inclination_deg"] = 0.0;
  return target;
}

}  // namespace helios::spec::grammar

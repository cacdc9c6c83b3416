// An orbit given by some of its elements, in words: "the circular equatorial orbit of radius 42,165 km
// (any longitude)", "geostationary orbit", "a circular polar orbit at an altitude of 800 km", "an orbit
// with semi-major axis 24500 km, eccentricity 0.72 and inclination 7 deg". The elements named are met;
// the others and the position on the orbit stay free. What needs the central body (geostationary, an
// altitude, the body an orbit is about) is kept with the target until the whole text is read
// (Builder::resolve_orbit).
#include <algorithm>
#include <cmath>
#include <set>

#include "grammar.hpp"
#include "helios/astro/constants.hpp"
#include "helios/io/json_io.hpp"

namespace helios::spec::grammar {
namespace {

// The forms an orbit is read in, for a phrase that cannot be placed.
const char* const kOrbitForms =
    "an orbit reads e.g. 'the circular equatorial orbit of radius 42165 km', 'geostationary orbit', 'a circular "
    "orbit at an altitude of 800 km inclined 28.5 deg' or 'an orbit with semi-major axis 24500 km, eccentricity "
    "0.72, inclination 7 deg, node 30 deg and argument of periapsis 90 deg'";

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

const std::string kNodeWords = "(?:right ascension of the ascending node|ascending node|RAAN|node)";
const std::string kArgpWords = "(?:argument of (?:periapsis|perigee|pericenter|pericentre|perihelion)|argp)";

// An orbit phrase read element by element: each reader takes the words it knows out of `rest`.
struct OrbitPhrase {
  json t = {{"kind", "orbital_elements"}};
  std::set<std::string> free;
  std::string rest;

  void set(const char* key, double value, const std::string& written) {
    if (t.contains(key) && t[key].get<double>() != value)
      throw sentence_error("the orbit's " + std::string(key) + " is given twice ('" + trimmed(written) + "')");
    t[key] = value;
  }

  // "circular", "equatorial", "polar", "geostationary".
  void shape() {
    take_all(rest, words("geostationary|GEO"), [&](const std::smatch&) { t["geostationary"] = true; });
    take_all(rest, words("circular"), [&](const std::smatch& m) { set("eccentricity", 0, m.str()); });
    take_all(rest, words("equatorial"), [&](const std::smatch& m) { set("inclination_deg", 0, m.str()); });
    take_all(rest, words("polar"), [&](const std::smatch& m) { set("inclination_deg", 90, m.str()); });
  }

  // The radius or the altitude of a circular orbit (either makes it circular), the semi-major axis.
  void size() {
    const std::string q = kQuantity;
    const auto radius = [&](const std::smatch& m) {
      set("semi_major_axis_km", quantity(m, 1, Dimension::Length), m.str());
      set("eccentricity", 0, m.str());
      t["length_unit"] = m[2].str();
    };
    take_all(rest, words("(?:of |with )?(?:a )?radius (?:of )?" + q), radius);
    take_all(rest, words("(?:of )?" + q + " (?:in )?radius"), radius);
    // An altitude counts from the central body's surface: above its equatorial radius.
    const auto altitude = [&](const std::smatch& m) {
      const double h = quantity(m, 1, Dimension::Length);
      if (!(h > 0)) throw sentence_error("the orbit's altitude must be above the surface, got " + trimmed(m.str()));
      set("altitude_km", h, m.str());
      set("eccentricity", 0, m.str());
    };
    take_all(rest, words("(?:at |with )?(?:an )?altitude (?:of )?" + q), altitude);
    take_all(rest, words("(?:at |of )?(?:an? )?" + q + " (?:in )?altitude"), altitude);
    take_all(rest, words(q + R"( above (?:the )?(?:([A-Za-z][A-Za-z0-9_]*)(?:'s)? )?surface)"),
             [&](const std::smatch& m) {
               altitude(m);
               if (m[3].matched && lowercase(m[3].str()) != "central") t["about"] = m[3].str();
             });
    take_all(rest, words("(?:a )?semi-?major axis (?:of |= ?)?" + q), [&](const std::smatch& m) {
      set("semi_major_axis_km", quantity(m, 1, Dimension::Length), m.str());
      t["length_unit"] = m[2].str();
    });
  }

  void angles() {
    const std::string deg = "(" + kNum + R"()\s*(deg|degrees?|°))";
    const auto angle = [](const std::smatch& m, std::size_t i) {
      return m[i + 1].str() == "°" ? number(m[i].str()) : quantity(m, i, Dimension::Angle);
    };
    take_all(rest, words("(?:an )?eccentricity (?:of |= ?)?(" + kNum + ")"),
             [&](const std::smatch& m) { set("eccentricity", number(m[1].str()), m.str()); });
    take_all(rest, words("(?:an )?inclination (?:of |= ?)?" + deg + "|inclined (?:at |by )?" + deg),
             [&](const std::smatch& m) { set("inclination_deg", angle(m, m[1].matched ? 1 : 3), m.str()); });
    take_all(rest, words("(?:a |an )?" + kNodeWords + " (?:of |= ?)?" + deg),
             [&](const std::smatch& m) { set("raan_deg", angle(m, 1), m.str()); });
    take_all(rest, words("(?:an )?" + kArgpWords + " (?:of |= ?)?" + deg),
             [&](const std::smatch& m) { set("argp_deg", angle(m, 1), m.str()); });
  }

  // What leaves the rest free, said in words: the node and the argument of periapsis are kept as
  // "free" (a departure orbit states them or says so; a target's unstated elements are free), and
  // the position on the orbit, which is always free.
  void free_words() {
    take_all(rest, words("(?:with |at )?any " + kNodeWords + "|(?:with )?(?:the )?" + kNodeWords + " free"),
             [&](const std::smatch&) { free.insert("raan"); });
    take_all(rest, words("(?:with |at )?any " + kArgpWords + "|(?:with )?(?:the )?" + kArgpWords + " free"),
             [&](const std::smatch&) { free.insert("argp"); });
    const std::string position = "(?:true |mean )?(?:anomaly|longitude|position|point|place)";
    const std::string on_it = "(?: on (?:it|that orbit|this orbit|the orbit))?";
    for (const std::string& said : std::vector<std::string>{
             "(?:with |at )?any " + position + on_it, "(?:with )?(?:its |the )?" + position + on_it + " (?:is )?free",
             "where on (?:it|that orbit|this orbit|the orbit) (?:it arrives|it ends|the spacecraft arrives) is free",
             "anywhere (?:along|on) (?:it|that orbit|this orbit|the orbit)"})
      take_all(rest, words(said), [](const std::smatch&) {});
  }

  // The body an orbit is about ("about the Earth", "a Mars orbit"): kept to be checked against the
  // central body.
  void body() {
    take_all(rest, words("(?:about|around) (?:the )?(?!central body)([A-Za-z][A-Za-z0-9_]*)"),
             [&](const std::smatch& m) { about(m[1].str()); });
    take_all(rest, words("(Sun|Earth|Moon|Mars|Venus|Jupiter)(?:'s)?(?= orbit)"),
             [&](const std::smatch& m) { about(m[1].str()); });
  }

  void about(const std::string& name) {
    if (t.contains("about") && lowercase(t["about"].get<std::string>()) != lowercase(name))
      throw sentence_error("the orbit is about " + t["about"].get<std::string>() + " and " + name + ": which one?");
    t["about"] = name;
  }

  void check() const {
    // What is left must be the words around the elements.
    static const std::regex filler = words("the|a|an|orbit|of|with|and|about|around|the central body|,|;|\\(|\\)");
    const std::string left =
        trimmed(std::regex_replace(std::regex_replace(rest, filler, " "), std::regex(R"([\s,;()]+)"), " "));
    if (!left.empty()) throw sentence_error("cannot place '" + left + "' in the target orbit; " + kOrbitForms);
    if (t.size() == (t.contains("about") ? 2u : 1u))
      throw sentence_error("the orbit names none of its elements; " + std::string(kOrbitForms));
    if (t.contains("raan_deg") && !t.contains("inclination_deg"))
      throw sentence_error("the orbit gives its node but not its inclination; " + std::string(kOrbitForms));
    if (t.contains("eccentricity") && !(t["eccentricity"].get<double>() >= 0 && t["eccentricity"].get<double>() < 1))
      throw sentence_error("the orbit's eccentricity must be below 1 (a closed orbit) and not negative");
    if (t.contains("argp_deg") && !(t.value("eccentricity", 0.0) > 0))
      throw sentence_error("the orbit gives an argument of periapsis but no eccentricity above 0; " +
                           std::string(kOrbitForms));
    if (free.count("raan") && t.contains("raan_deg"))
      throw sentence_error("the orbit gives its node and says it is free: say one");
    if (free.count("argp") && t.contains("argp_deg"))
      throw sentence_error("the orbit gives its argument of periapsis and says it is free: say one");
  }
};

// "42,165" as "42165": thousands separators, which the quantities of an orbit may have.
std::string without_thousands(const std::string& text) {
  static const std::regex grouped(R"((^|[^\d.,])([1-9]\d{0,2}(?:,\d{3})+)(?![\d,]))");
  std::string out;
  auto from = text.cbegin();
  for (std::sregex_iterator it(text.begin(), text.end(), grouped), end; it != end; ++it) {
    const auto& m = *it;
    out.append(from, m[2].first);
    std::string digits = m[2].str();
    digits.erase(std::remove(digits.begin(), digits.end(), ','), digits.end());
    out += digits;
    from = m[2].second;
  }
  return out.append(from, text.cend());
}

// The elements in one order, however they were written.
json in_order(const json& t) {
  json ordered = {{"kind", "orbital_elements"}};
  for (const char* key : {"geostationary", "semi_major_axis_km", "altitude_km", "eccentricity", "inclination_deg",
                          "raan_deg", "argp_deg", "about", "free", "length_unit"})
    if (t.contains(key)) ordered[key] = t[key];
  return ordered;
}

}  // namespace

json parse_orbit_target(const std::string& phrase) {
  OrbitPhrase o;
  o.rest = without_thousands(phrase);
  o.shape();
  o.size();
  o.angles();
  o.free_words();
  o.body();
  o.check();
  if (!o.free.empty()) o.t["free"] = o.free;
  return in_order(o.t);
}

// The orbit's elements once the central body is known: "geostationary" (circular and equatorial about
// the Earth, the radius of a sidereal day's period, a = (mu T^2 / (4 pi^2))^(1/3)), an altitude above
// the central body's radius, and the body it is about, which must be the central one.
json Builder::resolve_orbit(json target, const Where& w) const {
  if (target.value("kind", "") != "orbital_elements") return target;
  const std::string central = central_body.value("name", std::string("the central body"));
  if (target.contains("about")) {
    const std::string about = target["about"];
    target.erase("about");
    if (lowercase(about) != lowercase(central))
      fail(w, "the orbit is about " + about + ", but the central body is " + central +
                  ": HELIOS reaches orbits about the central body (state that body as the central one, or the orbit "
                  "about " +
                  central + ")");
  }
  if (target.contains("altitude_km")) {
    if (!central_body.contains("radius_km"))
      fail(w, "an altitude counts from the surface of " + central +
                  ", whose radius is not known: state it ('The central body is ... with equatorial radius Q.') or "
                  "give the orbit's radius");
    const double altitude = target["altitude_km"].get<double>(), body_radius = central_body["radius_km"].get<double>();
    // A radius and an altitude both stated say one thing twice, or two things: never keep one silently.
    if (target.contains("semi_major_axis_km") && std::abs(target["semi_major_axis_km"].get<double>() -
                                                          (altitude + body_radius)) > 1e-9 * (altitude + body_radius))
      fail(w, "the orbit's radius " + io::short_number(target["semi_major_axis_km"].get<double>()) +
                  " km and its altitude " + io::short_number(altitude) + " km (a radius of " +
                  io::short_number(altitude + body_radius) + " km) disagree: state one of them");
    target["semi_major_axis_km"] = altitude + body_radius;
    target.erase("altitude_km");
  }
  if (!target.contains("geostationary")) return in_order(target);
  target.erase("geostationary");
  if (lowercase(central) != "earth")
    fail(w, "a geostationary orbit is about the Earth; about " + central +
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
  return in_order(target);
}

}  // namespace helios::spec::grammar

// The departure: "The spacecraft departs [at t = Q | at MJD N | at MJD2000 N] from TARGET." (or "...
// departs from TARGET at ..."), TARGET a state, a coasting target, a body's name or an orbit; and
// "At the initial time the spacecraft is on ORBIT." (also "The spacecraft starts on ORBIT.", "The
// initial orbit is ORBIT-WORDS."). A departure orbit names every element that fixes
// it (or says it is free): only the position on it is found by the minimum principle.
#include <algorithm>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

// "t = Q", "MJD N" or "MJD2000 N": the departure time or its calendar epoch.
void departure_time(Builder& b, const std::string& phrase) {
  std::smatch m;
  static const std::regex t_re = re(R"(t\s*=\s*)" + kQuantity);
  static const std::regex t0_re = re(R"(t\s*=\s*0)");  // the time 0 needs no unit
  static const std::regex mjd_re = re("(MJD2000|MJD) (" + kNum + ")");
  if (std::regex_match(phrase, m, t_re) || std::regex_match(phrase, t0_re)) {
    b.once(detail::Field::T0);
    b.time["t0_days"] = m.empty() ? 0.0 : quantity(m, 1, Dimension::Time);
    b.departure_at_t = true;
  } else if (std::regex_match(phrase, m, mjd_re)) {
    b.set_epoch(mjd2000_of(m[1].str(), m[2].str()));
  } else {
    throw sentence_error("departure time '" + phrase + "' must read 't = VALUE UNIT', 'MJD VALUE' or 'MJD2000 VALUE'");
  }
}

void from_orbit(Builder& b, const std::string& at, const std::string& orbit) {
  json target = parse_orbit_target(orbit);
  const auto need = [&](bool given, const std::string& what) {
    if (!given)
      throw sentence_error("a departure orbit needs its " + what +
                           ": only the position on it may be free (e.g. 'departs from the circular orbit of radius "
                           "7000 km inclined 28.5 deg with node 40 deg')");
  };
  if (!target.contains("geostationary")) {
    const double e = target.value("eccentricity", -1.0), i = target.value("inclination_deg", -1.0);
    need(target.contains("semi_major_axis_km") || target.contains("altitude_km"),
         "semi-major axis (or its radius or altitude, if circular)");
    need(e >= 0, "eccentricity (or the word 'circular')");
    need(i >= 0, "inclination (or the word 'equatorial')");
    const auto free = [&](const char* element) {
      const json list = target.value("free", json::array());
      return std::find(list.begin(), list.end(), element) != list.end();
    };
    need(i == 0 || i == 180 || target.contains("raan_deg") || free("raan"), "node (or 'with any node')");
    need(e == 0 || target.contains("argp_deg") || free("argp"),
         "argument of periapsis (or 'with any argument of perigee')");
  }
  b.once("the departure");
  if (!at.empty()) departure_time(b, at);
  b.departure = Endpoint{b.here, target, "initial_state", std::nullopt};
}

void depart(Builder& b, const std::string& at, const std::string& target_text) {
  static const std::regex orbit_word = re(R"(.*\borbit\b.*)");
  if (std::regex_match(target_text, orbit_word)) return from_orbit(b, at, target_text);
  json target;
  try {
    target = parse_target(target_text);
  } catch (const sentence_error& form) {
    // "departs from Earth on 2001-02-04": the facts in other words read what the form does not
    detail::SentenceFacts facts;
    try {
      facts = detail::read_facts(b.sentence, b.body_names());
    } catch (const detail::facts_error& e) {
      // a body named, then words the form does not take: the facts' reason is the one to give
      static const std::regex named_then_more = re(R"([A-Za-z][A-Za-z0-9_]* (?:on|at|in) .+)");
      if (std::regex_match(target_text, named_then_more)) throw sentence_error(e.what());
      throw form;
    }
    return b.apply_facts(facts);
  }
  b.once("the departure");
  if (!at.empty()) departure_time(b, at);
  b.departure = Endpoint{b.here, target, "initial_state", std::nullopt};
}

void on_orbit_at_t0(Builder& b, const std::smatch& m) {
  from_orbit(b, "", m[1].str());
}

void from_then_at(Builder& b, const std::smatch& m) {
  depart(b, m[2].str(), m[1].str());
}

void at_then_from(Builder& b, const std::smatch& m) {
  depart(b, m[1].matched ? m[1].str() : "", m[2].str());
}

}  // namespace

std::vector<Form> departure() {
  return {
      {"the departure orbit the spacecraft starts on",
       91,
       "(?:At the initial time,? )?the spacecraft (?:starts|starts out|begins|is initially|is parked|waits)"
       " (?:on|in|from) " +
           kOrbitPhrase,
       on_orbit_at_t0,
       {{"The spacecraft starts on a circular equatorial orbit of radius 7000 km.", "earth -departure",
         R"~({"/departure/target": {"kind": "orbital_elements", "semi_major_axis_km": 7000, "eccentricity": 0,
                 "inclination_deg": 0}})~"},
        {"The spacecraft is initially in a circular orbit at an altitude of 700 km inclined 51.6 deg with any node.",
         "earth -departure",
         R"~({"/departure/target": {"kind": "orbital_elements", "semi_major_axis_km": 7078.137, "eccentricity": 0,
                 "inclination_deg": 51.6, "free": ["raan"]}})~"},
        {"The spacecraft starts on a circular orbit of radius 3000 km.", "earth -departure",
         R"~({"error": "a departure orbit needs its inclination (or the word 'equatorial')"})~"}}},
      {"the departure orbit described",
       92,
       R"((?:The )?(?:initial|departure|starting|parking) orbit(?: is|\s*:)\s*(.+))",
       on_orbit_at_t0,
       {{"The initial orbit is circular and equatorial with radius 8000 km.", "earth -departure",
         R"~({"/departure/target": {"kind": "orbital_elements", "semi_major_axis_km": 8000, "eccentricity": 0,
                 "inclination_deg": 0}})~"},
        {"Parking orbit: circular, equatorial, at an altitude of 400 km.", "earth -departure",
         R"~({"/departure/target/semi_major_axis_km": 6778.137})~"}}},
      {"the departure on an orbit",
       90,
       R"(At the initial time the spacecraft is (?:on|in) (.+\borbit\b.*))",
       on_orbit_at_t0,
       {{"At the initial time the spacecraft is on the circular orbit of radius 7000 km inclined 28.5 deg with any "
         "node.",
         "earth -departure",
         R"~({"/departure/target": {"kind": "orbital_elements", "semi_major_axis_km": 7000, "eccentricity": 0,
                 "inclination_deg": 28.5, "free": ["raan"]}})~"},
        {"At the initial time the spacecraft is on the circular orbit of radius 7000 km inclined 28.5 deg.",
         "earth -departure", R"~({"error": "a departure orbit needs its node (or 'with any node')"})~"}}},
      {"the departure, its target first",
       100,
       R"(The spacecraft departs from (.+) at ((?:t\s*=|MJD2000 |MJD ).+))",
       from_then_at,
       {{"The spacecraft departs from Earth at MJD 51944.", "planets -departure",
         R"~({"/time/epoch_mjd2000": 400, "/departure/target": {"kind": "body", "body": "Earth",
                 "ephemeris": "jpl_lp"}})~"}}},
      {"the departure",
       110,
       R"(The spacecraft departs(?: at (.+?))? from (.+))",
       at_then_from,
       {{"The spacecraft departs at t = 0 days from position [-140699693, -51614428, 980] km with velocity "
         "[9.774596, -28.07828, 4.337725e-4] km/s.",
         "sun -departure",
         R"~({"/time/t0_days": 0, "/departure/target": {"kind": "fixed_state",
                 "position_km": [-140699693, -51614428, 980], "velocity_km_s": [9.774596, -28.07828, 4.337725e-4]}})~"},
        {"The spacecraft departs at t = 0 from position [-140699693, -51614428, 980] km with velocity [9.774596, "
         "-28.07828, 4.337725e-4] km/s.",
         "sun -departure", R"~({"/time/t0_days": 0})~"},
        {"The spacecraft departs at MJD2000 400 from Earth.", "planets -departure",
         R"~({"/time/epoch_mjd2000": 400, "/departure/target/body": "Earth"})~"},
        {"The spacecraft departs from Earth on 2001-02-04.", "planets -departure",
         R"~({"/time/epoch_mjd2000": 400, "/departure/target/body": "Earth"})~"},
        {"The spacecraft departs at noon from Earth.", "planets -departure",
         R"~({"error": "departure time 'noon' must read 't = VALUE UNIT', 'MJD VALUE' or 'MJD2000 VALUE'"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

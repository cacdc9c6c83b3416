// "At the final time the spacecraft is on ORBIT." (also "transfers into", "is inserted into",
// "arrives into"): the elements named are met at tf, the others and the position on the orbit free.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the final rendezvous");
  json target = parse_orbit_target(m[1].matched ? m[1].str() : m[2].str());
  target.erase("free");  // a target's unstated elements are free already
  b.arrival = Endpoint{b.here, target, "orbit_insertion", std::nullopt};
}

}  // namespace

std::vector<Form> final_orbit() {
  return {
      {"the final orbit",
       140,
       R"(At the final time the spacecraft is (?:on|in) (.+\borbit\b.*)|The spacecraft (?:transfers|is transferred|is inserted|must transfer|arrives) (?:in)?to (.+\borbit\b.*?)(?: at the final time)?)",
       read,
       {{"At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.", "earth -arrival",
         R"~({"/arrival": {"id": "arrival", "kind": "orbit_insertion", "at": "tf", "target": {
                 "kind": "orbital_elements", "semi_major_axis_km": 42165, "eccentricity": 0, "inclination_deg": 0}}})~"},
        {"The spacecraft transfers into geostationary orbit.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 42164.169624086106,
                 "eccentricity": 0, "inclination_deg": 0}})~"},
        {"The spacecraft is inserted into an orbit with semi-major axis 24500 km, eccentricity 0.72, inclination 7 "
         "deg, node 30 deg and argument of perigee 90 deg.",
         "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 24500, "eccentricity": 0.72,
                 "inclination_deg": 7, "raan_deg": 30, "argp_deg": 90}})~"},
        {"At the final time the spacecraft is on the orbit of my dreams.", "earth -arrival",
         R"~({"error": "cannot place 'my dreams' in the target orbit"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

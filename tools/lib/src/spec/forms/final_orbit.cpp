// The final orbit: "At the final time the spacecraft is on ORBIT." (also "transfers into", "is
// inserted into", "arrives into"), "The spacecraft must end on ORBIT." (also "ends in", "finishes in",
// "reaches", "arrives on", "ends up on"), "The final orbit is circular and equatorial with radius Q."
// (also "target orbit", "Final orbit: ..."), "At arrival the orbit must be ...". The elements named are
// met at tf, the others and the position on the orbit free.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void arrive_on(Builder& b, const std::string& orbit) {
  b.once("the final rendezvous");
  json target = parse_orbit_target(orbit);
  target.erase("free");  // a target's unstated elements are free already
  b.arrival = Endpoint{b.here, target, "orbit_insertion", std::nullopt};
}

void read(Builder& b, const std::smatch& m) {
  arrive_on(b, m[1].matched ? m[1].str() : m[2].str());
}

// Without "at the final time" and without a window, an orbit the spacecraft reaches is the last: a
// second final condition then says why it was read so.
void read_windowless(Builder& b, const std::smatch& m) {
  arrive_on(b, m[1].str());
  b.windowless_rendezvous = b.here;
}

void read_described(Builder& b, const std::smatch& m) {
  arrive_on(b, m[1].str());
}

}  // namespace

std::vector<Form> final_orbit() {
  return {
      {"the final orbit",
       140,
       R"(At the final time the spacecraft is (?:on|in) (.+\borbit\b.*)|The spacecraft (?:transfers|is transferred|is inserted|must transfer|arrives) (?:in)?to (.+\borbit\b.*?)(?: at the final time)?)",
       read,
       {{"At the final time the spacecraft is on the circular equatorial orbit of radius 42,165 km (any longitude).",
         "earth -arrival",
         R"~({"/arrival": {"id": "arrival", "kind": "orbit_insertion", "at": "tf", "target": {
             "kind": "orbital_elements", "semi_major_axis_km": 42165, "eccentricity": 0, "inclination_deg": 0}}})~"},
        {"At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km; where on that orbit "
         "it arrives is free.",
         "earth -arrival", R"~({"/arrival/target/semi_major_axis_km": 42165})~"},
        {"The spacecraft transfers into geostationary orbit.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 42164.169624086106,
             "eccentricity": 0, "inclination_deg": 0}})~"},
        {"The spacecraft is inserted into an orbit with semi-major axis 24500 km, eccentricity 0.72, inclination 7 "
         "deg, node 30 deg and argument of perigee 90 deg.",
         "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 24500, "eccentricity": 0.72,
             "inclination_deg": 7, "raan_deg": 30, "argp_deg": 90}})~"},
        {"At the final time the spacecraft is on the orbit of my dreams.", "earth -arrival",
         R"~({"error": "cannot place 'my dreams' in the target orbit"})~"}}},
      {"the final orbit the spacecraft ends on",
       141,
       "(?:At the final time,? )?the spacecraft (?:must |should |has to |is to |will )?(?:end|ends|finish|finishes|"
       "arrive|arrives|reach|reaches|be|get|gets)(?: up)? (?:on|in|into|at )?" +
           kOrbitPhrase,
       read_windowless,
       {{"The spacecraft must end on a circular equatorial orbit with a radius of 42165 km.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 42165, "eccentricity": 0,
             "inclination_deg": 0}})~"},
        {"The spacecraft ends in a circular polar orbit at an altitude of 800 km.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 7178.137, "eccentricity": 0,
             "inclination_deg": 90}})~"},
        {"The spacecraft must reach the circular orbit of radius 42164 km about the Moon.", "earth -arrival",
         R"~({"error": "the orbit is about Moon, but the central body is Earth"})~"}}},
      {"the final orbit described",
       142,
       R"((?:The )?(?:final|target|arrival|destination|terminal) orbit(?: is| must be| has|\s*:)\s*(.+)|At (?:the )?(?:arrival|end(?: of the (?:transfer|flight|mission))?),? the (?:spacecraft|orbit) (?:must be|is|should be) (?:on |in )?(.+))",
       read,
       {{"The final orbit is circular and equatorial with radius 42165 km.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 42165, "eccentricity": 0,
             "inclination_deg": 0}})~"},
        {"The target orbit is geostationary.", "earth -arrival",
         R"~({"/arrival/target/semi_major_axis_km": 42164.169624086106})~"},
        {"At arrival the orbit must be circular with a radius of 10000 km (any true anomaly).", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 10000, "eccentricity": 0}})~"}}},
      {"the final orbit the transfer ends on",
       143,
       "The (?:transfer|trajectory|flight|mission) (?:ends|must end|finishes|must finish) (?:on|in) " + kOrbitPhrase,
       read_described,
       {{"The transfer ends on an equatorial circular orbit 35,786 km above the Earth's surface.", "earth -arrival",
         R"~({"/arrival/target": {"kind": "orbital_elements", "semi_major_axis_km": 42164.137, "eccentricity": 0,
             "inclination_deg": 0}})~"}}}};
}

}  // namespace helios::spec::grammar::forms

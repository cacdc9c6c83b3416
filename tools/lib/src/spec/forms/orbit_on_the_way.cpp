// "The spacecraft passes through ORBIT between day N and day N." (or "Between day N and day N the
// spacecraft reaches ..."): an orbit on the way, met at a free epoch inside the window anywhere along
// it; the state goes on unchanged.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  const bool before = m[1].matched, after = m[6].matched;
  if (before == after)
    throw sentence_error(before ? "the sentence gives two windows"
                                : "an orbit on the way needs its window ('... between day N and day N'); an orbit "
                                  "that ends the flight reads 'At the final time the spacecraft is on ...'");
  const std::size_t w = before ? 1 : 6;
  Event e;
  e.where = b.here;
  e.kind = "orbit_insertion";
  e.target = parse_orbit_target(m[5].str());
  e.target.erase("free");  // a target's unstated elements are free already
  e.lo = Builder::epoch_ref(m[w].str(), m[w + 1].str());
  e.hi = Builder::epoch_ref(m[w + 2].str(), m[w + 3].str());
  b.events.push_back(e);
}

}  // namespace

std::vector<Form> orbit_on_the_way() {
  const std::string bound = R"((day|MJD2000|MJD) ()" + kNum + ")";
  return {
      {"an orbit on the way",
       150,
       "(?:Between " + bound + " and " + bound +
           R"(,? )?the spacecraft (?:passes through|crosses|reaches|is (?:on|in)|must (?:pass through|cross|reach|be (?:on|in))) (.+\borbit\b.*?)(?: between )" +
           bound + " and " + bound + ")?",
       read,
       {{"The spacecraft passes through the circular orbit of radius 30000 km between day 0.2 and day 1.", "earth",
         R"~({"/constraints/1": {"id": "orbit", "kind": "orbit_insertion", "at": "interior", "target": {
                 "kind": "orbital_elements", "semi_major_axis_km": 30000, "eccentricity": 0},
                 "window_days": [0.2, 1]}})~"},
        {"Between day 0.2 and day 1, the spacecraft reaches the circular orbit of radius 30000 km.", "earth",
         R"~({"/constraints/1/window_days": [0.2, 1]})~"},
        {"The spacecraft crosses the circular orbit of radius 30000 km.", "earth",
         R"~({"error": "an orbit on the way needs its window"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

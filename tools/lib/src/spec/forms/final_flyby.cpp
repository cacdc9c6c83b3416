// "At the final time the spacecraft flies by TARGET[ with a relative speed of at most Q].": the
// position alone meets the target's at tf, the speed relative to it optionally bounded.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the final rendezvous");
  b.arrival = Endpoint{b.here, parse_target(m[1].str()), "flyby", std::nullopt};
  if (m[2].matched) {
    const double v = quantity(m, 2, Dimension::Speed);
    if (!(v > 0)) throw sentence_error("the relative speed bound must be positive");
    b.arrival->max_speed = v;
  }
}

}  // namespace

std::vector<Form> final_flyby() {
  return {
      {"the final flyby",
       160,
       R"(At the final time the spacecraft (?:flies|must fly) by (.+?)(?:,? with a relative speed of at most )" +
           kQuantity + ")?",
       read,
       {{"At the final time the spacecraft flies by Mars with a relative speed of at most 500 m/s.", "planets -arrival",
         R"~({"/arrival": {"id": "arrival", "kind": "flyby", "at": "tf", "target": {"kind": "body", "body": "Mars",
                 "ephemeris": "jpl_lp"}, "max_relative_speed_km_s": 0.5}})~"},
        {"At the final time the spacecraft flies by Mars with a relative speed of at most 0 km/s.", "planets -arrival",
         R"~({"error": "the relative speed bound must be positive"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

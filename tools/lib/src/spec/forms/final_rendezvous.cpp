// "At the final time the spacecraft rendezvouses with TARGET." (or "The spacecraft must rendezvous with
// TARGET at the final time."): position and velocity meet the target's at tf.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the final rendezvous");
  const std::string phrase = m[1].matched ? m[1].str() : m[2].str();
  b.arrival = Endpoint{b.here, parse_target(phrase), "rendezvous", std::nullopt};
}

}  // namespace

std::vector<Form> final_rendezvous() {
  return {
      {"the final rendezvous",
       130,
       R"(At the final time the spacecraft (?:rendezvouses|must rendezvous) with (.+)|The spacecraft (?:rendezvouses|must rendezvous) with (.+) at the final time)",
       read,
       {{"At the final time the spacecraft rendezvouses with a coasting target starting from position [7000, 0, 0] km "
         "with velocity [0, 7.546, 0] km/s.",
         "earth -arrival",
         R"~({"/arrival": {"id": "arrival", "kind": "rendezvous", "at": "tf", "target": {"kind": "coasting",
                 "position_km": [7000, 0, 0], "velocity_km_s": [0, 7.546, 0]}}})~"},
        {"The spacecraft must rendezvous with Mars at the final time.", "planets -arrival",
         R"~({"/arrival/target": {"kind": "body", "body": "Mars", "ephemeris": "jpl_lp"}})~"},
        {"At the final time the spacecraft rendezvouses with Pluto.", "planets -arrival",
         R"~({"error": "unknown body 'Pluto'"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

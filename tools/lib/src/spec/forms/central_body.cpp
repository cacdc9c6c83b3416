// "The central body is the Sun [with gravitational parameter Q, equatorial radius Q and J2
// coefficient N]": the body the spacecraft moves about, and its constants.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the central body");
  b.central(m[1].str(), m[2].matched ? m[2].str() : "");
}

}  // namespace

std::vector<Form> central_body() {
  return {{"the central body",
           20,
           R"(The central body is (?:the )?([A-Za-z]+)(?: with (.+))?)",
           read,
           {{"The central body is the Earth with gravitational parameter 398600.4418 km^3/s^2, equatorial radius "
             "6378.137 km and J2 coefficient 1.08262668e-3.",
             "earth -central",
             R"~({"/central_body": {"name": "Earth", "mu_km3_s2": 398600.4418, "radius_km": 6378.137,
                 "j2": 1.08262668e-3}})~"},
            {"The central body is Mars.", "sun -central",
             R"~({"/central_body": {"name": "Mars", "mu_km3_s2": 42828.3, "radius_km": 3389.9}})~"},
            {"The central body is Vulcan.", "sun -central",
             R"~({"error": "no gravitational parameter known for 'Vulcan'"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

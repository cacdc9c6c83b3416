// "The central body is the Sun [with gravitational parameter Q, equatorial radius Q and J2
// coefficient N]" (or the constants in parentheses: "the Earth (mu = Q, R = Q, J2 = N)"): the body the
// spacecraft moves about, and its constants. A body called "scaled" (normalized, fictitious,
// hypothetical) takes the text's constants on purpose: none is known or checked.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the central body");
  b.central_on_purpose = m[1].matched;
  b.central(m[2].str(), m[3].matched ? m[3].str() : m[4].matched ? m[4].str() : "");
}

}  // namespace

std::vector<Form> central_body() {
  return {
      {"the central body",
       20,
       R"(The central body is (?:the |an? )?(?:(scaled|normalized|normalised|fictitious|hypothetical) )?([A-Za-z]+)(?:\s*\((.+)\)|,? with (.+))?)",
       read,
       {{"The central body is the Earth with gravitational parameter 398600.4418 km^3/s^2, equatorial radius "
         "6378.137 km and J2 coefficient 1.08262668e-3.",
         "earth -central",
         R"~({"/central_body": {"name": "Earth", "mu_km3_s2": 398600.4418, "radius_km": 6378.137,
                 "j2": 1.08262668e-3}})~"},
        {"The central body is Mars.", "sun -central",
         R"~({"/central_body": {"name": "Mars", "mu_km3_s2": 42828.3, "radius_km": 3389.9}})~"},
        {"The central body is the Earth (mu = 398600.4418 km^3/s^2, R = 6378.137 km, J2 = 1.0826e-3).",
         "earth -central",
         R"~({"/central_body": {"name": "Earth", "mu_km3_s2": 398600.4418, "radius_km": 6378.137,
                 "j2": 1.0826e-3}})~"},
        {"The central body is a scaled Earth with gravitational parameter 1 km^3/s^2 and equatorial radius 1 km.",
         "earth -central -departure -arrival +scaled_orbits",
         R"~({"/central_body": {"name": "Earth", "mu_km3_s2": 1, "radius_km": 1}})~"},
        {"The central body is the Earth with gravitational parameter 398600.4418 m^3/s^2.", "earth -central",
         R"~({"error": "the gravitational parameter of the Earth is known: 398600.4418 km^3/s^2"})~"},
        {"The central body is Vulcan.", "sun -central",
         R"~({"error": "no gravitational parameter known for 'Vulcan'"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

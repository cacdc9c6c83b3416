// "The spacecraft is an ideal flat solar sail with a characteristic acceleration of Q at Q.": a sail,
// no engine and no mass.
#include "../form.hpp"
#include "../grammar.hpp"
#include "helios/astro/constants.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.sail(quantity(m, 1, Dimension::Acceleration), quantity(m, 3, Dimension::Length) / helios::astro::AU_KM);
}

}  // namespace

std::vector<Form> solar_sail() {
  return {{"a solar sail",
           30,
           R"(The spacecraft is an ideal (?:flat )?solar sail with (?:a )?characteristic acceleration (?:of )?)" +
               kQuantity + " at " + kQuantity,
           read,
           {{"The spacecraft is an ideal flat solar sail with a characteristic acceleration of 1.0 mm/s^2 at 1 AU.",
             "planets -engine -tof -objective +min_time",
             R"~({"/dynamics/propulsion": "solar_sail", "/spacecraft": {"sail_characteristic_acceleration_mm_s2": 1,
                 "sail_reference_distance_AU": 1}})~"}}}};
}

}  // namespace helios::spec::grammar::forms

// "The engine thrusts at full throttle throughout.": the throttle is 1 for the whole flight, the
// thrust direction the only control.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch&) {
  b.once("the engine's throttle");
  b.spacecraft["full_throttle"] = true;
}

}  // namespace

std::vector<Form> full_throttle() {
  return {
      {"an engine at full throttle",
       220,
       R"(The (?:engine|thruster) (?:thrusts|runs|burns|fires) at full (?:throttle|thrust) (?:throughout|all the time|at all times|from start to end))",
       read,
       {{"The engine runs at full thrust all the time.", "earth", R"~({"/spacecraft/full_throttle": true})~"}}}};
}

}  // namespace helios::spec::grammar::forms

// "The dynamics include the J2 perturbation of the central body.": the zonal acceleration of its
// oblateness (the body's J2 coefficient and radius are stated with it).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch&) {
  b.once("the J2 perturbation");
  b.perturbations.push_back({{"kind", "j2"}});
}

}  // namespace

std::vector<Form> j2_dynamics() {
  return {{"the J2 perturbation",
           40,
           R"(The dynamics include the J2 (?:perturbation|term) of the central body)",
           read,
           {{"The dynamics include the J2 perturbation of the central body.", "earth -central +earth_j2",
             R"~({"/dynamics/perturbations": [{"kind": "j2"}]})~"},
            {"The dynamics include the J2 perturbation of the central body.", "earth",
             R"~({"error": "the J2 perturbation needs the central body's J2 coefficient and radius"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

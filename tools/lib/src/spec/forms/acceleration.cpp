// "The dynamics include a perturbing acceleration NAME of [AX, AY, AZ] UNIT.": a user-written
// acceleration, its components expressions of the state, refused here if they use anything but the
// documented variables, so the deriver never meets an unknown symbol.
#include "../form.hpp"
#include "../grammar.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::spec::grammar::forms {
namespace {

json user_acceleration(const std::string& name, const std::string& list, const std::string& unit) {
  const std::vector<std::string> items = top_level_items(list);
  if (items.size() != 3)
    throw sentence_error("the acceleration " + name + " needs three components [ax, ay, az], got " +
                         std::to_string(items.size()));
  // The components are expressions, so their unit is kept as written: one of the spec's.
  if (unit != "mm/s^2" && unit != "m/s^2" && unit != "km/s^2")
    throw sentence_error("the acceleration " + name + " is written in '" + unit +
                         "'; its components are expressions, so their unit must be mm/s^2, m/s^2 or km/s^2");
  symbolic::SymbolTable vars;
  for (const char* v : kAccelerationVariables) vars.get(v);
  for (const auto& item : items) {
    try {
      vars.parse(item, "component");
    } catch (const std::invalid_argument& e) {
      throw sentence_error(std::string(e.what()) +
                           " (variables: x, y, z, r [km], vx, vy, vz [km/s], m [kg], t [s since departure])");
    }
  }
  return {{"kind", "acceleration"}, {"name", name}, {"components", items}, {"unit", unit}};
}

void read(Builder& b, const std::smatch& m) {
  b.once("the acceleration " + m[1].str());
  b.perturbations.push_back(user_acceleration(m[1].str(), m[2].str(), m[3].str()));
}

}  // namespace

std::vector<Form> acceleration() {
  return {
      {"a perturbing acceleration",
       50,
       R"(The dynamics include (?:a|an) (?:perturbing|additional) acceleration ([A-Za-z][A-Za-z0-9_]*) of \[(.+)\]\s*()" +
           kUnit + ")",
       read,
       {{"The dynamics include a perturbing acceleration push of [1e-3*x/r, 1e-3*y/r, 0] mm/s^2.", "sun",
         R"~({"/dynamics/perturbations": [{"kind": "acceleration", "name": "push",
                 "components": ["1e-3*x/r", "1e-3*y/r", "0"], "unit": "mm/s^2"}]})~"},
        {"The dynamics include a perturbing acceleration push of [q, 0, 0] mm/s^2.", "sun",
         R"~({"error": "variables: x, y, z, r [km], vx, vy, vz [km/s], m [kg], t [s since departure]"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

// "The spacecraft's mass is constant at Q." and "Neglect the propellant mass.": an engine whose mass
// does not change (an acceleration-bounded spacecraft, as the classical orbit-transfer literature
// states it): the derivation has no mass state, a specific impulse is optional (with one the
// minimum fuel is the propellant in kg, without one the delta-v in m/s).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void mark_constant(Builder& b) {
  b.once("the spacecraft's mass model");
  b.spacecraft["mass_model"] = "constant";
}

// "The spacecraft's mass is constant at 1500 kg.": the mass model and the mass (the initial mass,
// which is the mass throughout); "The spacecraft's mass is constant.": the mass model alone.
void read_constant(Builder& b, const std::smatch& m) {
  mark_constant(b);
  if (!m[1].matched) return;
  const detail::Field field = detail::Field::InitialMass;
  b.once(field);
  ++b.seen["the spacecraft's engine"];
  const double value = quantity(m, 1, Dimension::Mass);
  b.check_value(field, value, m[1].str() + " " + m[2].str());
  b.spacecraft[detail::spec_key(field)] = value;
}

void read_neglect(Builder& b, const std::smatch&) {
  mark_constant(b);
}

}  // namespace

std::vector<Form> constant_mass() {
  return {
      {"a constant mass",
       81,
       R"((?:The spacecraft's mass|The mass of the spacecraft|Its mass) (?:is|stays|remains) constant(?:,? at )" +
           kQuantity + ")?",
       read_constant,
       {{"The spacecraft's mass is constant at 2000 kg.", "earth", R"~({"error": "the initial mass is given twice"})~"},
        {"The spacecraft's mass is constant at 2000 kg.\nThe spacecraft has a maximum thrust of 60 N.", "earth -engine",
         R"~({"/spacecraft": {"thrust_N": 60, "initial_mass_kg": 2000, "mass_model": "constant"}})~"},
        {"The mass of the spacecraft remains constant at 1.5 t.\nThe spacecraft has a maximum thrust of 60 N and a "
         "specific impulse of 2000 s.",
         "earth -engine",
         R"~({"/spacecraft": {"thrust_N": 60, "isp_s": 2000, "initial_mass_kg": 1500, "mass_model": "constant"}})~"},
        {"The spacecraft's mass is constant.", "earth", R"~({"/spacecraft/mass_model": "constant"})~"},
        {"The spacecraft's mass is constant.", "earth -engine +final_mass",
         R"~({"error": "a constant mass has no final mass of its own"})~"},
        {"The spacecraft's mass is constant at -5 kg.", "earth -engine",
         R"~({"error": "the initial mass must be positive"})~"}}},
      {"a negligible propellant mass",
       82,
       R"((?:(?:Neglect|Ignore) the (?:propellant mass|mass of the propellant|propellant's mass|mass variation|)"
       R"(mass flow)|The (?:propellant mass|mass of the propellant|mass flow) is negligible))",
       read_neglect,
       {{"Neglect the propellant mass.", "earth", R"~({"/spacecraft/mass_model": "constant"})~"},
        {"The propellant mass is negligible.", "earth", R"~({"/spacecraft/mass_model": "constant"})~"},
        {"Neglect the propellant mass.\nThe spacecraft's mass is constant.", "earth",
         R"~({"error": "the spacecraft's mass model is given twice"})~"},
        {"Neglect the propellant mass.", "planets -engine -tof -objective +min_time +sail",
         R"~({"error": "a solar sail has no engine and no mass"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

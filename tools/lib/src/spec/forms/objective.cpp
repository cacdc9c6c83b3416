// The objective: "Minimize the fuel consumption.", "Minimize the time of flight.", "Minimize the
// initial mass." (for the final mass stated), "Maximize the final radius." / "... the final orbital
// energy." (a Mayer term at a fixed time of flight).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void set(Builder& b, const char* kind) {
  b.once("the objective");
  b.objective = {{"kind", kind}};
  b.objective_where = b.here;
}

void initial_mass(Builder& b, const std::smatch&) {
  set(b, "minimum_initial_mass");
}

void fuel(Builder& b, const std::smatch&) {
  set(b, "minimum_fuel");
}

void time(Builder& b, const std::smatch&) {
  set(b, "minimum_time");
}

void final_state(Builder& b, const std::smatch& m) {
  set(b, lowercase(m[1].str()) == "radius" ? "maximum_final_radius" : "maximum_final_energy");
}

}  // namespace

std::vector<Form> objective() {
  return {{"the minimum initial mass",
           180,
           R"(Minimi[sz]e (?:the )?(?:initial|launch|departure|wet) mass)",
           initial_mass,
           {{"Minimize the initial mass.", "sun -objective -engine +final_mass",
             R"~({"/objective/kind": "minimum_initial_mass", "/spacecraft/final_mass_kg": 800})~"},
            {"Minimize the launch mass.", "sun -objective",
             R"~({"error": "never states the spacecraft's final_mass_kg"})~"}}},
          {"the minimum fuel",
           190,
           R"(Minimi[sz]e (?:the )?(?:fuel(?: consumption)?|propellant(?: mass)?|fuel use))",
           fuel,
           {{"Minimise the propellant mass.", "sun -objective", R"~({"/objective": {"kind": "minimum_fuel"}})~"}}},
          {"the minimum time",
           200,
           R"(Minimi[sz]e (?:the )?(?:time of flight|flight time|final time|transfer time))",
           time,
           {{"Minimize the flight time.", "earth -objective", R"~({"/objective": {"kind": "minimum_time"}})~"}}},
          {"the maximum final radius or energy",
           210,
           R"(Maximi[sz]e (?:the )?final (?:orbital |orbit )?(radius|energy)(?: of the orbit)?)",
           final_state,
           {{"Maximize the final radius.", "earth -objective -tof -arrival +free_end",
             R"~({"/objective/kind": "maximum_final_radius"})~"},
            {"Maximise the final orbital energy.", "earth -objective -tof -arrival +free_end",
             R"~({"/objective/kind": "maximum_final_energy"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

// "It leaves a lander of Q at NAME.": the mass left at the one rendezvous with NAME stated before.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

// "It leaves a lander of Q at NAME": the one rendezvous with NAME stated before.
void leave(Builder& b, double kg, const std::string& name) {
  if (!(kg > 0)) throw sentence_error("the lander's mass must be positive");
  Event* found = &b.rendezvous_of(name);
  if (found->drop) throw sentence_error("the lander at " + name + " is given twice");
  found->drop = kg;
  found->drop_where = b.here;
}

void read(Builder& b, const std::smatch& m) {
  leave(b, quantity(m, 1, Dimension::Mass), body_name(m[3].str()));
}

}  // namespace

std::vector<Form> lander() {
  return {
      {"a lander",
       280,
       R"((?:It|The spacecraft) (?:leaves|drops|releases) (?:a|an) (?:lander|probe|payload|package) of )" + kQuantity +
           " at (.+)",
       read,
       {{"It leaves a lander of 50 kg at Nikko.", "planets +nikko +visit", R"~({"/constraints/1/mass_drop_kg": 50})~"},
        {"It leaves a lander of 50 kg at Mars.", "planets +nikko +visit",
         R"~({"error": "no rendezvous with Mars is stated before this sentence"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

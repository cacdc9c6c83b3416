// "Problem S01: Earth to Mars.": the problem's id and title.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.once("the problem name");
  b.problem = {{"id", m[1].str()}, {"title", m[2].str()}};
}

}  // namespace

std::vector<Form> problem() {
  return {{"the problem's name",
           10,
           R"(Problem ([A-Za-z0-9_-]+)\s*:\s*(.+))",
           read,
           {{"Problem X7: a name of one's own.", "sun -name",
             R"~({"/problem/id": "X7", "/problem/title": "a name of one's own"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

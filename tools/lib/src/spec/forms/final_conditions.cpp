// "At the final time r·v = 0 and |r| = 42165 km.": equations of the final state (state_conditions.hpp),
// split at the commas, semicolons and "and"s outside parentheses; more sentences of this form add to
// the same constraint.
#include "../form.hpp"
#include "../grammar.hpp"
#include "helios/spec/state_conditions.hpp"

namespace helios::spec::grammar::forms {
namespace {

std::vector<std::string> equations_of(const std::string& list) {
  std::vector<std::string> items;
  std::string current;
  int depth = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const char c = list[i];
    depth += c == '(' ? 1 : c == ')' ? -1 : 0;
    const bool comma = depth == 0 && (c == ',' || c == ';');
    const bool word_and = depth == 0 && list.compare(i, 5, " and ") == 0;
    if (comma || word_and) {
      items.push_back(trimmed(current));
      current.clear();
      i += word_and ? 4 : 0;
      continue;
    }
    current += c;
  }
  items.push_back(trimmed(current));
  return items;
}

void read(Builder& b, const std::smatch& m) {
  json conditions = json::array();
  for (const std::string& item : equations_of(m[1].str())) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos || item.find('=', eq + 1) != std::string::npos)
      throw sentence_error("'" + item +
                           "' is not one equation 'expression = value' (e.g. 'r·v = 0', '|r| = 42165 km')");
    try {
      conditions.push_back(state_condition(item.substr(0, eq), item.substr(eq + 1)));
    } catch (const std::invalid_argument& e) {
      throw sentence_error(e.what());
    }
  }
  if (b.arrival && b.arrival->kind == "state_conditions") {
    for (auto& c : conditions) b.arrival->target["conditions"].push_back(c);
    return;
  }
  b.once("the final rendezvous");
  b.arrival = Endpoint{b.here, {{"kind", "expressions"}, {"conditions", conditions}}, "state_conditions", std::nullopt};
}

}  // namespace

std::vector<Form> final_conditions() {
  return {
      {"conditions on the final state",
       170,
       R"(At the final time,? (?!the spacecraft\b)(?:the (?:final )?state (?:satisfies|meets) )?(.+=.+))",
       read,
       {{"At the final time r·v = 0 and |r| = 42165 km.", "earth -arrival",
         R"~({"/arrival": {"id": "arrival", "kind": "state_conditions", "at": "tf", "target": {"kind": "expressions",
                 "conditions": [{"expression": "(x*vx+y*vy+z*vz)", "equals": 0, "unit": "km^2/s"},
                                {"expression": "r", "equals": 42165, "unit": "km"}]}}})~"},
        {"At the final time |r| = 42165 km/s.", "earth -arrival", R"~({"error": "km/s"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

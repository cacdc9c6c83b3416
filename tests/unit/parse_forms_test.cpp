// The sentence forms of the builtin parser (tools/lib/src/spec/forms): every form is tried in an order
// of its own, and each of its examples is read by that form, first, into the spec the example states,
// or refused with the words it states.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "../../tools/lib/src/spec/form.hpp"     // the forms and their examples (internal to the parser)
#include "../../tools/lib/src/spec/grammar.hpp"  // with_digits: the numbers in words a form reads as digits
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/spec/parse.hpp"

namespace {

using helios::io::json;
namespace grammar = helios::spec::grammar;

// Where `got` differs from `want` ("" when it does not): numbers to 1e-12 relative, objects key by key.
std::string difference(const json& got, const json& want, const std::string& at) {
  if (want.is_number() && got.is_number()) {
    const double g = got.get<double>(), w = want.get<double>();
    return std::fabs(g - w) <= 1e-12 * std::max(1.0, std::fabs(w)) ? "" : at + ": " + got.dump() + " != " + want.dump();
  }
  if (want.is_object() && got.is_object()) {
    for (const auto& [key, value] : got.items())
      if (!want.contains(key)) return at + "/" + key + ": not expected";
    for (const auto& [key, value] : want.items()) {
      if (!got.contains(key)) return at + "/" + key + ": missing";
      const std::string d = difference(got[key], value, at + "/" + key);
      if (!d.empty()) return d;
    }
    return "";
  }
  if (want.is_array() && got.is_array() && want.size() == got.size()) {
    for (std::size_t k = 0; k < want.size(); ++k) {
      const std::string d = difference(got[k], want[k], at + "/" + std::to_string(k));
      if (!d.empty()) return d;
    }
    return "";
  }
  return got == want ? "" : at + ": " + got.dump() + " != " + want.dump();
}

// "/departure/..." and "/arrival/..." are the first and the last constraint.
json::json_pointer pointer_in(const json& spec, const std::string& where) {
  for (const auto& [name, index] :
       {std::pair<std::string, std::size_t>{"/departure", 0}, {"/arrival", spec["constraints"].size() - 1}})
    if (where.rfind(name, 0) == 0)
      return json::json_pointer("/constraints/" + std::to_string(index) + where.substr(name.size()));
  return json::json_pointer(where);
}

TEST(ParseForms, EveryFormHasAnOrderOfItsOwnAndExamples) {
  const auto& forms = grammar::compiled_forms();
  ASSERT_GE(forms.size(), 25u);
  std::set<int> orders;
  for (const auto& f : forms) {
    EXPECT_TRUE(orders.insert(f.form->order).second) << f.form->name;
    EXPECT_FALSE(f.form->examples.empty()) << f.form->name << " has no example";
  }
}

TEST(ParseForms, EachExampleIsReadByItsFormIntoTheSpecItStates) {
  int examples = 0;
  for (const auto& f : grammar::compiled_forms())
    for (const grammar::FormExample& ex : f.form->examples) {
      ++examples;
      SCOPED_TRACE(f.form->name + ": " + ex.sentence);
      std::string first = ex.sentence.substr(0, ex.sentence.find('\n'));
      if (!first.empty() && first.back() == '.') first.pop_back();
      const grammar::Form* reader = grammar::form_of(grammar::with_digits(first));
      EXPECT_EQ(reader ? reader->name : "the facts in other words", f.form->name);
      const json expect = json::parse(ex.expect);
      json spec;
      try {
        spec = helios::spec::parse_problem_text(grammar::example_text(ex), "problem.txt");
      } catch (const helios::input_error& e) {
        const std::string message = e.what();
        ASSERT_TRUE(expect.contains("error")) << message;
        EXPECT_NE(message.find(expect["error"].get<std::string>()), std::string::npos) << message;
        EXPECT_EQ(message.rfind("problem.txt:", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        continue;
      }
      ASSERT_FALSE(expect.contains("error")) << "accepted: " << spec.dump();
      EXPECT_NO_THROW(helios::io::validate("spec", spec, "spec"));
      for (const auto& [where, want] : expect.items()) {
        const json::json_pointer p = pointer_in(spec, where);
        ASSERT_TRUE(spec.contains(p)) << where << " missing in " << spec.dump();
        EXPECT_EQ(difference(spec[p], want, where), "");
      }
    }
  EXPECT_GE(examples, 50);
}

}  // namespace

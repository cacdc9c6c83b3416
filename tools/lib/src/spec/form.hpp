#pragma once
// A sentence form of the controlled English (internal to tools/lib/src/spec): the pattern a sentence
// must match whole (without case), the function that reads it into the Builder, and examples that
// show it and that the unit tests read (tests/unit/parse_forms_test.cpp). Each form is one file of
// forms/, which defines the function of its name, e.g. forms/time_of_flight.cpp defines
// forms::time_of_flight() returning its forms; the build lists those files (CMakeLists.txt), so a new
// form touches its file and LANGUAGE.md only.
#include <regex>
#include <string>
#include <vector>

namespace helios::spec::grammar {

struct Builder;

// An example of a form: `sentence` put into the problem `context` names (form_registry.cpp: "sun",
// "earth", "planets"), without the groups of facts written "-group" and with the sentences written
// "+group", and what the spec must then hold: {"/json/pointer": value, ...} ("/departure" and
// "/arrival" stand for the first and the last constraint; numbers compared to 1e-12 relative), or
// {"error": "words of the refusal"}.
struct FormExample {
  std::string sentence, context, expect;
};

struct Form {
  std::string name;  // what the form states: "the time of flight"
  int order;         // forms are tried by increasing order; the first whose pattern matches applies
  std::string pattern;
  void (*read)(Builder&, const std::smatch&);
  std::vector<FormExample> examples;
};

// Every form file's forms, in no order: defined by the list the build generates from forms/*.cpp.
namespace forms {
std::vector<Form> all_forms();
}

// Every form, by increasing order, each pattern compiled (whole sentence, without case).
struct CompiledForm {
  const Form* form;
  std::regex pattern;
};
const std::vector<CompiledForm>& compiled_forms();

// The form that reads `sentence` (final period removed), or nullptr: the facts in other words.
const Form* form_of(const std::string& sentence);

// The problem text of an example: its context's sentences and the example's.
std::string example_text(const FormExample& example);

}  // namespace helios::spec::grammar

#pragma once
// The derivation's "terms" listing (schemas/derivation.schema.json): the force terms whose sum
// is the dynamics f and the cost terms whose sum is the running cost L, each with the names of
// the parameters it uses. Read here for the verifier (which recomputes each term) and the code
// generator (which matches a template by its terms).
#include <optional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::derivation {

struct Term {
  std::string name, kind;                 // kind: force | cost
  std::vector<std::string> parameters;    // the derivation's parameters it uses, in its own order
  std::string label;                      // user_acceleration: its name in the spec
  std::vector<std::string> acceleration;  // user_acceleration: its normalized components
  std::string body;                       // third_body: the body's name
};

// The names of the catalogue's terms (helios/pmp/catalogue.hpp), forces then costs.
const std::vector<std::string>& force_term_names();
const std::vector<std::string>& cost_term_names();

// The listing of `derivation`, or nothing when it has no "terms" field. Throws io::input_error
// "<where>: field terms[<i>]...: ..." naming the entry and the value it cannot read.
std::optional<std::vector<Term>> read_terms(const io::json& derivation, const std::string& where);

// The names of the terms, in order ("two_body, thrust, fuel").
std::string term_names(const std::vector<Term>& terms);

}  // namespace helios::derivation

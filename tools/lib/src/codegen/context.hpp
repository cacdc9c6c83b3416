#pragma once
// What the generator's modules share (internal to tools/lib/src/codegen): the derivation read once
// into a Context (the typed derivation::Document: symbols, names, units, every section), and small
// text helpers.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "helios/derivation/document.hpp"
#include "helios/derivation/names.hpp"
#include "helios/io/json_io.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::codegen::detail {

namespace names = derivation::names;

using io::json;
using symbolic::SymbolTable;

// The index of `name` in v, -1 when absent.
int index_of(const std::vector<std::string>& v, const std::string& name);

// The derivation as read (names, symbols, units) and the generator's helpers over it.
struct Context : derivation::Document {
  explicit Context(const json& derivation) : Document(derivation), chain(chain_rule()) {}

  // The intermediates: each module computes them after unpacking y and differentiates through them.
  const symbolic::ChainRule chain;

  // The variables of the normalization equation (the sphere: lambda0 and lambda(t0)).
  std::vector<std::string> sphere_variables() {
    for (const auto& e : shooting.equations)
      if (e.name == "normalization")
        return symbolic::free_symbols(symbols.parse(e.expression.text, "field /shooting/equations/normalization"));
    return {};
  }

  // An expression of the derivation over the symbols; errors name its field ("field <pointer>: ...").
  GiNaC::ex parsed(const derivation::Expression& e) const { return symbols.parse(e.text, "field " + e.pointer); }

  // C++ for an expression; parameters are read from namespace problem. `scalar`: std::pow and the
  // like for double code, unqualified in code templated on its scalar (the RESIDUAL module: double,
  // or the runtime's dual numbers for the Jacobian).
  std::string cpp(const GiNaC::ex& e, symbolic::CppScalar scalar) {
    GiNaC::exmap qualified;
    for (const auto& p : parameters)
      if (index_of(runtime_evaluated, p) < 0) qualified[symbols.get(p)] = GiNaC::symbol("problem::" + p);
    return symbolic::to_csrc(e.subs(qualified), scalar);
  }
};

// A double as C++ source that reads back exactly (17 digits, always with a '.' or exponent).
std::string number(double v);

// "a", "b", ... as a C++ initializer list body.
std::string quoted_list(const std::vector<std::string>& v);

// `s` as a C++ string literal: quotes, backslashes and '?' escaped, control bytes as octal escapes.
// Every string from an artifact that the generated code holds goes through it.
std::string cpp_string(const std::string& s);

// `s` fit for a // comment: control bytes (a newline would end the comment and let the rest be
// code) become spaces, backslashes (a line splice) become '/'.
std::string comment_text(std::string s);

// The modules, each from its own unit.
std::string problem_block(Context& c);                   // problem_block.cpp
std::string generated_dynamics(Context& c);              // dynamics_module.cpp
std::string generated_jacobians(Context& c);             // jacobian_module.cpp
bool jacobian_supported(Context& c);                     // jacobian_module.cpp
bool template_matches(Context& c, const json& model);    // dynamics_module.cpp
std::string residual_module(Context& c, bool jacobian);  // residual_module.cpp (jacobian: shooting_jacobian too)
std::string solve_module(Context& c);                    // solve_module.cpp
std::string module_table(Context& c, bool jacobian);     // module_table.cpp (after SOLVE)

}  // namespace helios::codegen::detail

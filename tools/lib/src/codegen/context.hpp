#pragma once
// What the generator's modules share (internal to tools/lib/src/codegen): the derivation read once
// into a Context (symbols, names, the shooting variables), and small text helpers.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::codegen::detail {

using io::json;
using symbolic::SymbolTable;

// The index of `name` in v, -1 when absent.
int index_of(const std::vector<std::string>& v, const std::string& name);

struct Context {
  const json& d;
  SymbolTable symbols;
  std::vector<std::string> states, costates, controls, parameters;
  std::vector<std::string> runtime_evaluated;  // parameters with a source: locals of RESIDUAL, not constants
  std::vector<std::string> variables;          // the shooting variables' names, in x's order
  int throttle_index = -1;
  explicit Context(const json& derivation) : d(derivation) {
    for (const auto& s : d.at("states")) {
      states.push_back(s.at("name"));
      costates.push_back(s.at("costate"));
    }
    for (const auto& c : d.at("controls")) {
      controls.push_back(c.at("name"));
      if (c.at("kind") == "throttle") throttle_index = static_cast<int>(controls.size()) - 1;
    }
    for (const auto& p : d.at("parameters")) {
      parameters.push_back(p.at("name"));
      if (p.contains("source")) runtime_evaluated.push_back(p.at("name"));
    }
    const std::string mult = d.at("multiplier");
    symbols.get("t");
    if (d.contains("event_values"))
      for (const auto& e : d.at("event_values")) symbols.get(e.at("name").get<std::string>());
    for (const auto& v : d.at("shooting").at("variables")) {
      variables.push_back(v.at("name"));
      symbols.get(variables.back());
    }
    for (const char* kind : {"direction", "sail"})
      if (d.at("control_law").contains(kind))
        for (const auto& def : d.at("control_law").at(kind).value("definitions", json::array()))
          symbols.get(def.at("name").get<std::string>());
    for (const auto& n : states) symbols.get(n);
    for (const auto& n : costates) symbols.get(n);
    for (const auto& n : controls) symbols.get(n);
    for (const auto& n : parameters) symbols.get(n);
    symbols.get(mult);
    symbols.get(d.at("homotopy").at("symbol").get<std::string>());
    for (const auto& n : states) {
      symbols.get(n + "_tf");
      symbols.get(n + "_t0");
    }
    for (const auto& n : costates) {
      symbols.get(n + "_tf");
      symbols.get(n + "_t0");
    }
    for (const auto& e : d.value("events", json::array())) {
      const std::string id = e.at("id");
      events.push_back(id);
      symbols.get("t_" + id);
      for (const auto* names : {&states, &costates})
        for (const auto& n : *names) {
          symbols.get(n + "_" + id + "_m");
          symbols.get(n + "_" + id + "_p");
        }
    }
  }
  std::vector<std::string> events;

  // The variables of the normalization equation (the sphere: lambda0 and lambda(t0)).
  std::vector<std::string> sphere_variables() {
    for (const auto& e : d.at("shooting").at("equations"))
      if (e.at("name") == "normalization")
        return symbolic::free_symbols(symbols.parse(e.at("expression"), "field /shooting/equations/normalization"));
    return {};
  }

  // C++ for a stored expression; parameters are read from namespace problem.
  std::string cpp(const std::string& text, const std::string& where) {
    GiNaC::ex e = symbols.parse(text, "field " + where);
    GiNaC::exmap qualified;
    for (const auto& p : parameters)
      if (index_of(runtime_evaluated, p) < 0) qualified[symbols.get(p)] = GiNaC::symbol("problem::" + p);
    return symbolic::to_csrc(e.subs(qualified));
  }
};

// A double as C++ source that reads back exactly (17 digits, always with a '.' or exponent).
std::string number(double v);

// "a", "b", ... as a C++ initializer list body.
std::string quoted_list(const std::vector<std::string>& v);

// The modules, each from its own unit.
std::string problem_block(Context& c);                 // problem_block.cpp
std::string generated_dynamics(Context& c);            // dynamics_module.cpp
bool template_matches(Context& c, const json& model);  // dynamics_module.cpp
std::string residual_module(Context& c);               // residual_module.cpp
std::string solve_module(Context& c);                  // solve_module.cpp

}  // namespace helios::codegen::detail

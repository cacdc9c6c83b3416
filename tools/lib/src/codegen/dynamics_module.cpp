// The DYNAMICS and SWITCH modules generated from the derivation, and the check that the
// template's own implement it.
#include "body.hpp"
#include "context.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios::codegen::detail {
namespace {

// A function of the runtime's interface with the generated `body`: `(void)p;` for each of its
// `parameters` p (t, y, control, mult) the body uses neither itself nor through its locals.
std::string function(const std::string& signature, const std::vector<std::string>& parameters, Body& body) {
  return signature + " {\n" + body.unused_parameters(parameters) + body.str() + "}\n\n";
}

// dynamics: dy = the state and costate equations.
std::string dynamics_function(Context& c) {
  const auto& so = c.state_odes;
  const auto& co = c.costate_odes;
  if (so.size() != c.states.size() || co.size() != c.states.size())
    throw std::invalid_argument("field /state_odes or /costate_odes: one equation per state is required");
  Body body(c);
  body.unpack_variables(true);
  for (std::size_t i = 0; i < so.size(); ++i)
    body.code() << "  dy[" << i << "] = " << body.cpp(c.parsed(so[i].rhs)) << ";\n";
  for (std::size_t i = 0; i < co.size(); ++i)
    body.code() << "  dy[" << so.size() + i << "] = " << body.cpp(c.parsed(co[i].rhs)) << ";\n";
  return function(
      "void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy)",
      {"t", "y", "control", "mult"}, body);
}

std::string hamiltonian_function(Context& c) {
  Body body(c);
  body.unpack_variables(true);
  body.code() << "  return " << body.cpp(c.parsed(c.hamiltonian)) << ";\n";
  return function("double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult)",
                  {"t", "y", "control", "mult"}, body);
}

// direction_control: the direction (or sail) controls from their laws, after the laws' definitions.
std::string direction_function(Context& c) {
  const derivation::ControlLaw& cl = c.control_law;
  Body body(c);
  body.unpack_y();
  for (const char* kind : {"direction", "sail"}) {
    const bool direction = std::string(kind) == "direction";
    if (direction ? !cl.direction : !cl.sail) continue;
    const std::string where = "field /control_law/" + std::string(kind);
    const auto& names = direction ? cl.direction->controls : cl.sail->controls;
    const auto& law = direction ? cl.direction->law : cl.sail->law;
    for (const auto& def : direction ? cl.direction->definitions : cl.sail->definitions)
      body.code() << "  const double " << def.name << " = " << body.cpp(c.parsed(def.expression)) << ";\n";
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (j >= law.size()) throw std::invalid_argument(where + "/law/" + std::to_string(j) + " is missing");
      body.code() << "  control[" << index_of(c.controls, body.use(names[j])) << "] = " << body.cpp(c.parsed(law[j]))
                  << ";\n";
    }
  }
  return function("void direction_control(const double* y, double* control)", {"y", "control"}, body);
}

std::string throttle_function(Context& c) {
  const derivation::ThrottleLaw& throttle = *c.control_law.throttle;
  Body body(c);
  body.unpack_variables(false);
  body.code() << "  at_lower = " << body.cpp(c.parsed(throttle.dH_du_at_lower)) << ";\n"
              << "  at_upper = " << body.cpp(c.parsed(throttle.dH_du_at_upper)) << ";\n";
  return function("void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper)",
                  {"y", "mult"}, body);
}

}  // namespace

std::string generated_dynamics(Context& c) {
  std::string o =
      "// ----- modules DYNAMICS + SWITCH (generated from the derivation) ---------------------------\n"
      "namespace helios_rt {\n\n";
  o += dynamics_function(c) + hamiltonian_function(c) + direction_function(c);
  if (c.control_law.throttle) o += throttle_function(c);
  return o + "}  // namespace helios_rt\n";
}

// True if the template's default DYNAMICS/SWITCH implement this derivation: same state, costate
// and control order, and the same H (compared at random points).
bool template_matches(Context& c, const json& model) {
  if (model.at("states").get<std::vector<std::string>>() != c.states) return false;
  if (model.at("costates").get<std::vector<std::string>>() != c.costates) return false;
  if (model.at("controls").get<std::vector<std::string>>() != c.controls) return false;
  for (const auto& p : model.at("parameters"))
    if (index_of(c.parameters, p) < 0) return false;
  if (!c.control_law.throttle) return false;
  const derivation::ThrottleLaw& throttle = *c.control_law.throttle;
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {model.at("hamiltonian"), c.hamiltonian.text},
      {model.at("dH_du_at_lower"), throttle.dH_du_at_lower.text},
      {model.at("dH_du_at_upper"), throttle.dH_du_at_upper.text}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> dist(0.3, 1.7);
  for (int trial = 0; trial < 8; ++trial) {
    symbolic::Values values;
    for (const auto& [name, sym] : c.symbols.symtab())
      values[name] = dist(rng) * (trial % 2 ? 1 : -1) * (name == "m" ? -1 : 1);
    for (const auto& [a, b] : pairs) {
      try {
        const double va = symbolic::evaluate(c.symbols.parse(a, "template"), c.symbols, values);
        const double vb = symbolic::evaluate(c.symbols.parse(b, "derivation"), c.symbols, values);
        if (std::fabs(va - vb) > 1e-10 * (1 + std::max(std::fabs(va), std::fabs(vb)))) return false;
      } catch (const std::exception&) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace helios::codegen::detail

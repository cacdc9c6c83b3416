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
  const auto& so = c.d.at("state_odes");
  const auto& co = c.d.at("costate_odes");
  if (so.size() != c.states.size() || co.size() != c.states.size())
    throw std::invalid_argument("field /state_odes or /costate_odes: one equation per state is required");
  Body body(c);
  body.unpack_variables(true);
  for (std::size_t i = 0; i < so.size(); ++i)
    body.code() << "  dy[" << i << "] = " << body.cpp(so[i].at("rhs"), "/state_odes/" + std::to_string(i) + "/rhs")
                << ";\n";
  for (std::size_t i = 0; i < co.size(); ++i)
    body.code() << "  dy[" << so.size() + i
                << "] = " << body.cpp(co[i].at("rhs"), "/costate_odes/" + std::to_string(i) + "/rhs") << ";\n";
  return function(
      "void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy)",
      {"t", "y", "control", "mult"}, body);
}

std::string hamiltonian_function(Context& c) {
  Body body(c);
  body.unpack_variables(true);
  body.code() << "  return " << body.cpp(c.d.at("hamiltonian"), "/hamiltonian") << ";\n";
  return function("double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult)",
                  {"t", "y", "control", "mult"}, body);
}

// direction_control: the direction (or sail) controls from their laws, after the laws' definitions.
std::string direction_function(Context& c) {
  const json& cl = c.d.at("control_law");
  Body body(c);
  body.unpack_y();
  for (const char* kind : {"direction", "sail"}) {
    if (!cl.contains(kind)) continue;
    const std::string where = "/control_law/" + std::string(kind);
    const auto& names = cl.at(kind).at("controls");
    const auto& law = cl.at(kind).at("law");
    const json definitions = cl.at(kind).value("definitions", json::array());
    for (std::size_t j = 0; j < definitions.size(); ++j)
      body.code() << "  const double " << definitions[j].at("name").get<std::string>() << " = "
                  << body.cpp(definitions[j].at("expression"),
                              where + "/definitions/" + std::to_string(j) + "/expression")
                  << ";\n";
    for (std::size_t j = 0; j < names.size(); ++j)
      body.code() << "  control[" << index_of(c.controls, body.use(names[j]))
                  << "] = " << body.cpp(law[j], where + "/law/" + std::to_string(j)) << ";\n";
  }
  return function("void direction_control(const double* y, double* control)", {"y", "control"}, body);
}

std::string throttle_function(Context& c) {
  const json& throttle = c.d.at("control_law").at("throttle");
  Body body(c);
  body.unpack_variables(false);
  body.code() << "  at_lower = " << body.cpp(throttle.at("dH_du_at_lower"), "/control_law/throttle/dH_du_at_lower")
              << ";\n"
              << "  at_upper = " << body.cpp(throttle.at("dH_du_at_upper"), "/control_law/throttle/dH_du_at_upper")
              << ";\n";
  return function("void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper)",
                  {"y", "mult"}, body);
}

}  // namespace

std::string generated_dynamics(Context& c) {
  std::string o =
      "// ----- modules DYNAMICS + SWITCH (generated from the derivation) ---------------------------\n"
      "namespace helios_rt {\n\n";
  o += dynamics_function(c) + hamiltonian_function(c) + direction_function(c);
  if (c.d.at("control_law").contains("throttle")) o += throttle_function(c);
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
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {model.at("hamiltonian"), c.d.at("hamiltonian")},
      {model.at("dH_du_at_lower"), c.d.at("control_law").at("throttle").at("dH_du_at_lower")},
      {model.at("dH_du_at_upper"), c.d.at("control_law").at("throttle").at("dH_du_at_upper")}};
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

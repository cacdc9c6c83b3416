// The DYNAMICS and SWITCH modules generated from the derivation, and the check that the
// template's own implement it.
#include "context.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

namespace helios::codegen::detail {
namespace {

// Local names for y[], control[] and the multipliers, so generated expressions read like the math.
std::string unpack(Context& c, bool with_control) {
  std::ostringstream o;
  for (std::size_t i = 0; i < c.states.size(); ++i)
    o << "  [[maybe_unused]] const double " << c.states[i] << " = y[" << i << "];\n";
  for (std::size_t i = 0; i < c.costates.size(); ++i)
    o << "  [[maybe_unused]] const double " << c.costates[i] << " = y[" << c.states.size() + i << "];\n";
  if (with_control) o << "  [[maybe_unused]] const double t = time;\n";
  if (with_control)
    for (std::size_t i = 0; i < c.controls.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.controls[i] << " = control[" << i << "];\n";
  o << "  [[maybe_unused]] const double " << c.d.at("multiplier").get<std::string>() << " = mult.lambda0;\n"
    << "  [[maybe_unused]] const double " << c.d.at("homotopy").at("symbol").get<std::string>() << " = mult.eps;\n";
  return o.str();
}

}  // namespace

std::string generated_dynamics(Context& c) {
  const json& d = c.d;
  std::ostringstream o;
  o << "// ----- modules DYNAMICS + SWITCH (generated from the derivation) ---------------------------\n"
    << "namespace helios_rt {\n\n"
    << "void dynamics(double time, const double* y, const double* control, const Multipliers& mult, double* dy) {\n"
    << unpack(c, true);
  const auto& so = d.at("state_odes");
  const auto& co = d.at("costate_odes");
  if (so.size() != c.states.size() || co.size() != c.states.size())
    throw std::invalid_argument("field /state_odes or /costate_odes: one equation per state is required");
  for (std::size_t i = 0; i < so.size(); ++i)
    o << "  dy[" << i << "] = " << c.cpp(so[i].at("rhs"), "/state_odes/" + std::to_string(i) + "/rhs") << ";\n";
  for (std::size_t i = 0; i < co.size(); ++i)
    o << "  dy[" << so.size() + i << "] = " << c.cpp(co[i].at("rhs"), "/costate_odes/" + std::to_string(i) + "/rhs")
      << ";\n";
  o << "}\n\n"
    << "double hamiltonian(double time, const double* y, const double* control, const Multipliers& mult) {\n"
    << unpack(c, true) << "  return " << c.cpp(d.at("hamiltonian"), "/hamiltonian") << ";\n}\n\n"
    << "void direction_control(const double* y, double* control) {\n";
  const json& cl = d.at("control_law");
  if (cl.contains("direction") || cl.contains("sail")) {
    for (std::size_t i = 0; i < c.states.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.states[i] << " = y[" << i << "];\n";
    for (std::size_t i = 0; i < c.costates.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.costates[i] << " = y[" << c.states.size() + i << "];\n";
    for (const char* kind : {"direction", "sail"}) {
      if (!cl.contains(kind)) continue;
      const auto& names = cl.at(kind).at("controls");
      const auto& law = cl.at(kind).at("law");
      const json definitions = cl.at(kind).value("definitions", json::array());
      for (std::size_t j = 0; j < definitions.size(); ++j)
        o << "  const double " << definitions[j].at("name").get<std::string>() << " = "
          << c.cpp(definitions[j].at("expression"),
                   "/control_law/" + std::string(kind) + "/definitions/" + std::to_string(j) + "/expression")
          << ";\n";
      for (std::size_t j = 0; j < names.size(); ++j)
        o << "  control[" << index_of(c.controls, names[j])
          << "] = " << c.cpp(law[j], "/control_law/" + std::string(kind) + "/law/" + std::to_string(j)) << ";\n";
    }
  } else {
    o << "  (void)y;\n  (void)control;\n";
  }
  o << "}\n\n";
  if (cl.contains("throttle"))
    o << "void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper) {\n"
      << unpack(c, false)
      << "  at_lower = " << c.cpp(cl.at("throttle").at("dH_du_at_lower"), "/control_law/throttle/dH_du_at_lower")
      << ";\n"
      << "  at_upper = " << c.cpp(cl.at("throttle").at("dH_du_at_upper"), "/control_law/throttle/dH_du_at_upper")
      << ";\n"
      << "}\n\n";
  o << "}  // namespace helios_rt\n";
  return o.str();
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

// The JACOBIAN module generated from the derivation: the exact first derivatives of the DYNAMICS
// module's right-hand side (GiNaC diff of the derivation's state and costate equations) and of
// the SWITCH module's direction law and throttle slopes, the building blocks of the variational equations
// Phi' = (df/dy + df/du du/dy) Phi of the shooting Jacobian (issue 15).
#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "body.hpp"
#include "context.hpp"

namespace helios::codegen::detail {
namespace {

// The variables y (states then costates) as GiNaC symbols.
std::vector<GiNaC::symbol> y_symbols(Context& c) {
  std::vector<GiNaC::symbol> y;
  for (const auto& s : c.states) y.push_back(c.symbols.get(s));
  for (const auto& s : c.costates) y.push_back(c.symbols.get(s));
  return y;
}

// z = (y, lambda0): lambda0 is a shooting variable that the throttle's slopes (and in general the
// running cost's part of the dynamics) depend on, so the variational equations carry it.
std::vector<GiNaC::symbol> z_symbols(Context& c) {
  std::vector<GiNaC::symbol> z = y_symbols(c);
  z.push_back(c.symbols.get(c.multiplier));
  return z;
}

// The state and costate equations' right-hand sides.
std::vector<GiNaC::ex> right_hand_sides(Context& c) {
  const auto& so = c.state_odes;
  const auto& co = c.costate_odes;
  if (so.size() != c.states.size() || co.size() != c.states.size())
    throw std::invalid_argument("field /state_odes or /costate_odes: one equation per state is required");
  std::vector<GiNaC::ex> rhs;
  for (const auto* odes : {&so, &co})
    for (const auto& ode : *odes) rhs.push_back(c.parsed(ode.rhs));
  return rhs;
}

// The intermediates' gradients in the variables `vars`: locals d_<q>_<j> of a body (written where
// used), each by the chain rule through the earlier ones, so that a derivative through an
// intermediate names its gradient instead of repeating the expression in every entry.
class Gradients {
 public:
  Gradients(Context& c, Body& body, const std::vector<GiNaC::symbol>& vars) : vars_(vars) {
    for (const auto& [q, expression] : c.chain.order()) {
      std::vector<GiNaC::ex> g(vars.size(), GiNaC::ex(0));
      for (std::size_t j = 0; j < vars.size(); ++j) {
        const GiNaC::ex d = through(expression, j);
        if (d.is_zero()) continue;
        const std::string name = "d_" + q.get_name() + "_" + std::to_string(j);
        body.local(name, d);
        g[j] = c.symbols.get(name);
      }
      q_.push_back(q);
      gradient_.push_back(std::move(g));
    }
  }
  // d e / d vars[j], through the intermediates.
  GiNaC::ex through(const GiNaC::ex& e, std::size_t j) const {
    GiNaC::ex d = e.diff(vars_[j]);
    for (std::size_t i = 0; i < q_.size(); ++i)
      if (!gradient_[i][j].is_zero() && e.has(q_[i])) d += e.diff(q_[i]) * gradient_[i][j];
    return d;
  }

 private:
  const std::vector<GiNaC::symbol>& vars_;
  std::vector<GiNaC::symbol> q_;
  std::vector<std::vector<GiNaC::ex>> gradient_;  // gradient_[i][j]: the local of d q_i / d vars[j], or 0
};

// dynamics_jacobian: dfdz[i * nz + j] = d dy_i / d z_j and dfdu[i * nc + k] = d dy_i / d control_k
// at fixed control, zero where the derivative is identically zero.
std::string dynamics_jacobian_function(Context& c) {
  const std::vector<GiNaC::ex> rhs = right_hand_sides(c);
  const std::vector<GiNaC::symbol> z = z_symbols(c);
  const std::size_t ny = rhs.size(), nz = z.size(), nc = c.controls.size();
  Body body(c);
  body.unpack_variables(true);
  const Gradients gradients(c, body, z);
  body.code() << "  std::fill(dfdz, dfdz + " << ny * nz << ", 0.0);\n";
  if (nc > 0) body.code() << "  std::fill(dfdu, dfdu + " << ny * nc << ", 0.0);\n";
  for (std::size_t i = 0; i < ny; ++i) {
    for (std::size_t j = 0; j < nz; ++j) {
      const GiNaC::ex d = gradients.through(rhs[i], j);
      if (!d.is_zero()) body.code() << "  dfdz[" << i * nz + j << "] = " << body.cpp(d) << ";\n";
    }
    for (std::size_t k = 0; k < nc; ++k) {
      const GiNaC::ex d = rhs[i].diff(c.symbols.get(c.controls[k]));
      if (!d.is_zero()) body.code() << "  dfdu[" << i * nc + k << "] = " << body.cpp(d) << ";\n";
    }
  }
  if (nc == 0) body.code() << "  (void)dfdu;\n";
  const std::string text = body.str();
  return "void dynamics_jacobian(double t, const double* y, const double* control, const Multipliers& mult, "
         "double* dfdz, double* dfdu) {\n" +
         body.unused_parameters({"t", "y", "control", "mult"}) + text + "}\n\n";
}

// direction_jacobian: dcontrol_dy[k * ny + j] = d control_k / d y_j of the direction (or sail)
// law, its definitions substituted; the throttle's row (and any control without a law) is zero.
std::string direction_jacobian_function(Context& c) {
  const derivation::ControlLaw& cl = c.control_law;
  const std::vector<GiNaC::symbol> y = y_symbols(c);
  const std::size_t ny = y.size(), nc = c.controls.size();
  Body body(c);
  body.unpack_y();
  if (nc > 0) body.code() << "  std::fill(dcontrol_dy, dcontrol_dy + " << nc * ny << ", 0.0);\n";
  std::vector<std::pair<std::string, GiNaC::ex>> locals;   // the definitions and their gradients, in order
  std::vector<std::pair<std::size_t, GiNaC::ex>> entries;  // the nonzero entries of dcontrol_dy
  for (const char* kind : {"direction", "sail"}) {
    const bool direction = std::string(kind) == "direction";
    if (direction ? !cl.direction : !cl.sail) continue;
    const std::string where = "field /control_law/" + std::string(kind);
    const auto& names = direction ? cl.direction->controls : cl.sail->controls;
    const auto& law = direction ? cl.direction->law : cl.sail->law;
    const auto& definitions = direction ? cl.direction->definitions : cl.sail->definitions;
    // The definitions as locals, each with its gradient d_<name>_<j> by the chain rule through
    // the earlier ones (substituting them instead would grow the expressions without bound).
    std::vector<GiNaC::symbol> defs;
    std::vector<std::vector<GiNaC::ex>> grads;  // grads[i][j] = d def_i / d y_j (a symbol or 0)
    // The derivative of e in y_j: its own and through each definition's gradient.
    auto total = [&](const GiNaC::ex& e, std::size_t j) {
      GiNaC::ex d = c.chain.diff(e, y[j]);
      for (std::size_t i = 0; i < defs.size(); ++i)
        if (!grads[i][j].is_zero()) d += e.diff(defs[i]) * grads[i][j];
      return d;
    };
    for (std::size_t i = 0; i < definitions.size(); ++i) {
      const std::string& name = definitions[i].name;
      const GiNaC::ex e = c.parsed(definitions[i].expression);
      locals.emplace_back(name, e);
      std::vector<GiNaC::ex> g(ny, GiNaC::ex(0));
      for (std::size_t j = 0; j < ny; ++j) {
        const GiNaC::ex d = total(e, j);
        if (d.is_zero()) continue;
        const std::string d_name = "d_" + name + "_" + std::to_string(j);
        locals.emplace_back(d_name, d);
        g[j] = c.symbols.get(d_name);
      }
      defs.push_back(c.symbols.get(name));
      grads.push_back(g);
    }
    for (std::size_t k = 0; k < names.size(); ++k) {
      const int row = index_of(c.controls, names[k]);
      if (row < 0) throw std::invalid_argument(where + "/controls/" + std::to_string(k) + ": not a control");
      if (k >= law.size()) throw std::invalid_argument(where + "/law/" + std::to_string(k) + " is missing");
      const GiNaC::ex e = c.parsed(law[k]);
      for (std::size_t j = 0; j < ny; ++j) {
        const GiNaC::ex d = total(e, j);
        if (!d.is_zero()) entries.emplace_back(row * ny + j, d);
      }
    }
  }
  // Only the locals the entries need, directly or through later locals.
  std::set<std::string> needed;
  for (const auto& [k, d] : entries)
    for (const auto& n : symbolic::free_symbols(d)) needed.insert(n);
  for (auto it = locals.rbegin(); it != locals.rend(); ++it)
    if (needed.count(it->first))
      for (const auto& n : symbolic::free_symbols(it->second)) needed.insert(n);
  for (const auto& [name, e] : locals)
    if (needed.count(name)) body.code() << "  const double " << name << " = " << body.cpp(e) << ";\n";
  for (const auto& [k, d] : entries) body.code() << "  dcontrol_dy[" << k << "] = " << body.cpp(d) << ";\n";
  const std::string text = body.str();
  std::string unused = body.unused_parameters({"y"});
  if (nc == 0) unused += "  (void)dcontrol_dy;\n";
  return "void direction_jacobian(const double* y, double* dcontrol_dy) {\n" + unused + text + "}\n\n";
}

// throttle_slopes_jacobian: d_lower[j], d_upper[j] = d/dz_j of the throttle's dH/du at u = 0 and
// u = 1 (the SWITCH module's throttle_slopes): the interior throttle's and the switches' gradients.
std::string throttle_jacobian_function(Context& c) {
  const derivation::ThrottleLaw& throttle = *c.control_law.throttle;
  const std::vector<GiNaC::symbol> z = z_symbols(c);
  Body body(c);
  body.unpack_variables(false);
  const Gradients gradients(c, body, z);
  body.code() << "  std::fill(d_lower, d_lower + " << z.size() << ", 0.0);\n"
              << "  std::fill(d_upper, d_upper + " << z.size() << ", 0.0);\n";
  for (const char* side : {"lower", "upper"}) {
    const GiNaC::ex e = c.parsed(std::string(side) == "lower" ? throttle.dH_du_at_lower : throttle.dH_du_at_upper);
    for (std::size_t j = 0; j < z.size(); ++j) {
      const GiNaC::ex d = gradients.through(e, j);
      if (!d.is_zero()) body.code() << "  d_" << side << "[" << j << "] = " << body.cpp(d) << ";\n";
    }
  }
  const std::string text = body.str();
  return "void throttle_slopes_jacobian(const double* y, const Multipliers& mult, double* d_lower, double* d_upper) "
         "{\n" +
         body.unused_parameters({"y", "mult"}) + text + "}\n\n";
}

}  // namespace

// The variational equations hold where the dynamics are autonomous (no explicit time: the
// propagation's derivative in a free epoch is then f itself, and dH/dt = 0 at fixed state) and every
// control has a law the module differentiates (throttle, direction, sail).
bool jacobian_supported(Context& c) {
  std::vector<GiNaC::ex> checked = right_hand_sides(c);
  checked.push_back(c.parsed(c.hamiltonian));
  for (const auto& [q, expression] : c.chain.order()) checked.push_back(expression);
  for (const auto& e : checked)
    for (const auto& name : symbolic::free_symbols(e))
      if (name == "t") return false;
  return c.control_law.other.empty();
}

std::string generated_jacobians(Context& c) {
  return "// ----- module JACOBIAN (generated from the derivation: GiNaC derivatives) -----------------\n"
         "namespace helios_rt {\n\n" +
         dynamics_jacobian_function(c) + direction_jacobian_function(c) +
         (c.control_law.throttle ? throttle_jacobian_function(c) : std::string()) + "}  // namespace helios_rt\n";
}

}  // namespace helios::codegen::detail

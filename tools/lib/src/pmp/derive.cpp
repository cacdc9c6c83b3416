// The builtin PMP engine: the canonical system of H = lambda0 L + lambda^T f, then each family
// of conditions in its own unit (conditions.hpp), assembled into the shooting system.
#include "helios/pmp/derive.hpp"

#include <algorithm>

#include "conditions.hpp"

namespace helios::pmp {

using GiNaC::ex;

ex tidy(const ex& e) {
  const ex expanded = e.expand();
  return symbolic::to_text(expanded).size() <= symbolic::to_text(e).size() ? expanded : e;
}

ex time_derivative(Problem& p, const ex& e) {
  ex d = 0;
  for (const auto& [name, rate] : p.parameter_rates) d += e.diff(p.symbols.get(name)) * rate;
  return d;
}

ShootingVariable multiplier_variable(const std::string& name, const std::string& meaning, bool inequality) {
  return {name, meaning + (inequality ? " (a bound: 0 while inactive, >= 0 when active)" : " = 0"), "multiplier",
          "uniform in (-1, 1)"};
}

ShootingEquation constraint_equation(const std::string& name, const ex& expression, const std::string& meaning,
                                     const std::string& source, const GiNaC::symbol& multiplier, bool inequality) {
  ShootingEquation eq{name, expression, meaning + (inequality ? ", active: = 0" : " = 0"), source};
  if (inequality)
    eq.inequality = Inequality{"expression <= 0", multiplier.get_name(), multiplier,
                               "pass 1: inactive (multiplier = 0); if the expression is > 0 at the solution, "
                               "pass 2 makes it active (expression = 0) and requires multiplier >= 0"};
  return eq;
}

namespace {

// H = lambda0 L + lambda^T f and its canonical system: x' = dH/dlambda, lambda' = -dH/dx (through
// the intermediates f and L hold).
void canonical_system(Derivation& d) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  const symbolic::ChainRule chain = p.chain_rule();
  d.hamiltonian = S.get("lambda0") * p.running_cost;
  for (std::size_t i = 0; i < p.states.size(); ++i) d.hamiltonian += S.get(names::costate(p.states[i].name)) * p.f[i];
  d.smoothed = d.hamiltonian.has(S.get("eps"));
  for (const auto& s : p.states) {
    d.state_odes.push_back(d.hamiltonian.diff(S.get(names::costate(s.name))));
    d.costate_odes.push_back((-chain.diff(d.hamiltonian, S.get(s.name))).expand());
  }
}

// The values of H the conditions of free times refer to (H_t0, H_<id>_m/_p, H_tf).
std::vector<EventValue> hamiltonian_values(const Problem& p) {
  std::vector<EventValue> values;
  const auto at = [&](const std::string& where, const std::string& meaning) {
    values.push_back({names::hamiltonian(where),
                      "H " + meaning + " with the optimal control (the runtime evaluates it)", "hamiltonian", where});
  };
  if (p.free_departure) at("t0", "at t0");
  for (const auto& e : p.events) {
    at(names::before_label(e.id), "just before " + e.id);
    at(names::after_label(e.id), "just after " + e.id + (e.duration > 0 ? " (at the end of the stay)" : ""));
  }
  if (p.free_final_time || p.free_departure) at("tf", "at tf");
  return values;
}

}  // namespace

Derivation derive_conditions(const Problem& problem) {
  Derivation d;
  d.problem = problem;  // the symbol table grows while deriving
  canonical_system(d);
  d.control = control_law(d.problem, d.hamiltonian);
  if (d.control.throttle) d.control.throttle->smoothing = d.smoothed ? "quadratic" : "none";
  d.shooting.variables.push_back(
      {"lambda0", "cost multiplier lambda0 (>= 0)", "", "uniform in (0, 1), then the whole vector normalized"});
  endpoint_conditions(d);
  for (const auto& e : d.problem.events) d.events.push_back(event_conditions(d.problem, e, d.shooting));
  // Order: endpoint constraints first, then transversality, then the normalization.
  const auto is_psi = [](const ShootingEquation& q) { return names::is_constraint_row(q.name); };
  std::stable_sort(d.shooting.equations.begin(), d.shooting.equations.end(),
                   [&](const ShootingEquation& a, const ShootingEquation& b) { return is_psi(a) && !is_psi(b); });
  initial_costates(d);
  d.hamiltonian_values = hamiltonian_values(d.problem);
  return d;
}

io::json derive(const Problem& problem) {
  return derivation_json(derive_conditions(problem));
}

io::json derive_from_spec(const io::json& spec) {
  return derive(build_problem(spec));
}

}  // namespace helios::pmp

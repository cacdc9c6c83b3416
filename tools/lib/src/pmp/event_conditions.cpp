// Conditions of an interior event from Phi = ... + nu_c^T c(t, x-, p) + nu_g^T (x+ - g(t + D, x-, p))
// (Bryson-Ho): lambda(t+) = -dPhi/dx+ = -nu_g; lambda(t-) = dPhi/dx- = nu_c^T dc/dx- + lambda(t+)^T dg/dx-;
// H(t-) - H(t+) + dPhi/dt = 0 for the free epoch; dPhi/dp = 0 for a free parameter p of psi.
// A state the map carries over (dg_s/dx- = e_s) gets lambda(t+) explicitly from its jump row; any
// other state's lambda(t+) is a shooting variable and its jump row an equation.
#include "conditions.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

// The symbols of an event: each state and costate arriving (m) and leaving (p), the multipliers
// of c, the epoch and its shooting variable; which states the map carries over.
struct EventSymbols {
  std::vector<symbol> xm, xp, lm, lp, nu;
  std::string frac;  // t_<id>_frac
  symbol t_frac, epoch;
  std::vector<bool> carried;
};

EventSymbols event_symbols(Problem& p, const InteriorEvent& e) {
  auto& S = p.symbols;
  EventSymbols y;
  for (const auto& s : p.states) {
    y.xm.push_back(S.get(names::before(s.name, e.id)));
    y.xp.push_back(S.get(names::after(s.name, e.id)));
    y.lm.push_back(S.get(names::before(names::costate(s.name), e.id)));
    y.lp.push_back(S.get(names::after(names::costate(s.name), e.id)));
  }
  for (std::size_t j = 0; j < e.c.size(); ++j) y.nu.push_back(S.get(names::multiplier(e.id, j + 1)));
  y.frac = names::event_fraction(e.id);
  y.t_frac = S.get(y.frac);
  y.epoch = S.get(names::event_time(e.id));
  const std::size_t n = p.states.size();
  for (std::size_t s = 0; s < n; ++s) {
    bool carried = true;
    for (std::size_t k = 0; k < n; ++k)
      if (!(e.map[s].diff(y.xm[k]) - (k == s ? 1 : 0)).expand().is_zero()) carried = false;
    y.carried.push_back(carried);
  }
  return y;
}

// The epoch's fraction of its window, the multipliers of c, the costates leaving that are not
// carried over and the free parameters of psi.
void event_variables(const Problem& p, const InteriorEvent& e, const EventSymbols& y, Shooting& shooting) {
  shooting.variables.push_back(
      {y.frac, "epoch of " + e.id + " as a fraction of its window", "time_fraction", "uniform in (0, 1)"});
  for (std::size_t j = 0; j < y.nu.size(); ++j)
    shooting.variables.push_back(
        multiplier_variable(y.nu[j].get_name(), "multiplier of " + e.id + ": " + e.c_names[j], e.c_inequality[j]));
  for (std::size_t s = 0; s < p.states.size(); ++s)
    if (!y.carried[s])
      shooting.variables.push_back(
          {y.lp[s].get_name(),
           "costate of " + p.states[s].meaning + " just after " + e.id + " (= -multiplier of the state map)",
           "multiplier", "uniform in (-1, 1)"});
  for (const auto& q : e.free_parameters)
    shooting.variables.push_back(
        {q, "free parameter of " + e.id + "'s constraint (found by stationarity)", "parameter", "uniform in (-1, 1)"});
}

// psi = [c ; x+ - g] with its multipliers [nu_c ; -lambda(t+)]; c's rows are equations.
void event_rows(const InteriorEvent& e, const EventSymbols& y, EventConditions& c, Shooting& shooting) {
  for (std::size_t j = 0; j < e.c.size(); ++j) {
    c.psi.push_back(e.c[j]);
    c.multipliers.push_back(y.nu[j].get_name());
    ShootingEquation eq =
        constraint_equation(names::constraint_row(e.id, j + 1), e.c[j], e.kind + " at " + e.id + ": " + e.c_names[j],
                            e.id, y.nu[j], e.c_inequality[j]);
    // A leg alone holds its epoch: at a guess inside the window while the window's bound is
    // inactive, at the bound's edge while it is active (the bound's row is then its multiplier).
    if (e.c[j].has(y.epoch)) {
      eq.alone_expression = y.nu[j];
      if (eq.inequality)
        eq.inequality->held_when_active = Inequality::Held{y.frac, e.c[j].diff(y.epoch).is_equal(-1) ? 0.0 : 1.0};
    }
    shooting.equations.push_back(eq);
  }
  for (std::size_t s = 0; s < y.xp.size(); ++s) {
    c.psi.push_back(y.xp[s] - e.map[s]);
    c.multipliers.push_back("-" + y.lp[s].get_name());
  }
}

// Jump rows: lambda(t-)_s - nu^T dc/dx-_s - sum_k lambda(t+)_k dg_k/dx-_s = 0, solved for a
// carried state's lambda(t+)_s, an equation otherwise.
void jump_conditions(const Problem& p, const InteriorEvent& e, const EventSymbols& y, EventConditions& c,
                     Shooting& shooting) {
  const std::size_t n = p.states.size();
  for (std::size_t s = 0; s < n; ++s) {
    ex rest = y.lm[s];
    for (std::size_t j = 0; j < e.c.size(); ++j) rest -= y.nu[j] * e.c[j].diff(y.xm[s]);
    for (std::size_t k = 0; k < n; ++k)
      if (!y.carried[k] || k != s) rest -= y.lp[k] * e.map[k].diff(y.xm[s]);
    rest = tidy(rest);
    const std::string costate = names::costate(p.states[s].name);
    if (y.carried[s]) {
      c.costate_map.push_back({costate, rest, false});
    } else {
      c.costate_map.push_back({costate, y.lp[s], true});
      shooting.equations.push_back({names::jump_row(e.id, p.states[s].name), rest,
                                    "costate jump at " + e.id + ": " + y.lm[s].get_name() +
                                        " = nu^T dc/dx- + lambda(t+)^T dg/dx- (row " + p.states[s].name + ")",
                                    e.id});
    }
  }
}

// Time: H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0 (the map is evaluated at t + D);
// dc/dt is explicit (the window's bounds) and through the target's motion. A free parameter q
// of psi: nu^T dc/dq + lambda(t+)^T dg/dq = 0.
void epoch_conditions(Problem& p, const InteriorEvent& e, const EventSymbols& y, Shooting& shooting) {
  auto& S = p.symbols;
  const std::size_t n = p.states.size();
  ex time_condition = S.get(names::hamiltonian_before(e.id)) - S.get(names::hamiltonian_after(e.id));
  for (std::size_t j = 0; j < e.c.size(); ++j)
    time_condition += y.nu[j] * (e.c[j].diff(y.epoch) + time_derivative(p, e.c[j]));
  for (std::size_t k = 0; k < n; ++k) time_condition += y.lp[k] * time_derivative(p, e.map[k]);
  shooting.equations.push_back({names::time_row(e.id), tidy(time_condition),
                                "H(t-) - H(t+) + dPhi/dt = 0 at " + e.id + ": its epoch is free", e.id});
  for (const auto& q : e.free_parameters) {
    const symbol par = S.get(q);
    ex st = 0;
    for (std::size_t j = 0; j < e.c.size(); ++j) st += y.nu[j] * e.c[j].diff(par);
    for (std::size_t k = 0; k < n; ++k) st += y.lp[k] * e.map[k].diff(par);
    shooting.equations.push_back({names::stationarity_row(e.id, q), tidy(st),
                                  "dPhi/d" + q + " = 0: " + q + " is a free parameter of psi at " + e.id, e.id});
  }
}

}  // namespace

EventConditions event_conditions(Problem& p, const InteriorEvent& e, Shooting& shooting) {
  const EventSymbols y = event_symbols(p, e);
  event_variables(p, e, y, shooting);
  EventConditions c;
  c.event = e;
  c.time_symbol = names::event_time(e.id);
  c.time = e.window_lo + (e.window_hi - e.window_lo) * y.t_frac;
  event_rows(e, y, c, shooting);
  jump_conditions(p, e, y, c, shooting);
  epoch_conditions(p, e, y, shooting);
  return c;
}

}  // namespace helios::pmp

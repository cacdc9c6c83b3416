#include "helios/pmp/derive.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include "helios/io/schema.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using GiNaC::symbol;
using io::json;
using symbolic::to_text;

struct DirectionLaw {
  std::vector<std::string> controls;
  std::vector<ex> b;          // a* = -b/|b|
  std::vector<ex> law;        // a_j*
  std::vector<ex> gradient;   // g_j = dH/da_j
  std::string costate_block;  // e.g. "l_vx, l_vy, l_vz" if b is that block of costates
};

// The controls of one kind: their names and symbols, in the problem's order.
std::vector<symbol> controls_of_kind(Problem& p, const std::string& kind, std::vector<std::string>& names) {
  std::vector<symbol> symbols;
  for (const auto& c : p.controls)
    if (c.kind == kind) {
      names.push_back(c.name);
      symbols.push_back(p.symbols.get(c.name));
    }
  return symbols;
}

// Minimizes H over a unit vector a that enters H linearly: H = g.a + ..., so a* = -g/|g|.
// When g = k * (block of costates) with one scalar factor k, a* = -block/|block| (primer
// vector); that needs k > 0 on the admissible set, which helios-verify checks numerically (G2).
DirectionLaw direction_law(Problem& p, const ex& H) {
  DirectionLaw d;
  const std::vector<symbol> a = controls_of_kind(p, "direction", d.controls);
  if (a.empty()) return d;
  for (const auto& aj : a) {
    const ex g = H.diff(aj).expand();
    for (const auto& ak : a)
      if (!g.diff(ak).is_zero())
        throw std::invalid_argument("H is not linear in the thrust direction " + aj.get_name());
    d.gradient.push_back(g);
  }
  std::vector<ex> block;
  ex common;
  bool simple = true;
  for (const auto& g : d.gradient) {
    int hits = 0;
    for (const auto& s : p.states) {
      const ex lam = p.symbols.get(costate_name(s.name));
      const ex k = g.coeff(lam, 1);
      if (k.is_zero()) continue;
      ++hits;
      if (block.empty()) common = k;
      if (!(k - common).expand().is_zero() || !(g - k * lam).expand().is_zero()) simple = false;
      block.push_back(lam);
    }
    if (hits != 1) simple = false;
  }
  const bool primer = simple && block.size() == a.size();
  d.b = primer ? block : d.gradient;
  if (primer)
    for (std::size_t i = 0; i < block.size(); ++i) d.costate_block += (i ? ", " : "") + to_text(block[i]);
  ex norm2 = 0;
  for (const auto& b : d.b) norm2 += b * b;
  for (const auto& b : d.b) d.law.push_back(-b / GiNaC::sqrt(norm2));
  return d;
}

// Substitutes a* into H and simplifies b.(-b/|b|) to -|b|.
ex substitute_direction(const ex& H, const DirectionLaw& d, Problem& p) {
  if (d.controls.empty()) return H;
  const symbol norm("helios_direction_norm");
  GiNaC::exmap to_law;
  ex norm2 = 0;
  for (std::size_t j = 0; j < d.controls.size(); ++j) {
    to_law[p.symbols.get(d.controls[j])] = -d.b[j] / norm;
    norm2 += d.b[j] * d.b[j];
  }
  ex Hs = H.subs(to_law).expand();
  // b.b = norm^2: replace the first component's square, so the sum cancels.
  Hs = Hs.subs(GiNaC::pow(d.b[0], 2) == GiNaC::pow(norm, 2) - (norm2 - GiNaC::pow(d.b[0], 2)).expand(),
               GiNaC::subs_options::algebraic)
           .expand();
  return Hs.subs(norm == GiNaC::sqrt(norm2.expand()));
}

// Minimizes H over a sail normal n (|n| = 1, n.rhat >= 0) when the sail adds k (n.rhat)^2 n to
// the velocity: write n = cos(alpha) rhat + sin(alpha) s with s a unit vector normal to rhat.
// H is linear in s with the positive factor k cos^2 sin, so s* = -lv_perp/|lv_perp| (the primer
// vector in the plane normal to rhat), leaving h(alpha) = k cos^2 (A cos - B sin) with
// A = lv.rhat, B = |lv_perp|. h'(alpha) = 0 becomes a polynomial in tan(alpha); its root in
// [0, pi/2] with h'' > 0 is the optimal cone angle. The steps are done on GiNaC, not typed in.
struct SailLaw {
  std::vector<std::string> controls;
  std::vector<std::pair<std::string, ex>> definitions;  // sail_A, sail_B, in order
  ex cone_angle;                                        // alpha*(x, lambda, definitions)
  std::vector<ex> law;  // n* in terms of the cone angle symbol sail_alpha and the definitions
  std::string stationarity;
};

SailLaw sail_law(Problem& p, const ex& H) {
  SailLaw s;
  const std::vector<symbol> n = controls_of_kind(p, "sail_normal", s.controls);
  if (n.size() != 3)
    throw std::invalid_argument("a sail needs three normal components, got " + std::to_string(n.size()));
  const auto& rhat = p.sail.rhat;
  std::vector<ex> lv;
  for (const auto& v : p.sail.velocity) lv.push_back(p.symbols.get(costate_name(v)));
  const ex A = (lv[0] * rhat[0] + lv[1] * rhat[1] + lv[2] * rhat[2]);
  std::vector<ex> perp;
  for (int i = 0; i < 3; ++i) perp.push_back(lv[i] - A * rhat[i]);
  const ex B = GiNaC::sqrt(perp[0] * perp[0] + perp[1] * perp[1] + perp[2] * perp[2]);

  // Stationarity of h(alpha) = cos^2 (a cos - b sin) in t = tan(alpha).
  const symbol al("helios_alpha"), tt("helios_tan"), a("helios_A"), b("helios_B");
  const ex h = GiNaC::pow(GiNaC::cos(al), 2) * (a * GiNaC::cos(al) - b * GiNaC::sin(al));
  const ex dh = h.diff(al).expand().subs(GiNaC::sin(al) == tt * GiNaC::cos(al)).expand();
  const ex poly = (dh / GiNaC::pow(GiNaC::cos(al), 3)).expand().normal().expand();
  if (poly.has(al) || poly.degree(tt) != 2)
    throw std::logic_error("sail law: dh/dalpha is not cos^3 times a quadratic in tan(alpha)");
  const ex c2 = poly.coeff(tt, 2), c1 = poly.coeff(tt, 1), c0 = poly.coeff(tt, 0);
  s.stationarity = to_text(poly.subs(GiNaC::lst{tt == symbol("tan_alpha"), a == symbol("A"), b == symbol("B")})) +
                   " = 0 with A = lambda_v.rhat, B = |lambda_v_perp|";
  // c2 = 2B > 0 and c0 = -B < 0: the roots have opposite signs; the non-negative one,
  // t = -2 c0 / (c1 + sqrt(c1^2 - 4 c2 c0)), written as an angle that stays defined as B -> 0.
  const ex root = GiNaC::atan2(-2 * c0, c1 + GiNaC::sqrt(c1 * c1 - 4 * c2 * c0));
  // Second-order check at sample values: h'' > 0 at the root (a minimum, rule G2).
  for (const auto& [av, bv] : std::vector<std::pair<double, double>>{{-0.7, 0.4}, {0.3, 0.9}, {0.8, 0.05}}) {
    const ex at = root.subs(GiNaC::lst{a == av, b == bv}).evalf();
    const ex second = h.diff(al, 2).subs(GiNaC::lst{a == av, b == bv, al == at}).evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(second) || GiNaC::ex_to<GiNaC::numeric>(second).to_double() <= 0)
      throw std::logic_error("sail law: the root of the stationarity condition is not a minimum");
  }
  // The law is written with named intermediate quantities so it stays readable (and cheap).
  const symbol& A_sym = p.symbols.get("sail_A");
  const symbol& B_sym = p.symbols.get("sail_B");
  const symbol& alpha_sym = p.symbols.get("sail_alpha");
  ex lv2 = 0;
  for (const auto& l : lv) lv2 += l * l;
  s.definitions = {{"sail_A", A}, {"sail_B", GiNaC::sqrt(lv2 - A_sym * A_sym)}};
  s.cone_angle = root.subs(GiNaC::lst{a == A_sym, b == B_sym});
  s.definitions.push_back({"sail_alpha", s.cone_angle});
  for (int i = 0; i < 3; ++i)
    s.law.push_back(GiNaC::cos(alpha_sym) * rhat[i] - GiNaC::sin(alpha_sym) * (lv[i] - A_sym * rhat[i]) / B_sym);
  // The engine's own consistency check: along n*(alpha) the n-dependent part of H is k h(alpha).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> dist(0.2, 1.5);
  for (int trial = 0; trial < 4; ++trial) {
    GiNaC::exmap at;
    for (const auto& sym : symbolic::free_symbols(H)) at[p.symbols.get(sym)] = dist(rng) * (trial % 2 ? -1 : 1);
    for (const auto& nj : n) at[nj] = 0;
    const double alpha = 0.3 + 0.25 * trial;
    GiNaC::exmap on_law = at;
    for (int i = 0; i < 3; ++i) on_law[n[i]] = (std::cos(alpha) * rhat[i] - std::sin(alpha) * perp[i] / B).subs(at);
    const double lhs = GiNaC::ex_to<GiNaC::numeric>((H.subs(on_law) - H.subs(at)).evalf()).to_double();
    const double rhs =
        GiNaC::ex_to<GiNaC::numeric>((p.sail.k * h.subs(GiNaC::lst{al == alpha, a == A, b == B})).subs(at).evalf())
            .to_double();
    if (std::fabs(lhs - rhs) > 1e-10 * (1 + std::fabs(rhs)))
      throw std::logic_error("sail law: H does not have the form k (n.rhat)^2 (lambda_v.n) in the sail normal");
  }
  return s;
}

json named_list(const std::vector<Named>& v, bool with_value) {
  json out = json::array();
  for (const auto& n : v) {
    json e = {{"name", n.name}, {"meaning", n.meaning}, {"unit", n.unit}};
    if (with_value) e["value"] = n.value;
    if (!n.source.empty()) e["source"] = n.source;
    out.push_back(e);
  }
  return out;
}

// The expanded form of e where that is not longer (a swing-by's rotation expands enormously).
ex tidy(const ex& e) {
  const ex expanded = e.expand();
  return to_text(expanded).size() <= to_text(e).size() ? expanded : e;
}

// d e/dt through the time-dependent parameters (a target's state at its event).
ex time_derivative(Problem& p, const ex& e) {
  ex d = 0;
  for (const auto& [name, rate] : p.parameter_rates) d += e.diff(p.symbols.get(name)) * rate;
  return d;
}

double value_of(const Problem& p, const std::string& parameter) {
  for (const auto& q : p.parameters)
    if (q.name == parameter) return q.value;
  throw std::logic_error("no parameter " + parameter);
}

// The shooting variable of a multiplier; a bound's multiplier is 0 while the bound is inactive.
json multiplier_variable(const std::string& name, const std::string& meaning, bool inequality) {
  return {{"name", name},
          {"meaning", meaning + (inequality ? " (a bound: 0 while inactive, >= 0 when active)" : " = 0")},
          {"role", "multiplier"},
          {"scale", 1.0},
          {"init", "uniform in (-1, 1)"}};
}

// The equation psi_j = 0 of a constraint row; a bound psi_j <= 0 is handled in two passes: while
// inactive its multiplier is 0 (the equation is then `multiplier` = 0), when active psi_j = 0.
json constraint_equation(const std::string& name, const std::string& expression, const std::string& meaning,
                         const std::string& source, const std::string& multiplier, bool inequality) {
  json eq = {{"name", name},
             {"expression", expression},
             {"meaning", meaning + (inequality ? ", active: = 0" : " = 0")},
             {"scale", 1.0},
             {"source", source}};
  if (inequality)
    eq["inequality"] = {{"sense", "expression <= 0"},
                        {"multiplier", multiplier},
                        {"inactive_expression", multiplier},
                        {"rule", "pass 1: inactive (multiplier = 0); if the expression is > 0 at the solution, "
                                 "pass 2 makes it active (expression = 0) and requires multiplier >= 0"}};
  return eq;
}

// Conditions of an interior event from Phi = ... + nu_c^T c(t, x-, p) + nu_g^T (x+ - g(t + D, x-, p))
// (Bryson-Ho): lambda(t+) = -dPhi/dx+ = -nu_g; lambda(t-) = dPhi/dx- = nu_c^T dc/dx- + lambda(t+)^T dg/dx-;
// H(t-) - H(t+) + dPhi/dt = 0 for the free epoch; dPhi/dp = 0 for a free parameter p of psi.
// A state the map carries over (dg_s/dx- = e_s) gets lambda(t+) explicitly from its jump row; any
// other state's lambda(t+) is a shooting variable and its jump row an equation.
json interior_event_conditions(Problem& p, const InteriorEvent& e, json& variables, json& equations) {
  auto& S = p.symbols;
  const std::size_t n = p.states.size();
  std::vector<symbol> xm, xp, lm, lp;
  for (const auto& s : p.states) {
    xm.push_back(S.get(before_event(s.name, e.id)));
    xp.push_back(S.get(after_event(s.name, e.id)));
    lm.push_back(S.get(before_event(costate_name(s.name), e.id)));
    lp.push_back(S.get(after_event(costate_name(s.name), e.id)));
  }
  std::vector<symbol> nu;
  for (std::size_t j = 0; j < e.c.size(); ++j) nu.push_back(S.get("nu_" + e.id + "_" + std::to_string(j + 1)));
  const std::string frac = event_time_name(e.id) + "_frac";
  const symbol t_frac = S.get(frac);
  variables.push_back({{"name", frac},
                       {"meaning", "epoch of " + e.id + " as a fraction of its window"},
                       {"role", "time_fraction"},
                       {"scale", 1.0},
                       {"init", "uniform in (0, 1)"}});
  for (std::size_t j = 0; j < nu.size(); ++j)
    variables.push_back(multiplier_variable(nu[j].get_name(), "multiplier of " + e.id + ": " + e.c_names[j],
                                            e.c_inequality[j]));
  std::vector<bool> carried(n);
  for (std::size_t s = 0; s < n; ++s) {
    carried[s] = true;
    for (std::size_t k = 0; k < n; ++k)
      if (!(e.map[s].diff(xm[k]) - (k == s ? 1 : 0)).expand().is_zero()) carried[s] = false;
    if (!carried[s])
      variables.push_back({{"name", lp[s].get_name()},
                           {"meaning", "costate of " + p.states[s].meaning + " just after " + e.id +
                                           " (= -multiplier of the state map)"},
                           {"role", "multiplier"},
                           {"scale", 1.0},
                           {"init", "uniform in (-1, 1)"}});
  }
  for (const auto& q : e.free_parameters)
    variables.push_back({{"name", q},
                         {"meaning", "free parameter of " + e.id + "'s constraint (found by stationarity)"},
                         {"role", "parameter"},
                         {"scale", 1.0},
                         {"init", "uniform in (-1, 1)"}});

  json psi = json::array(), multipliers = json::array(), conditions = json::array();
  const symbol epoch = S.get(event_time_name(e.id));
  for (std::size_t j = 0; j < e.c.size(); ++j) {
    psi.push_back(to_text(e.c[j]));
    multipliers.push_back(nu[j].get_name());
    json eq = constraint_equation("psi_" + e.id + "_" + std::to_string(j + 1), to_text(e.c[j]),
                                  e.kind + " at " + e.id + ": " + e.c_names[j], e.id, nu[j].get_name(),
                                  e.c_inequality[j]);
    // A leg alone holds its epoch: at a guess inside the window while the window's bound is
    // inactive, at the bound's edge while it is active (the bound's row is then its multiplier).
    if (e.c[j].has(epoch)) {
      eq["alone_expression"] = nu[j].get_name();
      eq["inequality"]["held_when_active"] = {{"variable", frac}, {"value", e.c[j].diff(epoch).is_equal(-1) ? 0 : 1}};
    }
    equations.push_back(eq);
  }
  for (std::size_t s = 0; s < n; ++s) {
    psi.push_back(to_text(xp[s] - e.map[s]));
    multipliers.push_back("-" + lp[s].get_name());
  }
  // Jump rows: lambda(t-)_s - nu^T dc/dx-_s - sum_k lambda(t+)_k dg_k/dx-_s = 0.
  json state_map = json::array(), costate_map = json::array();
  for (std::size_t s = 0; s < n; ++s) {
    ex rest = lm[s];
    for (std::size_t j = 0; j < e.c.size(); ++j) rest -= nu[j] * e.c[j].diff(xm[s]);
    for (std::size_t k = 0; k < n; ++k)
      if (!carried[k] || k != s) rest -= lp[k] * e.map[k].diff(xm[s]);
    rest = tidy(rest);
    conditions.push_back(lm[s].get_name() + " = nu^T dc/d" + xm[s].get_name() + " + lambda(t+)^T dg/d" +
                         xm[s].get_name());
    state_map.push_back({{"state", p.states[s].name}, {"expression", to_text(e.map[s])}});
    if (carried[s]) {
      costate_map.push_back({{"costate", costate_name(p.states[s].name)}, {"expression", to_text(rest)}});
    } else {
      costate_map.push_back({{"costate", costate_name(p.states[s].name)}, {"variable", lp[s].get_name()}});
      equations.push_back({{"name", "jump_" + e.id + "_" + p.states[s].name},
                           {"expression", to_text(rest)},
                           {"meaning", "costate jump at " + e.id + ": " + lm[s].get_name() +
                                           " = nu^T dc/dx- + lambda(t+)^T dg/dx- (row " + p.states[s].name + ")"},
                           {"scale", 1.0},
                           {"source", e.id}});
    }
  }
  // Time: H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0 (the map is evaluated at t + D);
  // dc/dt is explicit (the window's bounds) and through the target's motion.
  ex time_condition = S.get("H_" + e.id + "_m") - S.get("H_" + e.id + "_p");
  for (std::size_t j = 0; j < e.c.size(); ++j)
    time_condition += nu[j] * (e.c[j].diff(epoch) + time_derivative(p, e.c[j]));
  for (std::size_t k = 0; k < n; ++k) time_condition += lp[k] * time_derivative(p, e.map[k]);
  equations.push_back({{"name", "time_" + e.id},
                       {"expression", to_text(tidy(time_condition))},
                       {"meaning", "H(t-) - H(t+) + dPhi/dt = 0 at " + e.id + ": its epoch is free"},
                       {"scale", 1.0},
                       {"source", e.id}});
  conditions.push_back("lambda(t+) = -nu_g (the multipliers of x+ - g)");
  conditions.push_back("H(t-) - H(t+) + nu_c^T dc/dt + lambda(t+)^T dg/dt = 0 (free epoch)");
  for (const auto& q : e.free_parameters) {
    const symbol par = S.get(q);
    ex st = 0;
    for (std::size_t j = 0; j < e.c.size(); ++j) st += nu[j] * e.c[j].diff(par);
    for (std::size_t k = 0; k < n; ++k) st += lp[k] * e.map[k].diff(par);
    equations.push_back({{"name", "stationarity_" + e.id + "_" + q},
                         {"expression", to_text(tidy(st))},
                         {"meaning", "dPhi/d" + q + " = 0: " + q + " is a free parameter of psi at " + e.id},
                         {"scale", 1.0},
                         {"source", e.id}});
    conditions.push_back("nu_c^T dc/d" + q + " + lambda(t+)^T dg/d" + q + " = 0");
  }
  const ex t_event = e.window_lo + (e.window_hi - e.window_lo) * t_frac;
  return {{"id", e.id},
          {"kind", e.kind},
          {"target", e.target},
          {"time", {{"symbol", event_time_name(e.id)}, {"window", {e.window_lo, e.window_hi}},
                    {"expression", to_text(t_event)}, {"duration", e.duration}}},
          {"psi", psi},
          {"multipliers", multipliers},
          {"conditions", conditions},
          {"state_map", state_map},
          {"costate_map", costate_map}};
}

}  // namespace

json derive(const Problem& problem) {
  Problem p = problem;  // the symbol table grows while deriving
  auto& S = p.symbols;
  const ex lambda0 = S.get("lambda0");
  const ex eps = S.get("eps");

  // H = lambda0 L + lambda^T f
  ex H = lambda0 * p.running_cost;
  for (std::size_t i = 0; i < p.states.size(); ++i) H += S.get(costate_name(p.states[i].name)) * p.f[i];

  json state_odes = json::array(), costate_odes = json::array();
  for (const auto& s : p.states) {
    const symbol x = S.get(s.name), lam = S.get(costate_name(s.name));
    state_odes.push_back({{"state", s.name}, {"rhs", to_text(H.diff(lam))}});
    costate_odes.push_back({{"costate", costate_name(s.name)}, {"rhs", to_text((-H.diff(x)).expand())}});
  }

  // Control law: direction first (independent of the throttle), then the throttle; a sail's
  // normal has its own law.
  json control = json::object();
  const DirectionLaw dir = direction_law(p, H);
  const ex Hstar = substitute_direction(H, dir, p);
  if (!dir.controls.empty()) {
    json direction = json::object();
    direction["controls"] = dir.controls;
    json law = json::array();
    for (const auto& l : dir.law) law.push_back(to_text(l));
    direction["law"] = law;
    json gradient = json::array();
    for (const auto& g : dir.gradient) gradient.push_back(to_text(g));
    direction["dH_da"] = gradient;
    direction["reason"] = dir.costate_block.empty()
                              ? "H is linear in the unit vector a, so a* = -g/|g| with g = dH/da minimizes it"
                              : "H is linear in the unit vector a with dH/da = k*(" + dir.costate_block +
                                    "), k > 0: a* = -lambda/|lambda| (primer vector) minimizes it";
    control["direction"] = direction;
  }
  const bool has_sail =
      std::any_of(p.controls.begin(), p.controls.end(), [](const Control& c) { return c.kind == "sail_normal"; });
  if (has_sail) {
    const SailLaw sail = sail_law(p, H);
    json law = json::array();
    for (const auto& l : sail.law) law.push_back(to_text(l));
    json definitions = json::array();
    for (const auto& [name, e] : sail.definitions) definitions.push_back({{"name", name}, {"expression", to_text(e)}});
    control["sail"] = {
        {"controls", sail.controls},
        {"definitions", definitions},
        {"cone_angle", to_text(sail.cone_angle)},
        {"law", law},
        {"stationarity", sail.stationarity},
        {"admissible", "|n| = 1, n.rhat >= 0 (the sail cannot push toward the Sun)"},
        {"reason",
         "n = cos(alpha) rhat + sin(alpha) s: H is linear in the unit vector s normal to rhat, so s* = "
         "-lambda_v_perp/|lambda_v_perp|; then dH/dalpha = 0 is a quadratic in tan(alpha) whose non-negative root "
         "minimizes H on [0, pi/2]"}};
  }

  const auto throttle_control =
      std::find_if(p.controls.begin(), p.controls.end(), [](const Control& c) { return c.kind == "throttle"; });
  if (throttle_control != p.controls.end()) {
    const symbol u = S.get(throttle_control->name);
    const ex dHdu = Hstar.diff(u).expand();
    if (!dHdu.diff(u, 2).is_zero())
      throw std::invalid_argument("H is not quadratic in the throttle " + throttle_control->name);
    const ex S0 = dHdu.subs(u == 0).expand();
    const ex S1 = dHdu.subs(u == 1).expand();
    const ex switching = S0.subs(eps == 0).expand();
    json throttle = json::object();
    throttle["control"] = throttle_control->name;
    throttle["bounds"] = json::array({0, 1});
    throttle["switching_function"] = to_text(switching);
    throttle["dH_du_at_lower"] = to_text(S0);
    throttle["dH_du_at_upper"] = to_text(S1);
    throttle["d2H_du2"] = to_text(dHdu.diff(u).expand());
    const ex span = (S0 - S1).expand();
    throttle["interior"] = span.is_zero() ? "0" : to_text((S0 / span).expand());
    throttle["smoothing"] = H.has(eps) ? "quadratic" : "none";
    throttle["law"] =
        "u = 0 where dH_du_at_lower >= 0, u = 1 where dH_du_at_upper <= 0, otherwise u = interior (dH/du = 0); "
        "at eps = 0: u = 1 if switching_function < 0 else 0 (bang-bang)";
    control["throttle"] = throttle;
  }

  // Endpoint conditions. Initial: fixed states have free costates (shooting variables);
  // free states would get lambda(t0) = -dPhi/dx(t0). Final: lambda(tf) = lambda0 dphi/dx + nu^T dpsi/dx.
  std::set<std::string> fixed_at_t0;
  json initial_values = json::array();
  json constraints = json::array();
  json equations = json::array();
  json variables = json::array();
  variables.push_back({{"name", "lambda0"},
                       {"meaning", "cost multiplier lambda0 (>= 0)"},
                       {"scale", 1.0},
                       {"init", "uniform in (0, 1), then the whole vector normalized"}});
  GiNaC::exmap at_tf;
  for (const auto& s : p.states) at_tf[S.get(s.name)] = S.get(at_event(s.name, "tf"));
  const symbol H_tf = S.get("H_tf");
  ex time_condition = H_tf + lambda0 * p.endpoint_cost.diff(S.get("t"));  // H(tf) + dPhi/dtf, nu added below
  ex departure_condition = 0;  // -H(t0) + dPhi/dt0 for a sliding departure
  bool final_constraint = false;
  for (const auto& k : p.constraints) {
    json c = {{"id", k.id}, {"kind", k.kind}, {"at", k.at}, {"target", k.target}};
    json psi = json::array();
    for (std::size_t i = 0; i < k.psi.size(); ++i) psi.push_back(to_text(k.psi[i]));
    c["psi"] = psi;
    json multipliers = json::array();
    for (std::size_t i = 0; i < k.psi.size(); ++i) multipliers.push_back("nu_" + k.id + "_" + std::to_string(i + 1));
    c["multipliers"] = multipliers;
    if (k.at == "t0") {
      // psi(x(t0)) = 0 solved for the states it fixes gives the initial values.
      GiNaC::lst eqs, unknowns;
      for (const auto& e : k.psi) eqs.append(e == 0);
      for (const auto& s : k.fixed_states) {
        fixed_at_t0.insert(s);
        unknowns.append(S.get(s));
      }
      const ex solved = GiNaC::lsolve(eqs, unknowns);
      if (solved.nops() != k.fixed_states.size())
        throw std::invalid_argument("constraint '" + k.id + "' does not determine the initial state it fixes");
      for (const auto& r : solved) initial_values.push_back({{"state", to_text(r.lhs())}, {"value", to_text(r.rhs())}});
      c["conditions"] = json::array({"x(t0) is fixed for " + std::to_string(k.fixed_states.size()) +
                                     " states, so their costates at t0 are free (shooting variables)"});
      if (p.free_departure) {
        // lambda(t0) = -nu^T dpsi/dx(t0) gives nu; the sliding t0 adds -H(t0) + nu^T dpsi/dt0.
        GiNaC::lst rows, nus;
        for (const auto& m : multipliers) nus.append(S.get(m.get<std::string>()));
        for (const auto& s : k.fixed_states) {
          ex row = S.get(at_event(costate_name(s), "t0"));
          for (std::size_t j = 0; j < k.psi.size(); ++j)
            row += S.get(multipliers[j].get<std::string>()) * k.psi[j].diff(S.get(s));
          rows.append(row == 0);
        }
        const ex nu = GiNaC::lsolve(rows, nus);
        if (nu.nops() != nus.nops())
          throw std::invalid_argument("constraint '" + k.id + "': its multipliers are not determined by lambda(t0)");
        GiNaC::exmap nu_value;
        for (const auto& r : nu) nu_value[r.lhs()] = r.rhs();
        departure_condition = -S.get("H_t0");
        for (std::size_t j = 0; j < k.psi.size(); ++j)
          departure_condition += S.get(multipliers[j].get<std::string>()).subs(nu_value) * k.psi_t[j];
        c["time_condition"] = "-H(t0) + nu^T dpsi/dt0, added to the final time's terms (tf = t0 + tof)";
      }
    } else {
      // lambda(tf) - lambda0 dphi/dx - nu^T dpsi/dx = 0; the multipliers of the equality rows are
      // solved from the rows of the states they fix (dpsi/dx_J invertible), the other rows remain.
      // A bound's multiplier is a shooting variable (0 while the bound is inactive).
      if (final_constraint) throw std::invalid_argument("constraint '" + k.id + "': only one constraint at tf");
      final_constraint = true;
      json conditions = json::array();
      json eliminated = json::array();
      GiNaC::lst touched_rows, nus;
      for (std::size_t j = 0; j < k.psi.size(); ++j) {
        if (!k.psi_inequality[j]) {
          nus.append(S.get(multipliers[j].get<std::string>()));
          continue;
        }
        variables.push_back(multiplier_variable(multipliers[j], "multiplier of " + k.id + ": " + k.psi_names[j], true));
      }
      std::map<std::string, ex> free_end;  // lambda_s(tf) - lambda0 dphi/dx_s: the row without psi
      for (std::size_t i = 0; i < p.states.size(); ++i) {
        const symbol x = S.get(p.states[i].name);
        ex row = S.get(at_event(costate_name(p.states[i].name), "tf")) - lambda0 * p.endpoint_cost.diff(x);
        free_end[p.states[i].name] = row.subs(at_tf);
        bool touched = false, bounded = false;
        for (std::size_t j = 0; j < k.psi.size(); ++j) {
          const ex d = k.psi[j].diff(x);
          if (d.is_zero()) continue;
          (k.psi_inequality[j] ? bounded : touched) = true;
          row -= S.get(multipliers[j].get<std::string>()) * d;
        }
        conditions.push_back(to_text(row) + " = 0");
        if (touched) {
          eliminated.push_back(to_text(row) + " = 0");
          touched_rows.append(row.subs(at_tf) == 0);
        } else {
          const std::string& n = p.states[i].name;
          equations.push_back(
              {{"name", "transversality_" + n},
               {"expression", to_text(row.subs(at_tf))},
               {"meaning", bounded ? "lambda_" + n + "(tf) = nu^T dpsi/d" + n + ": " + n + "(tf) is free but for a bound"
                                   : "lambda_" + n + "(tf) = 0: " + n + "(tf) is free"},
               {"scale", 1.0},
               {"source", k.id}});
        }
      }
      c["conditions"] = conditions;
      c["eliminated_multipliers"] = eliminated;
      for (std::size_t j = 0; j < k.psi.size(); ++j) {
        json eq = constraint_equation("psi_" + k.id + "_" + std::to_string(j + 1), to_text(k.psi[j].subs(at_tf)),
                                      k.kind + " at tf with " + k.id + ": " + k.psi_names[j], k.id,
                                      multipliers[j], k.psi_inequality[j]);
        // A state free at t0 is held at its guess while the last leg is solved alone, so the row
        // fixing it at tf gives way to that leg's free-end condition.
        if (p.free_initial_mass && !k.psi_inequality[j] && k.psi[j].has(S.get("m")))
          eq["alone_expression"] = to_text(free_end.at("m"));
        equations.push_back(eq);
      }
      if (p.free_final_time || p.free_departure) {
        // H(tf) + dPhi/dtf = 0 with Phi = lambda0 phi + nu^T psi: nu^T dpsi/dtf through the target's
        // motion, nu taken from the rows it was eliminated with.
        const ex nu = GiNaC::lsolve(touched_rows, nus);
        if (nu.nops() != nus.nops())
          throw std::invalid_argument("constraint '" + k.id + "': its multipliers are not determined by lambda(tf)");
        GiNaC::exmap nu_value;
        for (const auto& r : nu) nu_value[r.lhs()] = r.rhs();
        for (std::size_t j = 0; j < k.psi.size(); ++j)
          time_condition += S.get(multipliers[j].get<std::string>()).subs(nu_value) * k.psi_t[j].subs(at_tf);
        c["time_condition"] = "H(tf) + lambda0*dphi/dtf + nu^T dpsi/dtf = 0 (tf free)";
      }
    }
    constraints.push_back(c);
  }
  if (p.free_departure) {
    if (!final_constraint) throw std::invalid_argument("a sliding departure needs a constraint at tf");
    variables.push_back({{"name", "t0_frac"},
                         {"meaning", "departure epoch as a fraction of its window: t0 = t0_min + (t0_max - t0_min)*t0_frac"},
                         {"role", "time_fraction"},
                         {"scale", 1.0},
                         {"init", "uniform in (0, 1)"}});
    equations.push_back({{"name", "transversality_t0"},
                         {"expression", to_text((departure_condition + time_condition).expand())},
                         {"meaning",
                          "-H(t0) + dPhi/dt0 + H(tf) + dPhi/dtf = 0: t0 slides and tf = t0 + tof moves with it"},
                         {"scale", 1.0},
                         {"source", "departure"}});
  }
  if (p.free_final_time) {
    if (!final_constraint) throw std::invalid_argument("a free final time needs a constraint at tf");
    variables.push_back({{"name", "tf_frac"},
                         {"meaning", "final time as a fraction of its window: tf = tf_min + (tf_max - tf_min)*tf_frac"},
                         {"role", "time_fraction"},
                         {"scale", 1.0},
                         {"init", "uniform in (0, 1)"}});
    equations.push_back({{"name", "transversality_tf"},
                         {"expression", to_text(time_condition.expand())},
                         {"meaning", "H(tf) + dPhi/dtf = 0: the final time is free"},
                         {"scale", 1.0},
                         {"source", "final_time"}});
  }
  json events = json::array();
  for (const auto& e : p.events) events.push_back(interior_event_conditions(p, e, variables, equations));
  // Order: endpoint constraints first, then transversality, then the normalization.
  std::stable_sort(equations.begin(), equations.end(), [](const json& a, const json& b) {
    return a["name"].get<std::string>().rfind("psi_", 0) == 0 && b["name"].get<std::string>().rfind("psi_", 0) != 0;
  });
  ex norm2 = GiNaC::pow(lambda0, 2);
  for (const auto& s : p.states) {
    const std::string lam0 = at_event(costate_name(s.name), "t0");
    if (fixed_at_t0.count(s.name)) {
      variables.push_back({{"name", lam0},
                           {"meaning", "costate of " + s.meaning + " at t0"},
                           {"scale", 1.0},
                           {"init", "uniform in (-1, 1), then normalized"}});
      norm2 += GiNaC::pow(S.get(lam0), 2);
    } else if (s.name == "m" && p.free_initial_mass) {
      // Minimum initial mass: m(t0) is a shooting variable, and with no cost on it (the running
      // cost is the fuel) its transversality is lambda_m(t0) = -dPhi/dm(t0) = 0.
      const double most = p.final_mass + value_of(p, "Tmax") / value_of(p, "c") * (p.tf - p.t0);
      variables.push_back({{"name", at_event(s.name, "t0")},
                           {"meaning", "initial mass (free: minimized)"},
                           {"role", "initial_state"},
                           {"scale", 1.0},
                           {"range", {p.final_mass, most}},
                           {"init", "uniform in (final mass, final mass + Tmax (tf - t0)/c)"}});
      initial_values.push_back({{"state", s.name}, {"value", at_event(s.name, "t0")}});
      variables.push_back({{"name", lam0},
                           {"meaning", "costate of " + s.meaning + " at t0"},
                           {"scale", 1.0},
                           {"init", "uniform in (-1, 1), then normalized"}});
      norm2 += GiNaC::pow(S.get(lam0), 2);
      equations.push_back({{"name", "transversality_" + s.name + "_t0"},
                           {"expression", lam0},
                           {"meaning", "lambda_m(t0) = -dPhi/dm(t0) = 0: the initial mass is free"},
                           {"scale", 1.0},
                           {"source", "initial_mass"}});
    } else {
      throw std::invalid_argument("state " + s.name + " is free at t0: not supported by the builtin engine yet");
    }
  }
  // lambda0 and lambda(t0) first (the sphere), then the events' variables, then the time fractions.
  const auto rank = [&](const json& v) {
    if (norm2.has(S.get(v["name"].get<std::string>()))) return 0;
    return v.value("role", "") == "time_fraction" ? 2 : 1;
  };
  std::stable_sort(variables.begin(), variables.end(),
                   [&](const json& a, const json& b) { return rank(a) < rank(b); });
  equations.push_back({{"name", "normalization"},
                       {"expression", to_text(GiNaC::sqrt(norm2) - 1)},
                       {"meaning", "|(lambda0, lambda(t0))| = 1 (lambda0 inside the sphere normalization)"},
                       {"scale", 1.0},
                       {"source", "normalization"}});

  json doc = io::artifact_header("derivation", "helios-derive", "builtin");
  doc["problem"] = {{"id", p.id},
                    {"dynamics_model", p.dynamics_model},
                    {"objective", p.objective},
                    {"perturbations", p.perturbations}};
  doc["units"] = units_of(p);
  doc["times"] = times_of(p);
  json states = named_list(p.states, false);
  for (auto& s : states) s["costate"] = costate_name(s["name"].get<std::string>());
  doc["states"] = states;
  json controls = json::array();
  for (const auto& c : p.controls) controls.push_back({{"name", c.name}, {"meaning", c.meaning}, {"kind", c.kind}});
  doc["controls"] = controls;
  doc["parameters"] = named_list(p.parameters, true);
  if (H.has(eps))
    doc["homotopy"] = {
        {"symbol", "eps"},
        {"start", 1.0},
        {"end", 0.0},
        {"meaning", "quadratic smoothing of the throttle: eps = 1 energy-like, eps = 0 fuel-optimal bang-bang"}};
  else
    doc["homotopy"] = {{"symbol", "eps"},
                       {"start", 0.0},
                       {"end", 0.0},
                       {"meaning", "none: H does not contain eps (no smoothing is needed or used)"}};
  doc["multiplier"] = "lambda0";
  json rhs = json::array();
  for (const auto& fi : p.f) rhs.push_back(to_text(fi));
  doc["dynamics"] = {
      {"state_rhs", rhs}, {"running_cost", to_text(p.running_cost)}, {"endpoint_cost", to_text(p.endpoint_cost)}};
  const bool coasting = std::any_of(p.parameters.begin(), p.parameters.end(),
                                    [](const Named& q) { return q.source.rfind("coast:", 0) == 0; });
  if (coasting) {
    json coast = json::array();
    for (const auto& fi : p.coast_f) coast.push_back(to_text(fi));
    doc["coast_dynamics"] = {{"states", {"rx", "ry", "rz", "vx", "vy", "vz"}}, {"rhs", coast}};
  }
  json event_values = json::array();
  const auto hamiltonian_at = [&](const std::string& at, const std::string& meaning) {
    event_values.push_back({{"name", "H_" + at},
                            {"kind", "hamiltonian"},
                            {"at", at},
                            {"meaning", "H " + meaning + " with the optimal control (the runtime evaluates it)"}});
  };
  if (p.free_departure) hamiltonian_at("t0", "at t0");
  for (const auto& e : p.events) {
    hamiltonian_at(e.id + "_m", "just before " + e.id);
    hamiltonian_at(e.id + "_p", "just after " + e.id + (e.duration > 0 ? " (at the end of the stay)" : ""));
  }
  if (p.free_final_time || p.free_departure) hamiltonian_at("tf", "at tf");
  if (!event_values.empty()) doc["event_values"] = event_values;
  if (!p.orbit_bodies.empty()) {
    json bodies = json::array();
    for (const auto& b : p.orbit_bodies)
      bodies.push_back({{"name", b.name},
                        {"model", "kepler"},
                        {"epoch", b.epoch},
                        {"elements",
                         {{"a", b.elements.a},
                          {"e", b.elements.e},
                          {"i_rad", b.elements.i},
                          {"raan_rad", b.elements.raan},
                          {"argp_rad", b.elements.argp},
                          {"mean_anomaly_rad", b.elements.mean_anomaly}}},
                        {"meaning", "Keplerian orbit about the central body (normalized a and epoch)"}});
    doc["bodies"] = bodies;
  }
  if (!events.empty()) doc["events"] = events;
  doc["hamiltonian"] = to_text(H);
  doc["state_odes"] = state_odes;
  doc["costate_odes"] = costate_odes;
  doc["control_law"] = control;
  doc["initial_values"] = initial_values;
  doc["constraints"] = constraints;
  doc["shooting"] = {{"variables", variables}, {"equations", equations}};
  return doc;
}

json units_of(const Problem& p) {
  return {{"length", p.units.length_name},
          {"length_km", p.units.length_km},
          {"time", p.units.time_name},
          {"time_s", p.units.time_s},
          {"mass_kg", p.units.mass_kg}};
}

json times_of(const Problem& p) {
  json times;
  if (p.free_final_time) {
    const GiNaC::symbol tf_frac("tf_frac");
    times = {{"t0", p.t0},
             {"final_time", "free"},
             {"tf_window", {p.tf_min, p.tf}},
             {"tf_expression", to_text(p.tf_min + (p.tf - p.tf_min) * tf_frac)}};
  } else {
    times = {{"t0", p.t0}, {"tf", p.tf}, {"final_time", "fixed"}};
  }
  if (p.free_departure) {
    // The departure slides in its window; the total time of flight stays fixed.
    const GiNaC::symbol t0_frac("t0_frac");
    const GiNaC::ex t0 = p.t0_min + (p.t0_max - p.t0_min) * t0_frac;
    times["departure"] = "free";
    times["t0_window"] = {p.t0_min, p.t0_max};
    times["t0_expression"] = to_text(t0);
    times["tf_expression"] = to_text(t0 + (p.tf - p.t0));
  }
  if (p.has_epoch) times["epoch_mjd2000"] = p.epoch_mjd2000;
  return times;
}

json derive_from_spec(const json& spec) {
  return derive(build_problem(spec));
}

}  // namespace helios::pmp

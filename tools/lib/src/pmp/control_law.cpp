// The optimal control law: H minimized over the controls (Pontryagin's minimum principle), each
// kind of control by its own law; the laws are derived on GiNaC and checked, not typed in.
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "conditions.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using GiNaC::symbol;
using symbolic::to_text;

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
// `b` is the vector a* points against: the block of costates, or g.
DirectionLaw direction_law(Problem& p, const ex& H, std::vector<ex>& b) {
  DirectionLaw d;
  const std::vector<symbol> a = controls_of_kind(p, "direction", d.controls);
  if (a.empty()) return d;
  for (const auto& aj : a) {
    const ex g = H.diff(aj).expand();
    for (const auto& ak : a)
      if (!g.diff(ak).is_zero())
        throw std::invalid_argument("H is not linear in the thrust direction " + aj.get_name());
    d.dH_da.push_back(g);
  }
  std::vector<ex> block;
  ex common;
  bool simple = true;
  for (const auto& g : d.dH_da) {
    int hits = 0;
    for (const auto& s : p.states) {
      const ex lam = p.symbols.get(names::costate(s.name));
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
  b = primer ? block : d.dH_da;
  std::string costate_block;  // e.g. "l_vx, l_vy, l_vz"
  if (primer)
    for (std::size_t i = 0; i < block.size(); ++i) costate_block += (i ? ", " : "") + to_text(block[i]);
  d.reason = primer ? "H is linear in the unit vector a with dH/da = k*(" + costate_block +
                          "), k > 0: a* = -lambda/|lambda| (primer vector) minimizes it"
                    : "H is linear in the unit vector a, so a* = -g/|g| with g = dH/da minimizes it";
  ex norm2 = 0;
  for (const auto& bj : b) norm2 += bj * bj;
  for (const auto& bj : b) d.law.push_back(-bj / GiNaC::sqrt(norm2));
  return d;
}

// Substitutes a* into H and simplifies b.(-b/|b|) to -|b|.
ex substitute_direction(const ex& H, const std::vector<std::string>& controls, const std::vector<ex>& b, Problem& p) {
  if (controls.empty()) return H;
  const symbol norm("helios_direction_norm");
  GiNaC::exmap to_law;
  ex norm2 = 0;
  for (std::size_t j = 0; j < controls.size(); ++j) {
    to_law[p.symbols.get(controls[j])] = -b[j] / norm;
    norm2 += b[j] * b[j];
  }
  ex Hs = H.subs(to_law).expand();
  // b.b = norm^2: replace the first component's square, so the sum cancels.
  Hs = Hs.subs(GiNaC::pow(b[0], 2) == GiNaC::pow(norm, 2) - (norm2 - GiNaC::pow(b[0], 2)).expand(),
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
SailLaw sail_law(Problem& p, const ex& H) {
  SailLaw s;
  const std::vector<symbol> n = controls_of_kind(p, "sail_normal", s.controls);
  if (n.size() != 3)
    throw std::invalid_argument("a sail needs three normal components, got " + std::to_string(n.size()));
  const auto& rhat = p.sail.rhat;
  std::vector<ex> lv;
  for (const auto& v : p.sail.velocity) lv.push_back(p.symbols.get(names::costate(v)));
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
  s.admissible = "|n| = 1, n.rhat >= 0 (the sail cannot push toward the Sun)";
  s.reason =
      "n = cos(alpha) rhat + sin(alpha) s: H is linear in the unit vector s normal to rhat, so s* = "
      "-lambda_v_perp/|lambda_v_perp|; then dH/dalpha = 0 is a quadratic in tan(alpha) whose non-negative root "
      "minimizes H on [0, pi/2]";
  return s;
}

// Minimizes H* (H with the direction's law) over a throttle u in [0, 1]: H* is at most
// quadratic in u, so u* is a bound or the root of dH/du = 0.
ThrottleLaw throttle_law(Problem& p, const Control& throttle, const ex& Hstar) {
  const symbol u = p.symbols.get(throttle.name);
  const ex eps = p.symbols.get("eps");
  const ex dHdu = Hstar.diff(u).expand();
  if (!dHdu.diff(u, 2).is_zero()) throw std::invalid_argument("H is not quadratic in the throttle " + throttle.name);
  ThrottleLaw t;
  t.control = throttle.name;
  t.dH_du_at_lower = dHdu.subs(u == 0).expand();
  t.dH_du_at_upper = dHdu.subs(u == 1).expand();
  t.switching_function = t.dH_du_at_lower.subs(eps == 0).expand();
  t.d2H_du2 = dHdu.diff(u).expand();
  const ex span = (t.dH_du_at_lower - t.dH_du_at_upper).expand();
  t.interior = span.is_zero() ? ex(0) : (t.dH_du_at_lower / span).expand();
  t.law =
      "u = 0 where dH_du_at_lower >= 0, u = 1 where dH_du_at_upper <= 0, otherwise u = interior (dH/du = 0); "
      "at eps = 0: u = 1 if switching_function < 0 else 0 (bang-bang)";
  return t;
}

}  // namespace

// The direction first (independent of the throttle), then a sail's normal, then the throttle.
ControlLaw control_law(Problem& p, const ex& H) {
  ControlLaw law;
  std::vector<ex> b;
  DirectionLaw direction = direction_law(p, H, b);
  const ex Hstar = substitute_direction(H, direction.controls, b, p);
  if (!direction.controls.empty()) law.direction = std::move(direction);
  const auto of_kind = [&](const std::string& kind) {
    return std::find_if(p.controls.begin(), p.controls.end(), [&](const Control& c) { return c.kind == kind; });
  };
  if (of_kind("sail_normal") != p.controls.end()) law.sail = sail_law(p, H);
  const auto throttle = of_kind("throttle");
  if (throttle != p.controls.end()) law.throttle = throttle_law(p, *throttle, Hstar);
  return law;
}

}  // namespace helios::pmp

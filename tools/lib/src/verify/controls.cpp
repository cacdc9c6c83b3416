// The Hamiltonian, the state and costate ODEs and the control laws (direction, sail, throttle),
// each recomputed from the problem statement and compared with the derivation's claims.
#include "family.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include "helios/symbolic/expr.hpp"
#include "sail.hpp"

namespace helios::verify::detail {
namespace {

constexpr int kRandomDirections = 48;   // random unit vectors tried against a* at each point
constexpr int kRandomSailNormals = 64;  // random admissible sail normals tried against n* at each point
const char* const kAdmissibleSet = "the admissible hemisphere |n| = 1, n.r_hat >= 0";

class ControlFamily : public Family {
 public:
  using Family::Family;

  std::vector<Check> run() override {
    check_intermediate_partials();
    check_hamiltonian();
    check_odes(true);
    check_odes(false);
    check_direction();
    check_sail();
    check_throttle();
    return std::move(checks);
  }

 private:
  // a* for the exact throttle checks: the default of the context, the derivation's own law once verified.
  std::vector<ex> direction_law = ctx.direction_law;
  // The intermediates named as a partial (dQ_dx) that are not one.
  std::set<std::string> wrong_partials;

  // An intermediate named as another's partial in a state (names::partial: dP_in_drx) must be that
  // partial: a wrong one fails its own check, so the costate row that names it is not the only
  // thing the feedback points at (both are compared with everything substituted).
  void check_intermediate_partials() {
    const auto& list = ctx.doc.intermediate_list;
    for (std::size_t k = 0; k < list.size(); ++k)
      for (std::size_t j = 0; j < k; ++j)
        for (const auto& x : ctx.states) {
          if (list[k].name != derivation::names::partial(list[j].name, x)) continue;
          const ex of = ctx.statement(list[j].name, "intermediates[" + list[j].name + "]");
          const ex expected = of.diff(GiNaC::ex_to<symbol>(ctx.sym(x)));
          Check c = equality("intermediate:" + list[k].name, "intermediates", "intermediates[" + list[k].name + "]",
                             "d" + list[j].name + "/d" + x, {expected, ctx.compile(expected), {}},
                             list[k].expression.text, false);
          if (!c.pass) wrong_partials.insert(list[k].name);
          checks.push_back(c);
        }
  }

  void check_hamiltonian() {
    const std::string sum =
        join(std::vector<std::string>{ctx.multiplier + "*running_cost", "sum of costate*state_rhs"}, " + ");
    checks.push_back(equality("hamiltonian", "hamiltonian", "hamiltonian", sum,
                              {ctx.hamiltonian, ctx.hamiltonian_compiled, {}}, ctx.doc.hamiltonian.text, true));
  }

  // State ODEs (dH/dl_i) or costate ODEs (-dH/dx_i), one per state, in state order.
  void check_odes(bool state) {
    const std::string field = state ? "state_odes" : "costate_odes", key = state ? "state" : "costate";
    const std::vector<derivation::Ode>& list = state ? ctx.doc.state_odes : ctx.doc.costate_odes;
    std::set<std::string> known;
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      const std::string name = state ? ctx.states[i] : ctx.costates[i];
      known.insert(name);
      const std::string by = state ? ctx.costates[i] : ctx.states[i];
      const ex expected = state ? ctx.hamiltonian.diff(GiNaC::ex_to<symbol>(ctx.sym(by)))
                                : (-ctx.hamiltonian.diff(GiNaC::ex_to<symbol>(ctx.sym(by)))).expand();
      const std::string expected_name = std::string(state ? "dH/d" : "-dH/d") + by;
      const std::string id = std::string(state ? "state_ode:" : "costate_ode:") + name;
      const std::string category = state ? "state_odes" : "costate_odes";
      const derivation::Ode* entry = nullptr;
      std::string order;
      if (i < list.size() && list[i].name == name) {
        entry = &list[i];
      } else {
        for (std::size_t k = 0; k < list.size() && !entry; ++k)
          if (list[k].name == name) {
            entry = &list[k];
            order = field + "[" + std::to_string(k) + "] is the equation of " + name + " but must be entry " +
                    std::to_string(i) + " (the order of states)";
          }
      }
      if (!entry) {
        Check c = start(id, category, "random_points+exact");
        c.max_rel = 2;
        c.fail(field + " has no equation for " + name + ": expected " + expected_name + " = " + print(expected) + ".");
        checks.push_back(c);
        continue;
      }
      const std::string& given_text = entry->rhs.text;
      // A right-hand side with the optimal control substituted (no control symbols left) is
      // compared with the expected one at the verifier's own optimal controls: at the optimum
      // both are the same function (envelope theorem).
      std::function<Point(const Point&)> at;
      ex given;
      bool parsed = false;
      try {
        given = ctx.statement(given_text, field + "[" + name + "]");
        parsed = true;
      } catch (const std::exception&) {
      }
      if (parsed) {
        bool dropped = false, throttle_dropped = false;
        for (const auto* list : {&ctx.directions, &ctx.sails})
          for (const auto& u : *list) dropped = dropped || (expected.has(ctx.sym(u)) && !given.has(ctx.sym(u)));
        if (!ctx.throttle.empty())
          throttle_dropped = expected.has(ctx.sym(ctx.throttle)) && !given.has(ctx.sym(ctx.throttle));
        if (dropped || throttle_dropped)
          at = [this, throttle_dropped](const Point& p) { return ctx.optimal_controls(p, throttle_dropped); };
      }
      Check c = equality(id, category, field + "[" + name + "]", expected_name, {expected, ctx.compile(expected), at},
                         given_text, true);
      if (!c.pass && !state && parsed && !at && c.feedback.find("whole expression is flipped") == std::string::npos) {
        const std::string j = jacobian_diagnosis(i, given);
        if (!j.empty()) c.feedback += " " + j;
      }
      if (!c.pass) {
        std::vector<std::string> named;
        for (const auto& id : symbolic::identifiers(given_text))
          if (wrong_partials.count(id) && std::find(named.begin(), named.end(), id) == named.end()) named.push_back(id);
        if (!named.empty())
          c.feedback += " It names " + join(named, ", ") +
                        (named.size() == 1 ? ", which fails its own check (intermediates): correct it first."
                                           : ", which fail their own checks (intermediates): correct them first.");
      }
      if (!order.empty() && c.pass) c.fail(order + ".");
      checks.push_back(c);
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string& name = list[k].name;
      if (known.count(name)) continue;
      Check c =
          start(std::string(state ? "state_ode:" : "costate_ode:") + (name.empty() ? "#" + std::to_string(k) : name),
                state ? "state_odes" : "costate_odes", "structural");
      c.fail(field + "[" + std::to_string(k) + "] is for '" + name + "', which is not a " + key +
             " of this problem; remove it.");
      checks.push_back(c);
    }
  }

  // Which block of -dH/dx_i = -lambda0 dL/dx_i - sum_j lambda_j df_j/dx_i a wrong costate
  // equation gets wrong: its coefficient of each multiplier against the Jacobian entry.
  std::string jacobian_diagnosis(std::size_t i, const ex& given) const {
    const symbol& x = GiNaC::ex_to<symbol>(ctx.sym(ctx.states[i]));
    std::vector<std::string> parts;
    for (std::size_t j = 0; j <= ctx.states.size(); ++j) {
      const bool cost = j == ctx.states.size();
      const std::string lname = cost ? ctx.multiplier : ctx.costates[j];
      const symbol& l = GiNaC::ex_to<symbol>(ctx.sym(lname));
      const ex want = -(cost ? ctx.running_cost : ctx.state_rhs[j]).diff(x), got = given.diff(l);
      const Compiled wc = ctx.compile(want), gc = ctx.compile(got);
      double worst = 0;
      for (const auto& p : ctx.points) worst = std::max(worst, rel_diff(wc(p), gc(p)));
      if (worst <= 1e-7) continue;
      const std::string entry = cost ? "dynamics.running_cost" : "dynamics.state_rhs[" + ctx.states[j] + "]";
      const ex miss = tidy((want - got).expand());
      const std::string miss_text = print(miss);
      std::string part = "its coefficient of " + lname + " must be -d(" + entry + ")/d" + ctx.states[i];
      if (got.expand().is_zero())
        part += ", but " + lname + " is missing altogether";
      else if (miss_text.size() <= 240)
        part += ", and it misses " + lname + "*(" + miss_text + ")";
      parts.push_back(part + " (the Jacobian entry d" + (cost ? "L" : ctx.states[j] + "'") + "/d" + ctx.states[i] +
                      ")");
    }
    if (parts.empty()) return "";
    return "In costate_odes[" + ctx.costates[i] + "]: " + join(parts, "; ") + ".";
  }

  std::string gradient_text() const {
    std::vector<std::string> g;
    for (const auto& e : ctx.dH_da) g.push_back(print(e));
    return "(" + join(g, ", ") + ")";
  }

  void check_direction() {
    if (ctx.directions.empty()) return;
    Check c = start("control_direction", "control", "random_points+exact");
    const std::string advice = "a* = -g/|g| with g = dH/da = " + gradient_text() + " minimizes H over unit vectors";
    std::vector<ex> law;
    std::vector<Compiled> lc;
    if (!read_direction_law(c, advice, law, lc)) {
      checks.push_back(c);
      return;
    }
    std::mt19937_64 rng(0xD1B54A32D192ED03ULL ^ ctx.options.seed);
    double unit_err = 0, flip = 0, worse = 0;
    std::string unit_msg, flip_msg, worse_msg;
    for (const auto& p : ctx.points) {
      std::vector<double> A;
      double n2 = 0;
      for (const auto& f : lc) {
        A.push_back(f(p));
        n2 += A.back() * A.back();
      }
      const double ue = rel_diff(std::sqrt(n2), 1.0);
      if (ue > unit_err) {
        unit_err = ue;
        unit_msg = "control_law.direction.law is not a unit vector: |a*| = " + num(std::sqrt(n2)) +
                   " at a sample point; " + advice + ".";
      }
      const double hA = ctx.hamiltonian_compiled(ctx.set_direction(p, A));
      auto compare = [&](const std::vector<double>& b, bool is_flip) {
        const double hb = ctx.hamiltonian_compiled(ctx.set_direction(p, b));
        const double v = std::isfinite(hA) ? (hA - hb) / (1 + std::max(std::fabs(hA), std::fabs(hb))) : 2.0;
        if (is_flip && v > flip) {
          flip = v;
          flip_msg = "control_law.direction.law maximizes H instead of minimizing it: H(-a*) = " + num(hb) +
                     " < H(a*) = " + num(hA) + " at a sample point (G2); flip its sign: " + advice + ".";
        } else if (!is_flip && v > worse) {
          worse = v;
          std::vector<std::string> bt;
          for (double x : b) bt.push_back(num(x));
          worse_msg = "control_law.direction.law does not minimize H over unit vectors: H(a*) = " + num(hA) +
                      " but H(a) = " + num(hb) + " for a = (" + join(bt, ", ") + ") at a sample point; " + advice + ".";
        }
      };
      std::vector<double> minus = A;
      for (auto& x : minus) x = -x;
      compare(minus, true);
      compare(ctx.direction_of(ctx.with_direction(p, std::nan(""))), false);
      for (int k = 0; k < kRandomDirections; ++k) compare(random_unit(rng, ctx.directions.size()), false);
    }
    c.max_rel = std::max({unit_err, flip, worse});
    // Exact: |a*|^2 = 1 and a* parallel to g, shown symbolically (the sign is the numeric part).
    ex n2 = 0;
    for (const auto& l : law) n2 += l * l;
    bool exact = exact_equal(n2, 1);
    for (std::size_t j = 0; exact && j < law.size(); ++j)
      for (std::size_t k = j + 1; exact && k < law.size(); ++k)
        exact = exact_equal(law[j] * ctx.dH_da[k], law[k] * ctx.dH_da[j]);
    if (unit_err > kTol) {
      c.fail(unit_msg);
    } else if (flip > kTol) {
      c.fail(flip_msg);
    } else if (worse > kTol) {
      c.fail(worse_msg);
    } else {
      c.exact = exact;
      direction_law = law;  // verified: the exact throttle checks may use the derivation's own form
    }
    checks.push_back(c);
  }

  // The direction law as written and compiled; false (c failed) where it is missing, lists other
  // controls or cannot be read.
  bool read_direction_law(Check& c, const std::string& advice, std::vector<ex>& law, std::vector<Compiled>& lc) const {
    const std::string names = "(" + join(ctx.directions, ", ") + ")";
    const auto& dir = ctx.doc.control_law.direction;
    if (!dir) {
      c.fail("control_law.direction is missing: give the law of the thrust direction " + names + "; " + advice + ".");
      return false;
    }
    const std::vector<std::string>& listed = dir->controls;
    if (listed != ctx.directions) {
      c.fail("control_law.direction.controls is (" + join(listed, ", ") + "), expected " + names +
             " (the controls of kind direction, in order).");
      return false;
    }
    const std::vector<derivation::Expression>& law_text = dir->law;
    if (law_text.size() != ctx.directions.size()) {
      c.fail("control_law.direction.law must give one expression per direction control " + names + "; " + advice + ".");
      return false;
    }
    try {
      for (std::size_t j = 0; j < ctx.directions.size(); ++j) {
        const std::string where = "control_law.direction.law[" + ctx.directions[j] + "]";
        law.push_back(ctx.symbols.parse(law_text[j].text, where));
        for (const auto& a : ctx.directions)
          if (law.back().has(ctx.sym(a))) throw std::invalid_argument(where + " depends on the direction control " + a);
        lc.push_back(ctx.compile(law.back()));
      }
    } catch (const std::exception& e) {
      c.fail(std::string(e.what()) + "; " + advice + ".");
      return false;
    }
    return true;
  }

  // The sail law: n* admissible (|n*| = 1, n*.r_hat >= 0), stationary on the unit sphere (the
  // tangential part of dH/dn vanishes, so dH/dalpha = 0 in the plane of r_hat and n*), and the
  // minimum of H over the hemisphere (against the verifier's own numerical minimizer and random
  // admissible normals). The cone angle must be the angle between n* and r_hat.
  void check_sail() {
    if (ctx.sails.empty()) return;
    Check c = start("control_sail", "control", "random_points");
    Check ca = start("control_sail_cone_angle", "control", "random_points");
    std::vector<Compiled> lc;
    Compiled cone;
    const std::string error = read_sail_law(lc, cone);
    if (!error.empty()) {
      c.max_rel = ca.max_rel = 2;
      c.fail(error + ".");
      ca.fail(error + ".");
      checks.push_back(c);
      checks.push_back(ca);
      return;
    }
    const std::vector<Vec3> laws = check_sail_law(c, lc);
    check_cone_angle(c, ca, cone, laws);
    checks.push_back(c);
    checks.push_back(ca);
  }

  // The sail law and its cone angle as written, compiled; the reason they cannot be read, else "".
  std::string read_sail_law(std::vector<Compiled>& lc, Compiled& cone) const {
    const std::string names = "(" + join(ctx.sails, ", ") + ")";
    const std::string set = kAdmissibleSet;
    const auto& sail = ctx.doc.control_law.sail;
    std::string error;
    try {
      if (!sail)
        throw std::invalid_argument("control_law.sail is missing: give the law of the sail normal " + names +
                                    " minimizing H over " + set + ", and its cone angle");
      const std::vector<std::string>& listed = sail->controls;
      if (listed != ctx.sails)
        throw std::invalid_argument("control_law.sail.controls is (" + join(listed, ", ") + "), expected " + names +
                                    " (the controls of kind sail_normal, in order)");
      const std::vector<derivation::Expression>& law = sail->law;
      if (law.size() != 3)
        throw std::invalid_argument("control_law.sail.law must give one expression per sail control " + names);
      if (!ctx.sail_definitions_error.empty()) throw std::invalid_argument(ctx.sail_definitions_error);
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string where = "control_law.sail.law[" + ctx.sails[k] + "]";
        const ex e = ctx.statement(law[k].text, where).subs(ctx.sail_definitions);
        for (const auto& n : ctx.sails)
          if (e.has(ctx.sym(n))) throw std::invalid_argument(where + " depends on the sail control " + n);
        lc.push_back(ctx.compile(e));
      }
      const ex a = ctx.statement(sail->cone_angle.text, "control_law.sail.cone_angle").subs(ctx.sail_definitions);
      cone = ctx.compile(a);
    } catch (const std::exception& e) {
      error = e.what();
    }
    return error;
  }

  // The law n* at each sample point against H (unit, admissible, minimal, stationary); returns n*
  // at each point.
  std::vector<Vec3> check_sail_law(Check& c, const std::vector<Compiled>& lc) const {
    const std::string set = kAdmissibleSet;
    std::mt19937_64 rng(0x8CB92BA72F3D8DD7ULL ^ ctx.options.seed);
    double unit_err = 0, adm_err = 0, worse = 0, stat_err = 0;
    std::string unit_msg, adm_msg, worse_msg, stat_msg;
    std::vector<Vec3> laws;
    for (const auto& p : ctx.points) {
      const Vec3 n{lc[0](p), lc[1](p), lc[2](p)}, rh = r_hat(ctx, p);
      laws.push_back(n);
      const double norm = std::sqrt(dot(n, n));
      const double ue = rel_diff(norm, 1.0);
      if (ue > unit_err) {
        unit_err = ue;
        unit_msg = "control_law.sail.law is not a unit vector: |n*| = " + num(norm) + " at a sample point.";
      }
      const double nr = dot(n, rh);
      if (std::isfinite(nr) && -nr > adm_err) {
        adm_err = -nr;
        adm_msg = "control_law.sail.law leaves the admissible set: n*.r_hat = " + num(nr) +
                  " < 0 at a sample point (the sail cannot face away from the Sun; cone angle in [0, pi/2]).";
      }
      const double hn = ctx.hamiltonian_compiled(set_sail(ctx, p, n));
      auto compare = [&](const Vec3& m) {
        const double hm = ctx.hamiltonian_compiled(set_sail(ctx, p, m));
        const double v = std::isfinite(hn) ? (hn - hm) / (1 + std::max(std::fabs(hn), std::fabs(hm))) : 2.0;
        if (v > worse) {
          worse = v;
          worse_msg = "control_law.sail.law does not minimize H over " + set +
                      ": at a sample point it gives n* = " + vec_text(n) + " (cone angle " + num(cone_of(n, rh)) +
                      " rad) with H = " + num(hn) + ", but n = " + vec_text(m) + " (cone angle " + num(cone_of(m, rh)) +
                      " rad) gives H = " + num(hm);
        }
      };
      compare(optimal_sail(ctx, p));
      for (int k = 0; k < kRandomSailNormals; ++k) compare(random_admissible(ctx, p, rng));
      // Stationarity on the unit sphere where n* is inside the hemisphere.
      const Point q = set_sail(ctx, p, n);
      const Vec3 g{ctx.dH_dn_compiled[0](q), ctx.dH_dn_compiled[1](q), ctx.dH_dn_compiled[2](q)};
      if (nr > 1e-6 && std::fabs(norm - 1) < 1e-6) {
        const double gn = dot(g, n);
        Vec3 t{};
        for (std::size_t k = 0; k < 3; ++k) t[k] = g[k] - gn * n[k];
        const double se = std::isfinite(gn) ? std::sqrt(dot(t, t)) / (1 + std::sqrt(dot(g, g))) : 2.0;
        if (se > stat_err) {
          stat_err = se;
          stat_msg =
              "control_law.sail.law is not a stationary point of H on the unit sphere: at a sample point the "
              "part of dH/dn = " +
              vec_text(g) + " tangent to the sphere at n* = " + vec_text(n) + " has norm " + num(std::sqrt(dot(t, t))) +
              " (dH/dalpha != 0 at the given cone angle); solve dH/dalpha = 0 for the cone angle alpha in the "
              "plane of r_hat and the costate direction and take the root of smallest H.";
        }
      }
    }
    c.max_rel = std::min(2.0, std::max({unit_err, adm_err, worse, stat_err}));
    if (unit_err > kTol) {
      c.fail(unit_msg);
    } else if (adm_err > kTol) {
      c.fail(adm_msg);
    } else if (worse > kTol) {
      c.fail(worse_msg + (stat_err <= kTol
                              ? "; the law is a stationary point of H but not its minimum (a wrong root "
                                "of dH/dalpha = 0, or a maximizer): take the root of smallest H."
                              : "; solve dH/dalpha = 0 for the cone angle and take the root of smallest H."));
    } else if (stat_err > kTol) {
      c.fail(stat_msg);
    }
    return laws;
  }

  // The cone angle: against the law once verified, else against the verifier's own minimizer
  // where that is an interior stationary point resolved to full precision.
  void check_cone_angle(const Check& c, Check& ca, const Compiled& cone, const std::vector<Vec3>& laws) const {
    const double tol = c.pass ? kTol : 1e-6;
    for (std::size_t i = 0; i < ctx.points.size(); ++i) {
      const Point& p = ctx.points[i];
      const Vec3 rh = r_hat(ctx, p), n = c.pass ? laws[i] : optimal_sail(ctx, p);
      const double want = cone_of(n, rh), got = cone(p);
      const bool comparable = c.pass || (dot(n, rh) > 1e-3 && sail_tangential(ctx, p, n) < 1e-12);
      const double err = comparable ? rel_diff(got, want) : 0.0;
      ca.max_rel = std::max(ca.max_rel, err);
      if (!(got >= -kTol && got <= 1.5707963267948966 + kTol))
        ca.fail("control_law.sail.cone_angle gives " + num(got) + " rad at a sample point, outside [0, pi/2].");
      else if (err > tol)
        ca.fail("control_law.sail.cone_angle is not the angle between r_hat and the " +
                std::string(c.pass ? "sail law" : "sail normal minimizing H") + ": at a sample point it gives " +
                num(got) + " rad, expected " + num(want) + " rad.");
    }
  }

  // What the throttle's checks share: the law as written, dH/du and d2H/du2 (Hu_star: dH/du with
  // a* substituted), and the interior law as written (or why it cannot be read).
  struct ThrottleParts {
    const derivation::ThrottleLaw* t = nullptr;
    symbol u, eps;
    GiNaC::exmap astar;
    ex Hu, Huu, Hu_star;
    Compiled Hu_c, Huu_c;
    ex interior;
    Compiled interior_c;
    std::string interior_error;
  };

  // A point with the direction at a* (full thrust), the throttle at `uval` (NaN: the point's own)
  // and, with `eps0`, the homotopy parameter at 0.
  std::function<Point(const Point&)> throttle_point(double uval, bool eps0) const {
    const int us = ctx.slot(ctx.throttle), es = ctx.slot(ctx.eps);
    return [this, us, es, uval, eps0](const Point& p) {
      Point q = ctx.with_direction(p, 1.0);
      if (!std::isnan(uval)) q[static_cast<std::size_t>(us)] = uval;
      if (eps0) q[static_cast<std::size_t>(es)] = 0;
      return q;
    };
  }

  void check_throttle() {
    if (ctx.throttle.empty()) return;
    const derivation::ThrottleLaw* t = ctx.doc.control_law.throttle ? &*ctx.doc.control_law.throttle : nullptr;
    if (!t) {
      Check c = start("throttle_switching", "control", "structural");
      c.fail(
          "control_law.throttle is missing: give the switching function dH/du (at eps = 0, a* substituted), "
          "dH_du_at_lower, dH_du_at_upper and the interior law of the throttle " +
          ctx.throttle + ".");
      checks.push_back(c);
      return;
    }
    ThrottleParts parts;
    parts.t = t;
    parts.u = GiNaC::ex_to<symbol>(ctx.sym(ctx.throttle));
    parts.eps = GiNaC::ex_to<symbol>(ctx.sym(ctx.eps));
    for (std::size_t j = 0; j < ctx.directions.size(); ++j) parts.astar[ctx.sym(ctx.directions[j])] = direction_law[j];
    parts.Hu = ctx.hamiltonian.diff(parts.u);
    parts.Huu = parts.Hu.diff(parts.u);
    parts.Hu_star = parts.Hu.subs(parts.astar);
    parts.Hu_c = ctx.compile(parts.Hu);
    parts.Huu_c = ctx.compile(parts.Huu);
    try {
      parts.interior = ctx.symbols.parse(t->interior.text, "control_law.throttle.interior");
      parts.interior_c = ctx.compile(parts.interior);
    } catch (const std::exception& e) {
      parts.interior_error = e.what();
    }
    check_throttle_derivatives(parts);
    check_throttle_convexity(parts);
    if (!parts.Huu.expand().is_zero()) check_throttle_interior(parts);  // a smooth law: dH/du = 0 inside
    check_throttle_law(parts);
  }

  // The switching function and dH/du at both ends of [0, 1] (and d2H/du2 where given).
  void check_throttle_derivatives(const ThrottleParts& parts) {
    auto& [t, u, eps, astar, Hu, Huu, Hu_star, Hu_c, Huu_c, interior, interior_c, interior_error] = parts;
    const std::string a_note = ctx.directions.empty() ? "" : " with a* substituted";
    std::vector<std::string> no_u_a = ctx.directions, no_u_a_eps = ctx.directions;
    no_u_a.push_back(ctx.throttle);
    no_u_a_eps.push_back(ctx.throttle);
    no_u_a_eps.push_back(ctx.eps);
    checks.push_back(equality("throttle_switching", "control", "control_law.throttle.switching_function",
                              "dH/d" + ctx.throttle + " at " + ctx.eps + " = 0" + a_note,
                              {Hu_star.subs(GiNaC::lst{u == 0, eps == 0}), Hu_c, throttle_point(0, true)},
                              t->switching_function.text, true, no_u_a_eps));
    checks.push_back(equality("throttle_dH_du_at_lower", "control", "control_law.throttle.dH_du_at_lower",
                              "dH/d" + ctx.throttle + " at " + ctx.throttle + " = 0" + a_note,
                              {Hu_star.subs(u == 0), Hu_c, throttle_point(0, false)}, t->dH_du_at_lower.text, true,
                              no_u_a));
    checks.push_back(equality("throttle_dH_du_at_upper", "control", "control_law.throttle.dH_du_at_upper",
                              "dH/d" + ctx.throttle + " at " + ctx.throttle + " = 1" + a_note,
                              {Hu_star.subs(u == 1), Hu_c, throttle_point(1, false)}, t->dH_du_at_upper.text, true,
                              no_u_a));
    if (t->d2H_du2)
      checks.push_back(equality(
          "throttle_d2H_du2", "control", "control_law.throttle.d2H_du2", "d2H/d" + ctx.throttle + "2" + a_note,
          {Huu.subs(astar), Huu_c, throttle_point(std::nan(""), false)}, t->d2H_du2->text, true, ctx.directions));
  }

  // Convexity: dH/du = 0 must be a minimum (lambda0 > 0, eps > 0 at every sample point).
  void check_throttle_convexity(const ThrottleParts& parts) {
    auto& [t, u, eps, astar, Hu, Huu, Hu_star, Hu_c, Huu_c, interior, interior_c, interior_error] = parts;
    Check c = start("throttle_convexity", "control", "random_points");
    for (const auto& p : ctx.points) {
      const double v = Huu_c(throttle_point(std::nan(""), false)(p));
      const double viol = std::isfinite(v) ? std::max(0.0, -v) / (1 + std::fabs(v)) : 2.0;
      if (viol > c.max_rel) c.max_rel = viol;
      if (viol > kTol)
        c.fail("d2H/d" + ctx.throttle + "2 = " + print(tidy(Huu.subs(astar))) + " is " + num(v) +
               " < 0 at a sample point with " + ctx.multiplier + " > 0, " + ctx.eps +
               " > 0: dH/du = 0 is then a maximum of H; the " + ctx.eps +
               " smoothing in running_cost must make H convex in " + ctx.throttle + ".");
    }
    checks.push_back(c);
  }

  // Interior law: dH/du = 0 there.
  void check_throttle_interior(const ThrottleParts& parts) {
    auto& [t, u, eps, astar, Hu, Huu, Hu_star, Hu_c, Huu_c, interior, interior_c, interior_error] = parts;
    Check c = start("throttle_interior", "control", "random_points+exact");
    if (!interior_error.empty()) {
      c.max_rel = 2;
      c.fail(interior_error + "; expected the " + ctx.throttle + " solving " + print(tidy(Hu_star)) + " = 0.");
    } else {
      double worst = 0, wv = 0, wu = 0;
      for (const auto& p : ctx.points) {
        const double ui = interior_c(p);
        const double r = Hu_c(throttle_point(ui, false)(p));
        const double scale =
            std::max(std::fabs(Hu_c(throttle_point(0, false)(p))), std::fabs(Hu_c(throttle_point(1, false)(p))));
        const double rel = std::isfinite(r) && std::isfinite(scale) ? std::fabs(r) / (1 + scale) : 2.0;
        if (rel > worst) {
          worst = rel;
          wv = r;
          wu = ui;
        }
      }
      c.max_rel = worst;
      c.exact = exact_equal(Hu_star.subs(u == interior), 0);
      c.pass = worst <= kTol || c.exact;
      if (!c.pass)
        c.fail("control_law.throttle.interior = " + t->interior.text + " does not solve dH/d" + ctx.throttle + " = " +
               print(tidy(Hu_star)) + " = 0: at a sample point it gives " + ctx.throttle + " = " + num(wu) +
               " where dH/d" + ctx.throttle + " = " + num(wv) + ".");
    }
    checks.push_back(c);
  }

  // The clamped law minimizes H over a grid of u in [0, 1].
  void check_throttle_law(const ThrottleParts& parts) {
    auto& [t, u, eps, astar, Hu, Huu, Hu_star, Hu_c, Huu_c, interior, interior_c, interior_error] = parts;
    const int us = ctx.slot(ctx.throttle);
    Check c = start("throttle_law", "control", "random_points");
    const std::vector<double>& bounds = t->bounds;
    const bool bounds_ok = bounds.size() == 2 && bounds[0] == 0 && bounds[1] == 1;
    Compiled lo, hi;
    std::string error = interior_error;
    try {
      for (const bool lower_end : {true, false}) {
        const char* name = lower_end ? "dH_du_at_lower" : "dH_du_at_upper";
        const derivation::Expression& f = lower_end ? t->dH_du_at_lower : t->dH_du_at_upper;
        const std::string where = std::string("control_law.throttle.") + name;
        (lower_end ? lo : hi) = ctx.compile(ctx.symbols.parse(f.text, where));
      }
    } catch (const std::exception& e) {
      if (error.empty()) error = e.what();
    }
    const std::string& control = t->control;
    if (control != ctx.throttle) {
      c.fail("control_law.throttle.control is '" + control + "', expected '" + ctx.throttle +
             "' (the control of kind throttle).");
    } else if (!bounds_ok) {
      c.fail("control_law.throttle.bounds must be [0, 1] (the throttle is T/Tmax).");
    } else if (!error.empty()) {
      c.max_rel = 2;
      c.fail("cannot evaluate the throttle law: " + error + ".");
    } else {
      for (const auto& p : ctx.points) {
        const double s0 = lo(p), s1 = hi(p);
        const double ustar = s0 >= 0 ? 0.0 : (s1 <= 0 ? 1.0 : interior_c(p));
        const Point q = ctx.with_direction(p, 1.0);
        auto H_at = [&](double uv) {
          Point r = q;
          r[static_cast<std::size_t>(us)] = uv;
          return ctx.hamiltonian_compiled(r);
        };
        const double hs = H_at(ustar);
        if (!std::isfinite(ustar) || ustar < -kTol || ustar > 1 + kTol || !std::isfinite(hs)) {
          c.max_rel = 2;
          c.fail("the throttle law (u = 0 if dH_du_at_lower >= 0, 1 if dH_du_at_upper <= 0, else interior) gives " +
                 ctx.throttle + " = " + num(ustar) + " outside [0, 1] at a sample point.");
          break;
        }
        for (int k = 0; k <= kThrottleGrid; ++k) {
          const double uk = static_cast<double>(k) / kThrottleGrid, hk = H_at(uk);
          const double v = (hs - hk) / (1 + std::max(std::fabs(hs), std::fabs(hk)));
          if (v > c.max_rel) c.max_rel = v;
          if (v > kTol)
            c.fail(
                "the throttle law (u = 0 if dH_du_at_lower >= 0, 1 if dH_du_at_upper <= 0, else interior) does not "
                "minimize H over " +
                ctx.throttle + " in [0, 1]: at a sample point it gives " + ctx.throttle + " = " + num(ustar) +
                " with H = " + num(hs) + ", but " + ctx.throttle + " = " + num(uk) + " gives H = " + num(hk) + ".");
        }
      }
    }
    checks.push_back(c);
  }
};

}  // namespace

std::unique_ptr<Family> control_family(const Context& ctx) {
  return std::make_unique<ControlFamily>(ctx);
}

}  // namespace helios::verify::detail

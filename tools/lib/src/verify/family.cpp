// What several check families use: equalities, the shooting equations, moving epochs.
#include "family.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace helios::verify::detail {

Family::Family(const Context& ctx) : ctx(ctx) {}

Check Family::start(const std::string& id, const std::string& category, const std::string& method) const {
  Check c;
  c.id = id;
  c.category = category;
  c.method = method;
  c.points = method == "structural" ? 0 : static_cast<int>(ctx.points.size());
  return c;
}

Check Family::equality(const std::string& id, const std::string& category, const std::string& label,
                       const std::string& expected_name, const Expected& expected, const std::string& given_text,
                       bool diagnose, const std::vector<std::string>& forbidden) const {
  Check c = start(id, category, "random_points+exact");
  ex given;
  Compiled gc;
  try {
    given = ctx.symbols.parse(given_text, label);
    gc = ctx.compile(given);
  } catch (const std::exception& e) {
    c.max_rel = 2;
    c.fail(std::string(e.what()) + "; expected " + expected_name + " = " + print(tidy(expected.symbolic)) + ".");
    return c;
  }
  double worst = -1, we = 0, wg = 0;
  bool negated = true;
  for (const auto& p : ctx.points) {
    const double e = expected.numeric(expected.at ? expected.at(p) : p), g = gc(p);
    const double r = rel_diff(e, g);
    if (r > worst) {
      worst = r;
      we = e;
      wg = g;
    }
    if (rel_diff(e, -g) > kTol) negated = false;
  }
  c.max_rel = worst;
  c.exact = exact_equal(expected.symbolic, given);
  c.pass = worst <= kTol || c.exact;
  if (c.pass) return c;
  std::vector<std::string> diag;
  std::vector<std::string> bad;
  for (const auto& name : forbidden)
    if (ctx.slots.count(name) && given.has(ctx.sym(name))) bad.push_back(name);
  if (!bad.empty()) diag.push_back("it must not depend on " + join(bad, ", "));
  if (negated) {
    diag.push_back("the sign of the whole expression is flipped");
  } else if (diagnose) {
    const std::string t = term_diagnosis(expected.symbolic, given);
    if (!t.empty()) diag.push_back(t);
  }
  c.fail(label + ": expected " + expected_name + " = " + print(tidy(expected.symbolic)) + ", got " + given_text +
         (diag.empty() ? "" : "; " + join(diag, "; ")) + " (relative difference " + num(worst) +
         " at a sample point: " + num(we) + " expected, " + num(wg) + " given).");
  return c;
}

const derivation::Inequality* Family::inequality_of(const std::string& name) const {
  for (const auto& eq : ctx.doc.shooting.equations)
    if (eq.name == name && eq.inequality) return &*eq.inequality;
  return nullptr;
}

void Family::check_bound(const std::string& name, const derivation::Inequality& bound, const ex& nu) {
  Check k = start("bound:" + name, "events", "structural");
  const std::string where = "shooting.equations[" + name + "].inequality";
  const std::string& multiplier = bound.multiplier;
  if (bound.sense != "expression <= 0") {
    k.fail(where + ".sense must be 'expression <= 0' (the bound psi <= 0, its multiplier >= 0 when active).");
  } else if (multiplier != print(nu)) {
    k.fail(where + ".multiplier = '" + multiplier + "' is not " + print(nu) + ", the multiplier of the row " + name +
           ".");
  } else {
    bool inactive_ok = false;
    std::string got = "(none)";
    try {
      got = bound.inactive_expression.text;
      inactive_ok = (ctx.symbols.parse(got, where + ".inactive_expression") - nu).expand().is_zero();
    } catch (const std::exception&) {
    }
    if (!inactive_ok)
      k.fail(where + ".inactive_expression = '" + got + "' must be " + print(nu) +
             ": an inactive bound's equation is its multiplier = 0.");
  }
  checks.push_back(k);
}

double Family::proportional_mismatch(const Compiled& e, const Compiled& g) const {
  std::vector<double> gv;
  for (const auto& p : ctx.points) gv.push_back(g(p));
  return proportional_mismatch(e, gv);
}

double Family::proportional_mismatch(const Compiled& e, const std::vector<double>& gv) const {
  double best = 0, k = std::nan("");
  std::vector<double> ev;
  for (std::size_t i = 0; i < ctx.points.size(); ++i) {
    ev.push_back(e(ctx.points[i]));
    if (std::isfinite(ev.back()) && std::fabs(ev.back()) > best) {
      best = std::fabs(ev.back());
      k = gv[i] / ev.back();
    }
  }
  if (!(best > 0) || !std::isfinite(k) || std::fabs(k) < 1e-12) return 2.0;
  double m = 0;
  for (std::size_t i = 0; i < ev.size(); ++i) m = std::max(m, rel_diff(gv[i], k * ev[i]));
  return m;
}

void Family::find_equation(Check& c, const ex& expected, const std::string& missing) const {
  const Compiled ec = ctx.compile(expected);
  double best = 2;
  for (const auto& eq : ctx.equations) {
    if (!eq.ok) continue;
    const double m = proportional_mismatch(ec, eq.values);
    if (m <= kTol) {
      c.max_rel = m;
      c.exact = exact_proportional(eq.e, expected);
      return;
    }
    best = std::min(best, m);
  }
  c.max_rel = best;
  c.fail(missing);
}

std::map<std::string, ex> Family::rates_at(const std::string& label, std::vector<std::string>& problems) const {
  std::map<std::string, ex> rates;
  std::map<std::string, std::vector<std::string>> ephem, rate, coast;  // by body / constraint
  for (const auto& name : ctx.parameters) {
    const auto it = ctx.sources.find(name);
    if (it == ctx.sources.end()) continue;
    const std::string& src = it->second;
    const auto a = src.find(':'), b = src.rfind(':');
    if (a == std::string::npos || b == a || src.substr(b + 1) != label) continue;
    const std::string kind = src.substr(0, a), owner = src.substr(a + 1, b - a - 1);
    (kind == "ephemeris" ? ephem : kind == "ephemeris_rate" ? rate : coast)[owner].push_back(name);
  }
  for (const auto& [body, components] : ephem) {
    const auto& r = rate[body];
    for (std::size_t k = 0; k < components.size(); ++k) {
      const auto named = std::find(r.begin(), r.end(), names::rate(components[k]));
      if (named != r.end())
        rates[components[k]] = ctx.sym(*named);
      else if (r.size() == components.size())
        rates[components[k]] = ctx.sym(r[k]);
      else
        problems.push_back("parameter " + components[k] + " (source ephemeris:" + body + ":" + label + ") moves with " +
                           (label == "tf" || label == "t0" ? label : "the epoch of " + label) +
                           " but has no parameter with source ephemeris_rate:" + body + ":" + label);
    }
  }
  for (const auto& [owner, names] : coast) {
    if (!ctx.has_coast || !ctx.coast_error.empty() || names.size() != ctx.coast_states.size() ||
        ctx.coast_rhs.size() != ctx.coast_states.size()) {
      problems.push_back("the coasting target of " + owner + " (" + join(names, ", ") +
                         ") has no usable coast_dynamics to give its rate");
      continue;
    }
    GiNaC::exmap to_params;
    for (std::size_t k = 0; k < names.size(); ++k) to_params[ctx.sym(ctx.coast_states[k])] = ctx.sym(names[k]);
    for (std::size_t k = 0; k < names.size(); ++k) rates[names[k]] = ctx.coast_rhs[k].subs(to_params);
  }
  return rates;
}

ex Family::nu_dot(const std::vector<ex>& psi, const std::vector<ex>& dpsi,
                  const std::function<ex(std::size_t)>& rhs) const {
  const std::size_t m = psi.size(), n = ctx.states.size();
  if (m == 0) return 0;
  std::vector<std::vector<ex>> J(m, std::vector<ex>(n));
  std::vector<std::vector<double>> Jn(m, std::vector<double>(n));
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      J[j][i] = psi[j].diff(GiNaC::ex_to<symbol>(ctx.sym(ctx.states[i])));
      Jn[j][i] = ctx.compile(J[j][i])(ctx.points[0]);
    }
  std::vector<std::size_t> rows;
  for (std::size_t j = 0; j < m; ++j) {
    std::size_t best = n;
    for (std::size_t i = 0; i < n; ++i)
      if (std::find(rows.begin(), rows.end(), i) == rows.end() &&
          (best == n || std::fabs(Jn[j][i]) > std::fabs(Jn[j][best])))
        best = i;
    if (best == n || !(std::fabs(Jn[j][best]) > 1e-12))
      throw std::invalid_argument("the constraints' psi are not independent in the states");
    for (std::size_t k = j + 1; k < m; ++k) {
      const double f = Jn[k][best] / Jn[j][best];
      for (std::size_t i = 0; i < n; ++i) Jn[k][i] -= f * Jn[j][i];
    }
    rows.push_back(best);
  }
  const auto um = static_cast<unsigned>(m);
  GiNaC::matrix M(um, um), b(um, 1), nu(um, 1);
  for (unsigned r = 0; r < um; ++r) {
    for (unsigned j = 0; j < um; ++j) M(r, j) = J[j][rows[r]];
    b(r, 0) = rhs(rows[r]);
    nu(r, 0) = symbol("helios_nu_" + std::to_string(r));
  }
  const GiNaC::matrix sol = M.solve(nu, b);
  ex out = 0;
  for (unsigned j = 0; j < um; ++j) out += sol(j, 0) * dpsi[j];
  return out;
}

Family::Linear Family::linear_compare(const ex& expected, const ex& given, const std::vector<ex>& basis,
                                      const ex& anchor, bool fixed) const {
  GiNaC::exmap zero;
  for (const auto& b : basis) zero[b] = 0;
  std::vector<ex> parts_e, parts_g;
  std::vector<std::string> names;
  for (const auto& b : basis) {
    parts_e.push_back(expected.diff(GiNaC::ex_to<symbol>(b)).subs(zero));
    parts_g.push_back(given.diff(GiNaC::ex_to<symbol>(b)).subs(zero));
    names.push_back(print(b));
  }
  parts_e.push_back(expected.subs(zero));
  parts_g.push_back(given.subs(zero));
  const std::size_t P = parts_e.size();
  std::vector<std::vector<double>> E(P), G(P);
  for (std::size_t k = 0; k < P; ++k) {
    const Compiled ce = ctx.compile(parts_e[k]), cg = ctx.compile(parts_g[k]);
    for (const auto& p : ctx.points) {
      E[k].push_back(ce(p));
      G[k].push_back(cg(p));
    }
  }
  auto zero_all = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return rel_diff(x, 0) <= kTol; });
  };
  auto scaled = [](const std::vector<double>& g, const std::vector<double>& e, double k) {
    for (std::size_t i = 0; i < g.size(); ++i)
      if (rel_diff(g[i], k * e[i]) > kTol) return false;
    return true;
  };
  // The scale: the candidate ratio that matches the most parts.
  double scale = 1;
  int best = fixed ? std::numeric_limits<int>::max() : -1;
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < P; ++k)
    if (k < basis.size() && basis[k].is_equal(anchor))
      order.insert(order.begin(), k);
    else
      order.push_back(k);
  for (const std::size_t k : order) {
    std::size_t at = 0;
    for (std::size_t i = 1; i < E[k].size(); ++i)
      if (std::fabs(E[k][i]) > std::fabs(E[k][at])) at = i;
    if (E[k].empty() || !(std::fabs(E[k][at]) > 1e-12)) continue;
    const double r = G[k][at] / E[k][at];
    if (!std::isfinite(r) || std::fabs(r) < 1e-12) continue;
    int count = 0;
    for (std::size_t j = 0; j < P; ++j) count += !zero_all(E[j]) && scaled(G[j], E[j], r);
    if (count > best) {
      best = count;
      scale = r;
    }
  }
  Linear out;
  for (std::size_t k = 0; k < P; ++k) {
    const bool ez = zero_all(E[k]), gz = zero_all(G[k]);
    const bool rest = k + 1 == P;
    if (ez && gz) continue;
    if (scaled(G[k], E[k], scale)) continue;
    if (rest) {
      out.rest_wrong = true;
    } else if (gz) {
      out.missing.push_back(names[k]);
    } else if (ez) {
      out.extra.push_back(names[k]);
    } else if (scaled(G[k], E[k], -scale)) {
      out.flipped.push_back(names[k]);
    } else {
      out.wrong.push_back(names[k]);
    }
  }
  return out;
}

const Equation* Family::matching_equation(const std::string& name, const ex& expected, Check& c,
                                          const GiNaC::exmap& resolve) const {
  const Compiled ec = ctx.compile(expected);
  double best = 2;
  std::vector<const Equation*> order;
  for (const auto& eq : ctx.equations)
    if (eq.ok && eq.name == name)
      order.insert(order.begin(), &eq);
    else if (eq.ok)
      order.push_back(&eq);
  for (const auto* eq : order) {
    bool uses = false;
    for (const auto& [from, to] : resolve) uses = uses || eq->symbols.count(print(from));
    const ex e = uses ? eq->e.subs(resolve) : eq->e;
    const double m = uses ? proportional_mismatch(ec, ctx.compile(e)) : proportional_mismatch(ec, eq->values);
    if (m <= kTol) {
      c.max_rel = m;
      c.exact = exact_proportional(e, expected);
      return eq;
    }
    best = std::min(best, m);
  }
  c.max_rel = best;
  return nullptr;
}

const Equation* Family::named_equation(const std::string& name) const {
  for (const auto& eq : ctx.equations)
    if (eq.ok && eq.name == name) return &eq;
  return nullptr;
}

ex Family::time_derivative(const ex& e, const std::string& epoch, const std::map<std::string, ex>& rates) const {
  ex d = ctx.slots.count(epoch) ? e.diff(GiNaC::ex_to<symbol>(ctx.sym(epoch))) : ex(0);
  for (const auto& [name, rate] : rates) d += e.diff(GiNaC::ex_to<symbol>(ctx.sym(name))) * rate;
  return d;
}

}  // namespace helios::verify::detail

// Interior events (psi, multipliers, constraints, costate jumps, free epoch, stationarity,
// unknowns) and a sliding departure.
#include "family.hpp"

#include <set>
#include <stdexcept>

namespace helios::verify::detail {
namespace {

class EventFamily : public Family {
 public:
  using Family::Family;

  std::vector<Check> run() override {
    for (const auto& e : ctx.interior_events) check_event(e);
    check_departure();
    return std::move(checks);
  }

 private:
  // What the seven steps of an event's check share: the symbols just before and after it, psi
  // split into the constraints c and the map x+ = g(x-), the multipliers of c, the states the map
  // carries and the costate jump rows. Each step fills its part; the later ones read them.
  struct EventParts {
    EventParts(const Event& event, std::size_t states)
        : e(event), id(event.id), where("events[" + event.id + "]"), n(states) {}
    const Event& e;
    const std::string& id;
    std::string where;
    std::size_t n;
    std::vector<ex> xm, xp, lm, lp;   // states and costates just before / after
    std::vector<std::size_t> c_rows;  // the rows of psi that are c
    std::vector<int> map_row;         // the row x+_s - g_s of each state
    std::vector<ex> g, c;
    std::vector<ex> nu;                 // the multipliers of c
    std::vector<bool> carried;          // dg_s/dx- is the unit row s
    std::vector<ex> rows, explicit_lp;  // the jump rows; lambda(t+) of the carried states
    GiNaC::exmap resolve;               // lambda(t+) of carried states -> their explicit value
    std::vector<ex> basis_rows;
    std::vector<std::string> params;  // the free parameters of psi, once each
  };

  static ex derivative(const ex& f, const ex& x) { return f.diff(GiNaC::ex_to<symbol>(x)); }
  bool zero_at_points(const ex& f) const {
    const Compiled cf = ctx.compile(f);
    return std::all_of(ctx.points.begin(), ctx.points.end(),
                       [&](const Point& p) { return rel_diff(cf(p), 0) <= kTol; });
  }

  void check_event(const Event& e) {
    if (!e.error.empty()) {
      Check c = start("event:" + e.id, "events", "structural");
      c.fail(e.error + ".");
      checks.push_back(c);
      return;
    }
    EventParts parts(e, ctx.states.size());
    for (std::size_t i = 0; i < parts.n; ++i) {
      parts.xm.push_back(ctx.sym(names::before(ctx.states[i], e.id)));
      parts.xp.push_back(ctx.sym(names::after(ctx.states[i], e.id)));
      parts.lm.push_back(ctx.sym(names::before(ctx.costates[i], e.id)));
      parts.lp.push_back(ctx.sym(names::after(ctx.costates[i], e.id)));
    }
    if (!check_event_psi(parts) || !check_event_multipliers(parts)) return;
    check_event_constraints(parts);
    costate_jump_rows(parts);
    for (std::size_t s = 0; s < parts.n; ++s) check_costate_jump(parts, s);
    check_event_time(parts);
    check_event_stationarity(parts);
    check_event_unknowns(parts);
  }

  // 1. psi = [c(t, x-, p); x+ - g(t + D, x-, p)]: rows without x+ are c, each state has one row x+_s - g_s.
  bool check_event_psi(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    Check ps = start("event_psi:" + id, "events", "random_points+exact");
    ps.exact = true;
    map_row.assign(n, -1);
    for (std::size_t r = 0; r < e.psi.size(); ++r) {
      std::vector<std::size_t> plus;
      for (std::size_t i = 0; i < n; ++i)
        if (e.psi[r].has(xp[i])) plus.push_back(i);
      if (plus.empty()) {
        c_rows.push_back(r);
      } else if (plus.size() > 1) {
        ps.fail(where + ".psi[" + std::to_string(r) + "] = " + e.psi_text[r] + " involves " +
                std::to_string(plus.size()) +
                " states after the event; each row of the map part must be x+ - g(x-) for one state.");
      } else if (map_row[plus[0]] >= 0) {
        ps.fail(where + ".psi has two rows in " + print(xp[plus[0]]) + " (rows " + std::to_string(map_row[plus[0]]) +
                " and " + std::to_string(r) + "); the map part has one row x+ - g(x-) per state.");
      } else {
        map_row[plus[0]] = static_cast<int>(r);
      }
    }
    g.resize(n);
    for (const auto r : c_rows) c.push_back(e.psi[r]);
    for (std::size_t s = 0; s < n && ps.pass; ++s) {
      if (map_row[s] < 0) {
        ps.fail(where + ".psi has no row " + print(xp[s]) + " - g_" + ctx.states[s] + "(x-) for state " +
                ctx.states[s] + ": the map part of psi must give every state after the event.");
        break;
      }
      const ex& row = e.psi[static_cast<std::size_t>(map_row[s])];
      g[s] = tree_size(row, kExactBudget) > kExactBudget ? ex(xp[s] - row) : (xp[s] - row).expand();
      if (!zero_at_points(derivative(row, xp[s]) - 1) || g[s].has(xp[s])) {
        ps.fail(where + ".psi[" + std::to_string(map_row[s]) +
                "] = " + e.psi_text[static_cast<std::size_t>(map_row[s])] + " must be " + print(xp[s]) +
                " - g(x-) with coefficient 1 on " + print(xp[s]) + " (its multiplier is then -lambda_" + ctx.states[s] +
                "(t+)).");
        break;
      }
      const Compiled cg = ctx.compile(g[s]), cm = ctx.compile(e.map[s]);
      double worst = 0;
      for (const auto& p : ctx.points) worst = std::max(worst, rel_diff(cg(p), cm(p)));
      ps.max_rel = std::max(ps.max_rel, worst);
      if (worst > kTol && !exact_equal(g[s], e.map[s])) {
        ps.fail(where + ".state_map[" + ctx.states[s] + "] = " + e.map_text[s] + " is not the map of psi[" +
                std::to_string(map_row[s]) + "] = " + e.psi_text[static_cast<std::size_t>(map_row[s])] +
                ", which gives " + print(xp[s]) + " = " + short_print(g[s]) + " (relative difference " + num(worst) +
                ").");
      } else if (worst > kTol || tree_size(g[s], kExactBudget) > kExactBudget) {
        ps.exact = ps.exact && worst <= kTol;
      }
    }
    for (std::size_t j = 0; j < c.size() && ps.pass; ++j)
      for (std::size_t i = 0; i < n; ++i)
        if (e.psi[c_rows[j]].has(lm[i]) || e.psi[c_rows[j]].has(lp[i]))
          ps.fail(where + ".psi[" + std::to_string(c_rows[j]) + "] = " + e.psi_text[c_rows[j]] +
                  " involves a costate; psi constrains states, time and parameters only.");
    ps.exact = ps.exact && ps.pass;
    checks.push_back(ps);
    return ps.pass;
  }

  // 2. Multipliers: nu_<id>_j for the rows of c, -lambda(t+)_s for the row x+_s - g_s.
  bool check_event_multipliers(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    Check pm = start("event_multipliers:" + id, "events", "structural");
    pm.exact = true;
    if (e.multiplier_text.size() != e.psi.size()) {
      pm.fail(where + ".multipliers has " + std::to_string(e.multiplier_text.size()) + " entries for " +
              std::to_string(e.psi.size()) + " rows of psi: give one multiplier per row.");
    } else {
      std::set<std::string> seen;
      for (std::size_t j = 0; j < c.size(); ++j) {
        const std::string& m = e.multiplier_text[c_rows[j]];
        const bool fresh = is_identifier(m) && ctx.kinds[static_cast<std::size_t>(ctx.slot(m))] == Kind::Free &&
                           std::find(e.free_params.begin(), e.free_params.end(), m) == e.free_params.end() &&
                           std::find(e.time_vars.begin(), e.time_vars.end(), m) == e.time_vars.end();
        if (!fresh || !seen.insert(m).second)
          pm.fail(where + ".multipliers[" + std::to_string(c_rows[j]) + "] = '" + m + "' must be a new symbol (e.g. " +
                  names::multiplier(id, j + 1) + "), the multiplier of psi row " + e.psi_text[c_rows[j]] + ".");
        else
          nu.push_back(ctx.sym(m));
      }
      for (std::size_t s = 0; s < n && pm.pass; ++s) {
        const std::string& m = e.multiplier_text[static_cast<std::size_t>(map_row[s])];
        bool ok = false;
        try {
          ok = (ctx.symbols.parse(m, where + ".multipliers") + lp[s]).expand().is_zero();
        } catch (const std::exception&) {
        }
        if (!ok)
          pm.fail(where + ".multipliers[" + std::to_string(map_row[s]) + "] = '" + m + "' must be -" + print(lp[s]) +
                  ": the multiplier of the row " + print(xp[s]) + " - g is -lambda_" + ctx.states[s] +
                  "(t+) (lambda(t+) = -dPhi/dx+).");
      }
    }
    checks.push_back(pm);
    return pm.pass;
  }

  // 3. Each row of c is a shooting equation (Rule 0).
  void check_event_constraints(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    for (std::size_t j = 0; j < c.size(); ++j) {
      const std::string name = names::constraint_row(id, j + 1);
      Check k = start("event_constraint:" + id + "_" + std::to_string(j + 1), "events", "random_points+exact");
      if (!matching_equation(name, c[j], k, {}))
        k.fail("missing interior constraint " + e.psi_text[c_rows[j]] + " = 0 (" + where + ".psi[" +
               std::to_string(c_rows[j]) + "] at " + id + "); add it to shooting.equations.");
      checks.push_back(k);
      if (const auto* bound = inequality_of(name)) check_bound(name, *bound, nu[j]);
    }
  }

  // 4. Costate jumps: lambda(t-)_s = nu^T dc/dx-_s + lambda(t+)^T dg/dx-_s. A state the map
  //    carries (dg_s/dx- = unit row s) gets lambda(t+)_s explicitly, any other a shooting variable.
  void costate_jump_rows(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    carried.assign(n, true);
    std::vector<std::vector<ex>> dg(n, std::vector<ex>(n));  // dg[k][s] = dg_k/dx-_s
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t s = 0; s < n; ++s) {
        dg[k][s] = derivative(g[k], xm[s]);
        if (carried[k] && !zero_at_points(dg[k][s] - (k == s ? 1 : 0))) carried[k] = false;
      }
    rows.resize(n);
    explicit_lp.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
      ex row = lm[s];
      for (std::size_t j = 0; j < c.size(); ++j) row -= nu[j] * derivative(c[j], xm[s]);
      for (std::size_t k = 0; k < n; ++k)
        if (!carried[k]) row -= lp[k] * dg[k][s];
      rows[s] = row;
      if (carried[s]) {
        explicit_lp[s] = row;
        resolve[lp[s]] = row;
      }
    }
    basis_rows = nu;
    for (std::size_t k = 0; k < n; ++k)
      if (!carried[k]) basis_rows.push_back(lp[k]);
    for (std::size_t s = 0; s < n; ++s) basis_rows.push_back(lm[s]);
  }

  // 4b. The costate jump of the state s: given explicitly where the map carries s, else a row.
  void check_costate_jump(EventParts& parts, std::size_t s) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    const std::string cid = "costate_jump:" + id + "_" + ctx.states[s];
    const CostateEntry& entry = e.costate_map[s];
    const std::string label = where + ".costate_map[" + ctx.costates[s] + "]";
    const std::string jump_rule = print(lm[s]) + " = nu^T dc/d" + print(xm[s]) + " + lambda(t+)^T dg/d" + print(xm[s]);
    if (!entry.given) {
      Check k = start(cid, "events", "structural");
      k.fail(label + " is missing: give lambda_" + ctx.states[s] + " just after " + id + " (" + jump_rule + ").");
      checks.push_back(k);
      return;
    }
    if (carried[s]) {
      if (entry.is_variable) {
        Check k = start(cid, "events", "structural");
        k.fail(label + " makes lambda_" + ctx.states[s] + "(t+) a shooting variable, but the map carries " +
               ctx.states[s] + " (dg_" + ctx.states[s] +
               "/dx- is the unit row), so its jump row gives it explicitly: expected " + print(lp[s]) + " = " +
               short_print(explicit_lp[s]) + " (" + jump_rule + ").");
        checks.push_back(k);
        return;
      }
      Check k = equality(cid, "events", label, "lambda_" + ctx.states[s] + "(t+) from " + jump_rule,
                         {explicit_lp[s], ctx.compile(explicit_lp[s]), {}}, entry.text, false);
      if (!k.pass) {
        const Linear lc = linear_compare(explicit_lp[s], entry.expr, basis_rows, lm[s], true);
        std::string why = lc.text();
        if (!lc.flipped.empty() &&
            std::any_of(nu.begin(), nu.end(), [&](const ex& v) { return lc.has(lc.flipped, print(v)); }))
          why += " (lambda(t+) = lambda(t-) - nu^T dc/dx-: the jump subtracts the multipliers)";
        else if (!lc.missing.empty() &&
                 std::any_of(nu.begin(), nu.end(), [&](const ex& v) { return lc.has(lc.missing, print(v)); }))
          why += " (psi constrains " + ctx.states[s] + " at " + id + ", so its costate jumps by -nu^T dc/dx-)";
        else {
          bool in_c = false;
          for (const auto& cj : c) in_c = in_c || cj.has(xm[s]);
          why += " (the map carries " + ctx.states[s] + " over, " + print(xp[s]) + " = " + short_print(g[s]) +
                 " with dg/d" + print(xm[s]) + " = 1, " +
                 (in_c ? std::string("so lambda_" + ctx.states[s] + " jumps by -nu^T dc/dx- only")
                       : std::string("and no row of c involves it, so lambda_" + ctx.states[s] +
                                     " does not jump: " + print(lp[s]) + " = " + print(lm[s]))) +
                 ")";
        }
        k.feedback = label + " = " + entry.text + " is not the costate jump at " + id + ": expected " + print(lp[s]) +
                     " = " + short_print(explicit_lp[s]) + " (" + jump_rule + ")" + (why.empty() ? "" : "; " + why) +
                     ".";
      }
      checks.push_back(k);
      return;
    }
    // Not carried: lambda(t+)_s is a shooting variable and the row an equation.
    Check k = start(cid, "events", "random_points+exact");
    const std::string row_text = short_print(rows[s]);
    if (!entry.is_variable) {
      k.fail(label + " = " + entry.text + " treats lambda_" + ctx.states[s] + " as given across " + id +
             ", but the map " + print(xp[s]) + " = " + short_print(g[s]) + " does not carry " + ctx.states[s] +
             " over (dg/dx- is not the unit row): lambda_" + ctx.states[s] + "(t+) is unknown; make it the shooting " +
             "variable " + print(lp[s]) + " (\"variable\") and add the jump row " + row_text + " = 0 as equation " +
             names::jump_row(id, ctx.states[s]) + ".");
      checks.push_back(k);
      return;
    }
    if (entry.variable != print(lp[s])) {
      k.fail(label + " names the variable '" + entry.variable + "'; lambda_" + ctx.states[s] + " just after " + id +
             " is the symbol " + print(lp[s]) + ".");
      checks.push_back(k);
      return;
    }
    const std::string ename = names::jump_row(id, ctx.states[s]);
    if (!matching_equation(ename, rows[s], k, resolve)) {
      const Equation* meant = named_equation(ename);
      if (meant) {
        const Linear lc = linear_compare(rows[s], meant->e.subs(resolve), basis_rows, lm[s]);
        k.fail("shooting equation '" + ename + "' (" + (meant->text.size() > 300 ? "..." : meant->text) +
               " = 0) is not the costate jump row " + jump_rule + ", i.e. " + row_text + " = 0" +
               (lc.ok() ? "" : ": " + lc.text()) + ".");
      } else {
        k.fail("missing costate jump row " + row_text + " = 0 at " + id + " (" + jump_rule + ", row " + ctx.states[s] +
               "; lambda_" + ctx.states[s] + "(t+) is the shooting variable " + print(lp[s]) +
               "); add it to shooting.equations as " + ename + ".");
      }
    }
    checks.push_back(k);
  }

  // 5. Free epoch: H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0, d/dt through the moving parameters.
  void check_event_time(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    std::vector<std::string> problems;
    std::set<std::string> labels;
    for (const auto& name : ctx.parameters) {
      const auto it = ctx.sources.find(name);
      if (it == ctx.sources.end() || it->second.rfind("ephemeris_rate:", 0) == 0) continue;
      bool used = false;
      for (const auto& r : e.psi) used = used || r.has(ctx.sym(name));
      if (used) labels.insert(it->second.substr(it->second.rfind(':') + 1));
    }
    std::map<std::string, ex> rates;
    for (const auto& l : labels)
      for (const auto& [name, rate] : rates_at(l, problems)) rates[name] = rate;
    {
      Check k = start("event_time:" + id, "events", "random_points+exact");
      if (e.Hm.empty() || e.Hp.empty())
        problems.push_back("event_values must declare H just before and just after " + id + " (kind hamiltonian, at " +
                           id + "_m and " + id + "_p)");
      if (!problems.empty()) {
        k.max_rel = 2;
        k.fail("cannot form the free-epoch condition of " + id + ": " + join(problems, "; ") + ".");
      } else {
        const std::string epoch = names::event_time(id);
        ex dphi = 0;
        for (std::size_t j = 0; j < c.size(); ++j) dphi += nu[j] * time_derivative(c[j], epoch, rates);
        for (std::size_t s = 0; s < n; ++s)
          dphi += (carried[s] ? explicit_lp[s] : lp[s]) * time_derivative(g[s], epoch, rates);
        const ex Hm = ctx.sym(e.Hm), Hp = ctx.sym(e.Hp);
        const ex expected = Hm - Hp + dphi;
        const std::string ename = names::time_row(id);
        const std::string want =
            "H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0, i.e. " + short_print(expected) + " = 0";
        if (!matching_equation(ename, expected, k, resolve)) {
          const Equation* meant = named_equation(ename);
          if (!meant)
            for (const auto& eq : ctx.equations)
              if (eq.ok && !meant && (eq.e.has(Hm) || eq.e.has(Hp))) meant = &eq;
          if (!meant) {
            k.fail("missing free-epoch condition of " + id + " " + want + "; add it to shooting.equations as " + ename +
                   ".");
          } else {
            std::vector<ex> basis{Hm, Hp};
            basis.insert(basis.end(), nu.begin(), nu.end());
            for (std::size_t s = 0; s < n; ++s)
              if (!carried[s]) basis.push_back(lp[s]);
            const ex given = meant->e.subs(resolve);
            const Linear lc = linear_compare(expected, given, basis, nu.empty() ? ex(0) : nu[0]);
            std::vector<std::string> why;
            const std::string hm = print(Hm), hp = print(Hp);
            if (!given.has(Hm) && !given.has(Hp))
              why.push_back("the jump of the Hamiltonian H(t-) - H(t+) = " + hm + " - " + hp + " is missing");
            else if (lc.has(lc.flipped, hm) && lc.has(lc.flipped, hp))
              why.push_back("the jump of the Hamiltonian has the wrong sign: it must be H(t-) - H(t+) = " + hm + " - " +
                            hp);
            bool rate_missing = false;
            for (const auto& name : lc.missing) rate_missing = rate_missing || (name != hm && name != hp);
            if (rate_missing && !dphi.is_zero())
              why.push_back("nu^T dpsi/dt is missing (" + short_print(dphi) + "): the target moves with the epoch " +
                            "(parameters " +
                            join(
                                [&] {
                                  std::vector<std::string> v;
                                  for (const auto& [name, rate] : rates) v.push_back(name + "' = " + print(rate));
                                  return v;
                                }(),
                                ", ") +
                            ")");
            if (why.empty() && !lc.ok()) why.push_back(lc.text());
            k.fail("shooting equation '" + meant->name + "' (" + (meant->text.size() > 300 ? "..." : meant->text) +
                   " = 0) is not the free-epoch condition of " + id + " " + want +
                   (why.empty() ? "" : ": " + join(why, "; ")) + ".");
          }
        }
      }
      checks.push_back(k);
    }
  }

  // 6. Stationarity in the free parameters of psi (Category C): nu^T dc/dq + lambda(t+)^T dg/dq = 0.
  void check_event_stationarity(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    for (const auto& q : e.free_params)
      if (std::find(params.begin(), params.end(), q) == params.end()) params.push_back(q);
    for (const auto& q : params) {
      Check k = start("event_stationarity:" + id + "_" + q, "events", "random_points+exact");
      ex expected = 0;
      for (std::size_t j = 0; j < c.size(); ++j) expected += nu[j] * derivative(c[j], ctx.sym(q));
      for (std::size_t s = 0; s < n; ++s)
        expected += (carried[s] ? explicit_lp[s] : lp[s]) * derivative(g[s], ctx.sym(q));
      const std::string ename = names::stationarity_row(id, q);
      const std::string want = "dPhi/d" + q + " = nu^T dc/d" + q + " + lambda(t+)^T dg/d" + q + " = 0";
      if (!matching_equation(ename, expected, k, resolve)) {
        const Equation* meant = named_equation(ename);
        if (meant) {
          std::vector<ex> basis = nu;
          for (std::size_t s = 0; s < n; ++s)
            if (!carried[s]) basis.push_back(lp[s]);
          const Linear lc = linear_compare(expected, meant->e.subs(resolve), basis);
          k.fail("shooting equation '" + ename + "' is not the stationarity condition " + want + " of the free " +
                 "parameter " + q + " of psi at " + id + (lc.ok() ? "" : ": " + lc.text()) + ".");
        } else {
          k.fail("missing stationarity condition " + want + " (" + q + " is a free parameter of psi at " + id + ": " +
                 short_print(expected) + " = 0); add it to shooting.equations as " + ename + ".");
        }
      }
      checks.push_back(k);
    }
  }

  // 7. The event's unknowns are shooting variables (Rule 0): its nu's, its epoch's fraction,
  //    lambda(t+) of the states the map does not carry, and the free parameters of psi.
  void check_event_unknowns(EventParts& parts) {
    auto& [e, id, where, n, xm, xp, lm, lp, c_rows, map_row, g, c, nu, carried, rows, explicit_lp, resolve, basis_rows,
           params] = parts;
    {
      Check k = start("event_unknowns:" + id, "counts", "structural");
      k.exact = true;
      const std::set<std::string> vars(ctx.variables.begin(), ctx.variables.end());
      std::vector<std::string> missing;
      for (const auto& v : nu)
        if (!vars.count(print(v))) missing.push_back(print(v) + " (multiplier of c)");
      for (const auto& v : e.time_vars)
        if (!vars.count(v)) missing.push_back(v + " (the epoch of " + id + ")");
      for (std::size_t s = 0; s < n; ++s)
        if (!carried[s] && !vars.count(print(lp[s])))
          missing.push_back(print(lp[s]) + " (lambda_" + ctx.states[s] + " after " + id + ", not carried by the map)");
      for (const auto& q : params)
        if (!vars.count(q)) missing.push_back(q + " (free parameter of psi)");
      if (!missing.empty()) k.fail("shooting.variables lacks " + join(missing, ", ") + " for the event " + id + ".");
      bool free_epoch = false;
      for (const auto& name : symbolic::free_symbols(e.time_expr)) free_epoch = free_epoch || vars.count(name);
      if (!free_epoch)
        k.fail(where + ".time.expression = " + e.time_text + " depends on no shooting variable: the epoch of " + id +
               " is free and must be an unknown of the shooting (Rule 0).");
      else if (e.time_vars.size() == 1 && e.window.size() == 2) {
        const ex lo = e.time_expr.subs(ctx.sym(e.time_vars[0]) == 0).evalf(),
                 hi = e.time_expr.subs(ctx.sym(e.time_vars[0]) == 1).evalf();
        if (!GiNaC::is_a<numeric>(lo) || !GiNaC::is_a<numeric>(hi) ||
            rel_diff(GiNaC::ex_to<numeric>(lo).to_double(), e.window[0]) > 1e-9 ||
            rel_diff(GiNaC::ex_to<numeric>(hi).to_double(), e.window[1]) > 1e-9)
          k.fail(where + ".time.expression = " + e.time_text + " does not run over the window [" + num(e.window[0]) +
                 ", " + num(e.window[1]) + "] as " + e.time_vars[0] + " goes from 0 to 1.");
      }
      checks.push_back(k);
    }
  }

  // A sliding departure (times.departure free): its times and its transversality condition.
  void check_departure() {
    if (!ctx.free_t0) return;
    check_t0_expression();
    check_sliding_departure();
  }

  // times.t0_expression: t0 slides with a shooting variable, tf = t0 + the fixed time of flight.
  void check_t0_expression() {
    Check c = start("t0_expression", "counts", "structural");
    c.exact = true;
    const std::set<std::string> vars(ctx.variables.begin(), ctx.variables.end());
    if (!ctx.t0_error.empty()) {
      c.fail(ctx.t0_error + ".");
    } else {
      std::vector<std::string> missing;
      bool used = false;
      for (const auto& name : symbolic::free_symbols(ctx.t0_expr)) {
        used = used || vars.count(name);
        if (std::find(ctx.t0_vars.begin(), ctx.t0_vars.end(), name) != ctx.t0_vars.end() && !vars.count(name))
          missing.push_back(name);
      }
      if (!missing.empty() || !used) {
        c.fail("times.t0_expression depends on no shooting variable" +
               (missing.empty() ? std::string() : " (" + join(missing, ", ") + " is not one)") +
               ": a sliding departure adds one shooting variable, t0_frac (Rule 0).");
      } else if (ctx.doc.times.tf) {
        const double tof = *ctx.doc.times.tf - ctx.doc.times.t0;
        const Compiled gap = ctx.compile(ctx.t0_tf_expr - ctx.t0_expr);
        for (const auto& p : ctx.points)
          if (rel_diff(gap(p), tof) > 1e-9) {
            c.fail("times.tf_expression - times.t0_expression must be the fixed time of flight " + num(tof) +
                   " (tf = t0 + tof moves with t0), got " + num(gap(p)) + ".");
            break;
          }
      }
    }
    checks.push_back(c);
  }

  // Sliding departure: -H(t0) + nu0^T dpsi0/dt0 + H(tf) + dPhi/dtf = 0 (tf = t0 + tof moves with
  // t0), nu0 from lambda(t0) = -nu0^T dpsi0/dx(t0), nu_f from lambda(tf) = lambda0 dphi/dx + nu_f^T dpsi_f/dx.
  void check_sliding_departure() {
    Check c = start("transversality_t0", "transversality", "random_points+exact");
    std::vector<std::string> problems;
    const std::map<std::string, ex> r0 = rates_at("t0", problems), rf = rates_at("tf", problems);
    std::string H0, Hf;
    for (const auto& v : ctx.event_values)
      if (v.hamiltonian && v.at == "t0")
        H0 = v.name;
      else if (v.hamiltonian && v.at == "tf")
        Hf = v.name;
    if (H0.empty() || Hf.empty())
      problems.push_back("event_values must declare the Hamiltonian at t0 and at tf (kind hamiltonian, at t0 / tf)");
    GiNaC::exmap to_t0, to_tf;
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      to_t0[ctx.sym(ctx.states[i])] = ctx.sym(names::at_t0(ctx.states[i]));
      to_t0[ctx.sym(ctx.costates[i])] = ctx.sym(names::at_t0(ctx.costates[i]));
      to_tf[ctx.sym(ctx.states[i])] = ctx.sym(names::at_tf(ctx.states[i]));
      to_tf[ctx.sym(ctx.costates[i])] = ctx.sym(names::at_tf(ctx.costates[i]));
    }
    ex depart, coupling, expected;
    try {
      if (!problems.empty()) throw std::invalid_argument(join(problems, "; "));
      std::vector<ex> psi0, d0, psif, df;
      for (const auto& k : ctx.constraints)
        for (const auto& e : k.psi) {
          const auto& rates = k.at == "t0" ? r0 : rf;
          const std::string epoch = k.at;
          (k.at == "t0" ? psi0 : psif).push_back(e);
          (k.at == "t0" ? d0 : df).push_back(time_derivative(e, epoch, rates));
        }
      const ex lambda0 = ctx.sym(ctx.multiplier);
      depart = -ctx.sym(H0) + nu_dot(psi0, d0, [&](std::size_t i) { return -ctx.sym(ctx.costates[i]); }).subs(to_t0);
      coupling = ctx.sym(Hf) + nu_dot(psif, df, [&](std::size_t i) {
                                 return ctx.sym(ctx.costates[i]) -
                                        lambda0 * ctx.endpoint_cost.diff(GiNaC::ex_to<symbol>(ctx.sym(ctx.states[i])));
                               }).subs(to_tf);
      if (ctx.slots.count("tf"))
        coupling += lambda0 * ctx.endpoint_cost.diff(GiNaC::ex_to<symbol>(ctx.sym("tf"))).subs(to_tf);
      depart = GiNaC::normal(depart).expand();
      coupling = GiNaC::normal(coupling).expand();
      expected = depart + coupling;
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail("cannot form the sliding-departure condition -H(t0) + dPhi/dt0 + H(tf) + dPhi/dtf = 0: " +
             std::string(e.what()) + ".");
      checks.push_back(c);
      return;
    }
    const std::string want = "-H(t0) + nu0^T dpsi0/dt0 + H(tf) + nu_f^T dpsi_f/dtf = 0, i.e. " + print(expected) +
                             " = 0 (t0 slides and tf = t0 + tof moves with it)";
    const std::string row = names::transversality_row("t0");
    if (!matching_equation(row, expected, c, {})) {
      const Equation* meant = named_equation(row);
      if (!meant)
        for (const auto& eq : ctx.equations)
          if (eq.ok && !meant && eq.e.has(ctx.sym(H0))) meant = &eq;
      if (!meant) {
        c.fail("missing sliding-departure condition " + want + "; add it to shooting.equations as " + row + ".");
      } else {
        std::vector<std::string> why;
        bool motion = false, tf_side = meant->e.has(ctx.sym(Hf));
        for (const auto& [name, rate] : r0)
          for (const auto& s : symbolic::free_symbols(rate)) motion = motion || meant->e.has(ctx.sym(s));
        for (const auto& l : ctx.costates) tf_side = tf_side || meant->e.has(ctx.sym(names::at_tf(l)));
        const ex motion_part = (depart + ctx.sym(H0)).expand();
        if (!motion && !motion_part.is_zero())
          why.push_back("the departure body's motion is missing (nu0^T dpsi0/dt0 = " + print(motion_part) +
                        ": the departure state moves with t0)");
        if (!tf_side)
          why.push_back("the coupling with tf is missing (H(tf) + dPhi/dtf = " + print(coupling) +
                        ": tf = t0 + tof moves with t0)");
        if (why.empty()) {
          std::vector<ex> basis{ctx.sym(H0), ctx.sym(Hf)};
          for (const auto& l : ctx.costates) {
            basis.push_back(ctx.sym(names::at_t0(l)));
            basis.push_back(ctx.sym(names::at_tf(l)));
          }
          const Linear lc = linear_compare(expected, meant->e, basis);
          if (!lc.ok()) why.push_back(lc.text());
        }
        c.fail("shooting equation '" + meant->name + "' (" + meant->text + " = 0) is not the sliding-departure " +
               "condition " + want + (why.empty() ? "" : ": " + join(why, "; ")) + ".");
      }
    }
    checks.push_back(c);
  }
};

}  // namespace

std::unique_ptr<Family> event_family(const Context& ctx) {
  return std::make_unique<EventFamily>(ctx);
}

}  // namespace helios::verify::detail

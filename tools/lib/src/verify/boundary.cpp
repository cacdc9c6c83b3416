// The boundary conditions: coasting targets, transversality and endpoint conditions (free final
// time included), and the times (tf_expression, event_values).
#include "family.hpp"

#include <set>
#include <stdexcept>

namespace helios::verify::detail {
namespace {

class BoundaryFamily : public Family {
 public:
  using Family::Family;

  std::vector<Check> run() override {
    check_coast();
    check_endpoints();
    check_times();
    return std::move(checks);
  }

 private:
  // Coasting targets: coast_dynamics.rhs must be the problem's own r, v dynamics with the controls
  // removed (throttle 0), so that the target obeys the same field (J2 included).
  void check_coast() {
    std::map<std::string, std::vector<std::string>> groups;
    for (const auto& [name, src] : ctx.sources)
      if (src.rfind("coast:", 0) == 0) groups[src.substr(6, src.rfind(':') - 6)].push_back(name);
    if (groups.empty() && !ctx.has_coast) return;
    Check c = start("coast_dynamics", "state_odes", "random_points+exact");
    std::vector<std::size_t> rv;
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      const Kind k = ctx.kinds[static_cast<std::size_t>(ctx.slot(ctx.states[i]))];
      if (k == Kind::Position || k == Kind::Velocity) rv.push_back(i);
    }
    std::set<std::string> ids;
    for (const auto& k : ctx.constraints) ids.insert(k.id);
    if (!ctx.has_coast) {
      c.fail(
          "parameters with source coast:<constraint>:tf exist but coast_dynamics is missing: give the "
          "uncontrolled dynamics that carries the target from t0.");
    } else if (!ctx.coast_error.empty()) {
      c.fail(ctx.coast_error + ".");
    } else if (ctx.coast_states.size() != rv.size() || ctx.coast_rhs.size() != rv.size()) {
      c.fail("coast_dynamics must have one state and one rhs per position and velocity state of the problem (" +
             std::to_string(rv.size()) + "), got " + std::to_string(ctx.coast_states.size()) + " states and " +
             std::to_string(ctx.coast_rhs.size()) + " rhs.");
    } else {
      for (const auto& [owner, names] : groups)
        if (!ids.count(owner))
          c.fail("parameters " + join(names, ", ") + " have source coast:" + owner + ":tf, but no constraint has id " +
                 owner + ".");
        else if (names.size() != ctx.coast_states.size())
          c.fail("the coasting target of " + owner + " has " + std::to_string(names.size()) +
                 " parameters but coast_dynamics has " + std::to_string(ctx.coast_states.size()) + " states.");
      GiNaC::exmap to_coast, off;
      for (std::size_t k = 0; k < rv.size(); ++k) to_coast[ctx.sym(ctx.states[rv[k]])] = ctx.sym(ctx.coast_states[k]);
      if (!ctx.throttle.empty()) off[ctx.sym(ctx.throttle)] = 0;
      for (std::size_t k = 0; k < rv.size() && c.pass; ++k) {
        const ex expected = ctx.state_rhs[rv[k]].subs(off).subs(to_coast);
        std::vector<std::string> left;
        for (const auto& name : symbolic::free_symbols(expected)) {
          const Kind kk = ctx.kinds[static_cast<std::size_t>(ctx.slot(name))];
          if (kk != Kind::Parameter && kk != Kind::Sourced &&
              std::find(ctx.coast_states.begin(), ctx.coast_states.end(), name) == ctx.coast_states.end())
            left.push_back(name);
        }
        const std::string& text = ctx.doc.coast_dynamics->rhs[k].text;
        if (!left.empty()) {
          c.fail("cannot form the uncontrolled dynamics of " + ctx.states[rv[k]] +
                 ": state_rhs with the throttle at 0 " + "still depends on " + join(left, ", ") + ".");
          break;
        }
        const Compiled ec = ctx.compile(expected), gc = ctx.compile(ctx.coast_rhs[k]);
        double worst = 0;
        for (const auto& p : ctx.points) worst = std::max(worst, rel_diff(ec(p), gc(p)));
        c.max_rel = std::max(c.max_rel, worst);
        if (worst > kTol && !exact_equal(expected, ctx.coast_rhs[k])) {
          const std::string t = term_diagnosis(expected, ctx.coast_rhs[k]);
          c.fail("coast_dynamics.rhs[" + std::to_string(k) + "] (the rate of " + ctx.coast_states[k] +
                 ") must be dynamics.state_rhs[" + ctx.states[rv[k]] + "] with the controls removed, expected " +
                 print(tidy(expected)) + ", got " + text + (t.empty() ? "" : "; " + t) +
                 " (the target moves in the same field as the spacecraft).");
        }
      }
      c.exact = c.pass;
    }
    checks.push_back(c);
  }

  void check_endpoints() {
    const ex lambda0 = ctx.sym(ctx.multiplier);
    GiNaC::exmap to_tf;
    for (const auto& s : ctx.states) to_tf[ctx.sym(s)] = ctx.sym(names::at_tf(s));
    // Final state: a state no psi fixes has lambda(tf) = lambda0 dphi/dx(tf) + nu^T dpsi/dx(tf), the
    // nu those of the constraints whose multipliers are unknowns (0 for a state no psi involves).
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      const std::string& s = ctx.states[i];
      if (ctx.fixed_at_tf.count(s)) continue;
      const symbol x = GiNaC::ex_to<symbol>(ctx.sym(s));
      ex expected = ctx.sym(names::at_tf(ctx.costates[i])) - lambda0 * ctx.endpoint_cost.diff(x);
      bool on_constraint = false;
      for (const auto& k : ctx.constraints)
        if (k.at == "tf" && k.multipliers_unknown)
          for (std::size_t j = 0; j < k.psi.size() && j < k.multipliers.size(); ++j) {
            const ex dpsi = k.psi[j].diff(x);
            if (dpsi.is_zero()) continue;
            expected -= ctx.sym(k.multipliers[j]) * dpsi;
            on_constraint = true;
          }
      expected = expected.subs(to_tf).expand();
      Check c = start("transversality:" + s, "transversality", "random_points+exact");
      find_equation(c, expected,
                    "missing transversality condition " + print(expected) + " = 0: " + s +
                        (on_constraint ? "(tf) moves along the final constraint's set, its multipliers unknowns"
                                       : "(tf) is free (no final constraint involves it)") +
                        "; add it to shooting.equations.");
      checks.push_back(c);
    }
    // Each final constraint component psi(x(tf)) = 0.
    for (const auto& k : ctx.constraints) {
      if (k.at != "tf") continue;
      for (std::size_t j = 0; j < k.psi.size(); ++j) {
        const ex expected = k.psi[j].subs(to_tf);
        Check c = start("endpoint:" + k.id + "_" + std::to_string(j + 1), "transversality", "random_points+exact");
        find_equation(c, expected,
                      "missing endpoint condition " + print(expected) + " = 0 (constraints[" + k.id + "].psi[" +
                          std::to_string(j) + "] at tf); add it to shooting.equations.");
        checks.push_back(c);
        const std::string name = names::constraint_row(k.id, j + 1);
        if (const auto* bound = inequality_of(name)) {
          const std::string nu = j < k.multipliers.size() ? k.multipliers[j] : "";
          if (is_identifier(nu)) check_bound(name, *bound, ctx.sym(nu));
        }
      }
    }
    // Initial state not fixed by a constraint: lambda(t0) = 0 (the endpoint cost is at tf).
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      const std::string& s = ctx.states[i];
      if (ctx.fixed_at_t0.count(s)) continue;
      Check c = start("transversality_t0:" + s, "transversality", "random_points+exact");
      const std::string lambda_t0 = names::at_t0(ctx.costates[i]);
      find_equation(c, ctx.sym(lambda_t0),
                    "missing transversality condition " + lambda_t0 + " = 0: " + s +
                        "(t0) is free (no initial constraint involves it); add it to shooting.equations.");
      checks.push_back(c);
    }
    for (const auto& k : ctx.constraints)
      if (k.at == "t0") check_initial_stationarity(k);
    if (ctx.free_tf) check_free_tf(to_tf);
  }

  // A free parameter q of psi at t0 (a departure orbit's anomaly): nu^T dpsi/dq = 0 with nu from
  // lambda(t0) = -nu^T dpsi/dx(t0).
  void check_initial_stationarity(const Constraint& k) {
    for (const auto& q : k.free_params) {
      Check c = start("initial_stationarity:" + k.id + "_" + q, "transversality", "random_points+exact");
      std::vector<ex> dpsi;
      for (const auto& e : k.psi) dpsi.push_back(e.diff(GiNaC::ex_to<symbol>(ctx.sym(q))));
      ex expected;
      try {
        expected = nu_dot(k.psi, dpsi, [&](std::size_t i) { return -ctx.sym(names::at_t0(ctx.costates[i])); });
        expected = GiNaC::normal(expected).expand();
      } catch (const std::exception& e) {
        c.max_rel = 2;
        c.fail("cannot form the stationarity condition of " + q + ": " + std::string(e.what()) + ".");
        checks.push_back(c);
        continue;
      }
      find_equation(c, expected,
                    "missing stationarity condition " + short_print(expected) + " = 0 (dPhi/d" + q + " = nu^T dpsi/d" +
                        q + " with lambda(t0) = -nu^T dpsi/dx: " + q +
                        " is a free parameter of psi at t0); add it to shooting.equations as " +
                        names::stationarity_row(k.id, q) + ".");
      checks.push_back(c);
    }
  }

  // Free final time: H(tf) + dPhi/dtf = 0 with Phi = lambda0 phi + nu.psi, where nu is eliminated
  // through lambda(tf) = dPhi/dx(tf) and dpsi/dtf comes from the parameters that move with tf.
  void check_free_tf(GiNaC::exmap to_tf) {
    Check c = start("transversality_tf", "transversality", "random_points+exact");
    for (const auto& l : ctx.costates) to_tf[ctx.sym(l)] = ctx.sym(names::at_tf(l));
    std::vector<std::string> problems;
    const std::map<std::string, ex> rates = rates_at("tf", problems);
    const EventValue* H_tf = nullptr;
    for (const auto& v : ctx.event_values)
      if (v.hamiltonian && v.at == "tf" && !H_tf) H_tf = &v;
    if (!H_tf)
      problems.push_back("event_values must declare the Hamiltonian at tf (e.g. {\"name\": \"" +
                         names::hamiltonian("tf") +
                         "\", \"meaning\": \"H at tf under the optimal control\"}) for the free-final-time condition");
    std::vector<ex> psi, dpsi;
    for (const auto& k : ctx.constraints)
      if (k.at == "tf")
        for (const auto& e : k.psi) {
          ex d = ctx.slots.count("tf") ? e.diff(GiNaC::ex_to<symbol>(ctx.sym("tf"))) : ex(0);
          for (const auto& [name, rate] : rates) d += e.diff(GiNaC::ex_to<symbol>(ctx.sym(name))) * rate;
          psi.push_back(e);
          dpsi.push_back(d);
        }
    // nu from m independent rows of lambda_i(tf) - lambda0 dphi/dx_i = sum_j nu_j dpsi_j/dx_i.
    const ex lambda0 = ctx.sym(ctx.multiplier);
    ex expected;
    try {
      if (!problems.empty()) throw std::invalid_argument(join(problems, "; "));
      expected = H_tf ? ctx.sym(H_tf->name) : ex(0);
      if (ctx.slots.count("tf")) expected += lambda0 * ctx.endpoint_cost.diff(GiNaC::ex_to<symbol>(ctx.sym("tf")));
      expected += nu_dot(psi, dpsi, [&](std::size_t i) {
        return ctx.sym(ctx.costates[i]) -
               lambda0 * ctx.endpoint_cost.diff(GiNaC::ex_to<symbol>(ctx.sym(ctx.states[i])));
      });
      expected = GiNaC::normal(expected.subs(to_tf)).expand();
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail("cannot form the free-final-time condition H(tf) + dPhi/dtf = 0: " + std::string(e.what()) + ".");
      checks.push_back(c);
      return;
    }
    const std::string want = print(expected) + " = 0 (H(tf) + dPhi/dtf = 0 with Phi = " + ctx.multiplier +
                             "*phi + nu.psi and nu eliminated through lambda(tf) = dPhi/dx(tf))";
    find_equation(c, expected, "missing free-final-time condition " + want + "; add it to shooting.equations.");
    if (!c.pass) {
      // Name the equation that was meant to be it: the one called transversality_tf, else the one using H_tf.
      const Equation* meant = nullptr;
      const std::string row = names::transversality_row("tf");
      for (const auto& eq : ctx.equations)
        if (eq.ok && (eq.name == row || (!meant && H_tf && eq.e.has(ctx.sym(H_tf->name))))) meant = &eq;
      if (meant) {
        const std::string t = term_diagnosis(expected, meant->e);
        c.feedback = "shooting equation '" + meant->name + "' (" + meant->text + " = 0) is not the free-final-time " +
                     "transversality condition " + want + (t.empty() ? "" : ": " + t) +
                     "; ephemeris targets contribute -lambda(tf).(target rate) through dpsi/dtf.";
      }
    }
    checks.push_back(c);
  }

  // tf_expression: with a free final time tf is an unknown of the shooting (Rule 0).
  void check_times() {
    if (!ctx.event_values.empty()) {
      Check c = start("event_values", "counts", "structural");
      c.exact = true;
      std::vector<std::string> unknown;
      for (const auto& v : ctx.event_values)
        if (!v.hamiltonian) unknown.push_back(v.name + " ('" + v.meaning + "')");
      if (!unknown.empty())
        c.fail("event_values " + join(unknown, ", ") +
               " cannot be recomputed (known: the Hamiltonian at tf under the optimal control, H_tf); express them "
               "in states, costates and parameters at tf instead.");
      checks.push_back(c);
    }
    if (!ctx.free_tf) return;
    Check c = start("tf_expression", "counts", "structural");
    c.exact = true;
    const std::vector<double>& w = ctx.doc.times.tf_window;
    if (!ctx.tf_error.empty()) {
      c.fail(ctx.tf_error + ".");
    } else if (w.size() != 2 || !(w[0] < w[1])) {
      c.fail("times.tf_window must be [lo, hi] with lo < hi (normalized time).");
    } else {
      const std::set<std::string> vars(ctx.variables.begin(), ctx.variables.end());
      std::vector<std::string> used, missing;
      for (const auto& name : symbolic::free_symbols(ctx.tf_expr)) {
        if (vars.count(name)) used.push_back(name);
        if (std::find(ctx.tf_vars.begin(), ctx.tf_vars.end(), name) != ctx.tf_vars.end() && !vars.count(name))
          missing.push_back(name);
      }
      if (!missing.empty())
        c.fail("times.tf_expression = " + ctx.tf_text + " uses " + join(missing, ", ") +
               ", which shooting.variables lacks: a free final time adds one shooting variable (Rule 0).");
      else if (used.empty())
        c.fail("times.tf_expression = " + ctx.tf_text +
               " depends on no shooting variable: a free final time must be an unknown of the shooting (Rule 0).");
    }
    checks.push_back(c);
  }
};

}  // namespace

std::unique_ptr<Family> boundary_family(const Context& ctx) {
  return std::make_unique<BoundaryFamily>(ctx);
}

}  // namespace helios::verify::detail

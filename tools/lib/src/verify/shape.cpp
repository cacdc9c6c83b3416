// The shooting system's shape (square, its variables, the symbols of its equations), the
// normalization of the multipliers (G1) and the use of every state (G4).
#include "family.hpp"

#include <cmath>
#include <set>

namespace helios::verify::detail {
namespace {

class ShapeFamily : public Family {
 public:
  using Family::Family;

  std::vector<Check> run() override {
    check_shooting_shape();
    check_normalization();
    check_state_usage();
    return std::move(checks);
  }

 private:
  void check_shooting_shape() {
    {
      Check c = start("count", "counts", "structural");
      c.exact = true;
      std::set<std::string> seen, dup;
      for (const auto& v : ctx.variables)
        if (!seen.insert(v).second) dup.insert(v);
      if (ctx.variables.size() != ctx.equations.size())
        c.fail("shooting has " + std::to_string(ctx.variables.size()) + " variables but " +
               std::to_string(ctx.equations.size()) + " equations: the shooting system must be square.");
      else if (!dup.empty())
        c.fail("shooting.variables lists " + join({dup.begin(), dup.end()}, ", ") + " more than once.");
      checks.push_back(c);
    }
    {
      Check c = start("shooting_variables", "counts", "structural");
      c.exact = true;
      const std::set<std::string> vars(ctx.variables.begin(), ctx.variables.end());
      std::vector<std::string> missing;
      if (!vars.count(ctx.multiplier)) missing.push_back(ctx.multiplier + " (the cost multiplier, G1)");
      for (std::size_t i = 0; i < ctx.states.size(); ++i)
        if (ctx.fixed_at_t0.count(ctx.states[i]) && !vars.count(names::at_t0(ctx.costates[i])))
          missing.push_back(names::at_t0(ctx.costates[i]) + " (" + ctx.states[i] +
                            "(t0) is fixed, so its costate at t0 is unknown)");
      std::vector<std::string> unknown;
      for (const auto& v : ctx.variables)
        if (!ctx.slots.count(v)) unknown.push_back("'" + v + "'");
      if (!missing.empty()) c.fail("shooting.variables lacks " + join(missing, ", ") + ".");
      if (!unknown.empty())
        c.fail("shooting.variables has " + join(unknown, ", ") + ", which are not symbols of this derivation.");
      checks.push_back(c);
    }
    {
      // Every symbol of an equation must be known when the shooting function evaluates it.
      Check c = start("equation_symbols", "counts", "structural");
      c.exact = true;
      std::set<std::string> allowed(ctx.variables.begin(), ctx.variables.end());
      allowed.insert(ctx.parameters.begin(), ctx.parameters.end());
      allowed.insert(ctx.eps);
      for (const auto& v : ctx.event_values) allowed.insert(v.name);
      // Around an interior event the shooting knows the states and costates just before and after
      // it (it propagates arc by arc) and its epoch.
      for (const auto& e : ctx.interior_events) {
        if (!e.error.empty()) continue;
        allowed.insert(names::event_time(e.id));
        for (std::size_t i = 0; i < ctx.states.size(); ++i)
          for (const auto& name : {ctx.states[i], ctx.costates[i]}) {
            allowed.insert(names::before(name, e.id));
            allowed.insert(names::after(name, e.id));
          }
      }
      for (std::size_t i = 0; i < ctx.states.size(); ++i)
        for (const auto& name :
             {names::at_t0(ctx.states[i]), names::at_tf(ctx.states[i]), names::at_tf(ctx.costates[i])})
          allowed.insert(name);
      std::vector<std::string> problems;
      for (const auto& eq : ctx.equations) {
        if (!eq.ok) {
          problems.push_back(eq.error);
          continue;
        }
        std::vector<std::string> bad;
        for (const auto& name : symbolic::free_symbols(eq.e))
          if (!allowed.count(name)) bad.push_back(name);
        if (!bad.empty())
          problems.push_back(
              "shooting equation '" + eq.name + "' uses " + join(bad, ", ") +
              ", not known at the shooting boundaries (use <state>_tf, <costate>_tf, <state>_t0, shooting "
              "variables and parameters)");
      }
      if (!problems.empty()) c.fail(join(problems, "; ") + ".");
      checks.push_back(c);
    }
  }

  void check_normalization() {
    Check c = start("normalization", "counts", "zero_set+exact");
    std::vector<std::string> sphere{ctx.multiplier};
    for (const auto& v : ctx.variables)
      for (const auto& l : ctx.costates)
        if (v == names::at_t0(l)) sphere.push_back(v);
    ex norm2 = 0;
    for (const auto& v : sphere) norm2 += GiNaC::pow(ctx.sym(v), 2);
    const ex expected = GiNaC::sqrt(norm2) - 1;
    const std::string want = "missing normalization equation " + print(expected) + " = 0 (G1: " + ctx.multiplier +
                             " must be inside the sphere normalization with the costates at t0)";
    std::vector<std::size_t> idx;
    for (const auto& v : sphere) idx.push_back(static_cast<std::size_t>(ctx.slot(v)));
    // Zero on the unit sphere of (multiplier, costates at t0), nonzero off it.
    auto test = [&](const Compiled& g, double& on_err) {
      on_err = 0;
      bool off_ok = true;
      for (const auto& p : ctx.points) {
        double n = 0;
        for (auto i : idx) n += p[i] * p[i];
        n = std::sqrt(n);
        if (!(n > 0)) continue;
        for (double radius : {1.0, 0.5, 1.7}) {
          Point q = p;
          for (auto i : idx) q[i] = p[i] * radius / n;
          const double v = g(q);
          if (radius == 1.0)
            on_err = std::max(on_err, rel_diff(v, 0));
          else if (!std::isfinite(v) || std::fabs(v) < 1e-6)
            off_ok = false;
        }
      }
      return on_err <= kTol && off_ok;
    };
    const Equation* named = nullptr;
    double best = 2;
    for (const auto& eq : ctx.equations) {
      if (eq.name == "normalization") named = &eq;
      if (!eq.ok) continue;
      double err = 0;
      // An equation free of the sphere's symbols cannot vanish on it and only on it.
      if (std::none_of(sphere.begin(), sphere.end(), [&](const std::string& v) { return eq.symbols.count(v) > 0; }))
        continue;
      if (test(eq.c, err)) {
        c.max_rel = err;
        c.exact = exact_equal(eq.e, expected) || exact_equal(eq.e, norm2 - 1);
        checks.push_back(c);
        return;
      }
      best = std::min(best, err);
    }
    c.max_rel = best;
    if (named && named->ok) {
      std::vector<std::string> left_out;
      for (const auto& v : sphere)
        if (!named->e.has(ctx.sym(v))) left_out.push_back(v);
      c.fail("shooting equation 'normalization' (" + named->text + " = 0) is not equivalent to " + print(expected) +
             " = 0" + (left_out.empty() ? "" : ": it leaves out " + join(left_out, ", ")) + " (G1: " + ctx.multiplier +
             " must be inside the sphere normalization with the costates at t0).");
    } else {
      c.fail(want + ".");
    }
    checks.push_back(c);
  }

  // G4: a state with identically zero dynamics that appears nowhere else is not a state.
  void check_state_usage() {
    Check c = start("state_usage", "counts", "structural");
    c.exact = true;
    std::vector<std::string> unused, constant;
    for (std::size_t i = 0; i < ctx.states.size(); ++i) {
      const ex x = ctx.sym(ctx.states[i]);
      if (!ctx.state_rhs[i].expand().is_zero()) continue;
      bool used = ctx.running_cost.has(x) || ctx.endpoint_cost.has(x);
      for (const auto& fj : ctx.state_rhs) used = used || fj.has(x);
      for (const auto& k : ctx.constraints)
        if (k.at == "tf")
          for (const auto& psi : k.psi) used = used || psi.has(x);
      if (!used)
        unused.push_back(ctx.states[i]);
      else if (ctx.fixed_at_t0.count(ctx.states[i]))
        constant.push_back(ctx.states[i]);
    }
    if (!unused.empty())
      c.fail("state(s) " + join(unused, ", ") +
             " have identically zero dynamics and appear in no other dynamics, cost or final "
             "constraint: they are not states of this problem; remove them (G4; e.g. a sail has no mass state).");
    if (!constant.empty())
      c.fail("state(s) " + join(constant, ", ") +
             " have identically zero dynamics and a fixed initial value: they are constants, not states; make them "
             "parameters and remove their costates and shooting variables (G4; e.g. a sail has no mass state).");
    checks.push_back(c);
  }
};

}  // namespace

std::unique_ptr<Family> shape_family(const Context& ctx) {
  return std::make_unique<ShapeFamily>(ctx);
}

}  // namespace helios::verify::detail

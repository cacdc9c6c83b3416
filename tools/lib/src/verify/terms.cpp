// The dynamics and the running cost as the sums of the terms the derivation lists (its field
// "terms"), each force recomputed by the verifier's own recomputation of its catalogue entry
// (verify/terms/, one file per term file of pmp/terms), the cost here: fuel and initial_mass
// Tmax/c (u - eps u (1 - u)) (with a solar-electric engine its recomputed T(r)/c), delta_v
// Tmax/mass (...), time 1, final_radius and final_energy Mayer terms. Checks: dynamics_terms
// (state_rhs equals the kinematics plus the forces' sum) and cost_terms (running_cost equals the
// cost term). A failure names the term: one missing, one with the wrong sign, one whose parameters
// are not the derivation's, or a part no term accounts for.
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "family.hpp"
#include "helios/derivation/terms.hpp"
#include "helios/pmp/catalogue.hpp"
#include "sail.hpp"
#include "terms/recompute.hpp"

namespace helios::verify::detail {

const recompute::Recomputation* recompute::find(const std::string& name) {
  static const std::vector<Recomputation> all = all_files();
  for (const auto& r : all)
    if (r.name == name) return &r;
  return nullptr;
}

namespace {

using derivation::Term;

// A term's contribution to each state's rate (0 where it has none).
struct Contribution {
  std::string name;
  std::vector<ex> rate;
  std::vector<ex> parameters;  // the symbols of its listed parameters
};

class TermFamily : public Family {
 public:
  explicit TermFamily(const Context& ctx) : Family(ctx) {}
  std::vector<Check> run() override;

 private:
  std::vector<ex> r_, v_;  // the position and velocity states
  ex m_ = 1;               // the mass state (1 without one)
  int mass_ = -1;          // its index
  std::vector<Point> points_;

  bool read_frame(Check& c);
  // The states read_frame found, with the listed terms, as a recomputation sees them.
  recompute::Frame frame(const std::vector<Term>& all) const { return {ctx, r_, v_, m_, mass_, all}; }
  void sample();
  std::optional<std::vector<ex>> parameters_of(const Term& t, const std::vector<std::size_t>& counts, Check& c) const;
  std::optional<Contribution> force(const Term& t, const std::vector<Term>& all, Check& c) const;
  double mismatch(const ex& given, const ex& expected, Check& c) const;
  bool depends(const ex& difference, const ex& expected, const ex& q) const;
  void diagnose(Check& c, std::size_t state, const std::vector<ex>& expected,
                const std::vector<Contribution>& parts) const;
  Check dynamics(const std::optional<std::vector<Term>>& terms);
  Check cost(const std::optional<std::vector<Term>>& terms);
};

// The position, velocity and mass states by their kinds.
bool TermFamily::read_frame(Check& c) {
  r_.clear();
  v_.clear();
  for (std::size_t i = 0; i < ctx.states.size(); ++i) {
    const Kind k = ctx.kinds[static_cast<std::size_t>(ctx.slot(ctx.states[i]))];
    if (k == Kind::Position) r_.push_back(ctx.sym(ctx.states[i]));
    if (k == Kind::Velocity) v_.push_back(ctx.sym(ctx.states[i]));
    if (k == Kind::Mass) {
      m_ = ctx.sym(ctx.states[i]);
      mass_ = static_cast<int>(i);
    }
  }
  if (r_.size() == 3 && v_.size() == 3) return true;
  c.fail("the states are not three positions and three velocities: the terms cannot be recomputed.");
  return false;
}

// The sample points with a random unit thrust direction and sail normal (drawn as 0 there).
void TermFamily::sample() {
  std::mt19937_64 rng(0x7E4D5ULL ^ ctx.options.seed);
  for (Point p : ctx.points) {
    if (ctx.directions.size() == 3) p = ctx.set_direction(p, random_unit(rng, 3));
    if (ctx.sails.size() == 3) {
      const auto n = random_unit(rng, 3);
      p = set_sail(ctx, p, {n[0], n[1], n[2]});
    }
    points_.push_back(p);
  }
}

// The symbols of a term's listed parameters, as many as one of `counts`, each a parameter of the
// derivation.
std::optional<std::vector<ex>> TermFamily::parameters_of(const Term& t, const std::vector<std::size_t>& counts,
                                                         Check& c) const {
  if (std::find(counts.begin(), counts.end(), t.parameters.size()) == counts.end()) {
    std::vector<std::string> allowed;
    for (const auto n : counts) allowed.push_back(std::to_string(n));
    c.fail("term " + t.name + " lists " + std::to_string(t.parameters.size()) + " parameter(s), it needs " +
           join(allowed, " or ") + ".");
    return std::nullopt;
  }
  std::vector<ex> out;
  for (const auto& name : t.parameters) {
    if (std::find(ctx.parameters.begin(), ctx.parameters.end(), name) == ctx.parameters.end()) {
      c.fail("term " + t.name + ": its parameter '" + name + "' is not a parameter of the derivation.");
      return std::nullopt;
    }
    out.push_back(ctx.sym(name));
  }
  return out;
}

// One force term's contribution to the velocities' (and the mass's) rates, by its recomputation.
std::optional<Contribution> TermFamily::force(const Term& t, const std::vector<Term>& all, Check& c) const {
  const recompute::Recomputation* recomputation = recompute::find(t.name);
  if (!recomputation) {
    c.fail("term " + t.name + " has no recomputation in the verifier (tools/lib/src/verify/terms/).");
    return std::nullopt;
  }
  const auto q = parameters_of(t, pmp::parameter_counts(*pmp::find_term(t.name)), c);
  if (!q) return std::nullopt;
  const auto rates = recomputation->rates(frame(all), t, *q, c);
  if (!rates) return std::nullopt;
  Contribution out{t.name + (t.body.empty() ? "" : " (" + t.body + ")") + (t.label.empty() ? "" : " (" + t.label + ")"),
                   std::vector<ex>(ctx.states.size(), 0), *q};
  for (std::size_t i = 0, k = 0; i < ctx.states.size() && k < 3; ++i)
    if (ctx.kinds[static_cast<std::size_t>(ctx.slot(ctx.states[i]))] == Kind::Velocity)
      out.rate[i] = rates->acceleration[k++];
  if (mass_ >= 0) out.rate[static_cast<std::size_t>(mass_)] = rates->mass_rate;
  return out;
}

// The largest relative difference of two expressions over the sample points (2 if one cannot
// be evaluated, with the reason in c).
double TermFamily::mismatch(const ex& given, const ex& expected, Check& c) const {
  try {
    const Compiled g = ctx.compile(given), e = ctx.compile(expected);
    double worst = 0;
    for (const auto& p : points_) worst = std::max(worst, rel_diff(g(p), e(p)));
    return worst;
  } catch (const std::exception& e) {
    c.fail(std::string("cannot evaluate the terms: ") + e.what() + ".");
    return 2;
  }
}

// Why state_rhs[state] is not the sum `expected`: a term missing, or with the wrong sign, or a
// part no listed term accounts for.
void TermFamily::diagnose(Check& c, std::size_t state, const std::vector<ex>& expected,
                          const std::vector<Contribution>& parts) const {
  const std::string where = "dynamics.state_rhs[" + ctx.states[state] + "]";
  Check scratch;
  for (const auto& part : parts) {
    if (part.rate[state].is_zero()) continue;
    if (mismatch(ctx.state_rhs[state], expected[state] - part.rate[state], scratch) <= kTol)
      return c.fail(where + " lacks the term " + part.name + ", or the term is listed but not in the dynamics.");
    if (mismatch(ctx.state_rhs[state], expected[state] - 2 * part.rate[state], scratch) <= kTol)
      return c.fail(where + ": the term " + part.name + " has the wrong sign.");
    if (mismatch(ctx.state_rhs[state] - expected[state], part.rate[state], scratch) <= kTol)
      return c.fail(where + " has the term " + part.name + " twice.");
  }
  std::vector<std::string> in, blamed;
  const ex difference = ctx.state_rhs[state] - expected[state];
  for (const auto& part : parts) {
    if (part.rate[state].is_zero()) continue;
    in.push_back(part.name);
    for (const auto& q : part.parameters)
      if (depends(difference, expected[state], q)) {
        blamed.push_back(part.name);
        break;
      }
  }
  // The parameters of the derivation no listed term uses, on which the difference depends.
  std::vector<std::string> unlisted;
  for (const auto& name : ctx.parameters) {
    bool listed = false;
    for (const auto& part : parts)
      for (const auto& q : part.parameters) listed = listed || GiNaC::ex_to<symbol>(q).get_name() == name;
    if (!listed && depends(difference, expected[state], ctx.sym(name))) unlisted.push_back(name);
  }
  c.fail(where + " is not the sum of its listed terms (" + join(in, ", ") + "): it differs by " +
         short_print(tidy(difference)) +
         (!unlisted.empty()
              ? " (it depends on " + join(unlisted, ", ") + ", parameters of no listed term: a term not listed)"
          : blamed.empty() ? std::string(" (a term not listed, or one of another form)")
                           : " (it depends on the parameters of " + join(blamed, ", ") +
                                 ": a parameter or the form of that term is not the listed one)") +
         ".");
}

// Whether `difference` varies with the parameter q, relative to how much `expected` does.
bool TermFamily::depends(const ex& difference, const ex& expected, const ex& q) const {
  try {
    const symbol& s = GiNaC::ex_to<symbol>(q);
    const Compiled dd = ctx.compile(difference.diff(s)), de = ctx.compile(expected.diff(s));
    for (const auto& p : points_)
      if (std::fabs(dd(p)) > 1e-9 * (1 + std::fabs(de(p)))) return true;
  } catch (const std::exception&) {
    // A derivative that cannot be evaluated blames no term: the feedback still prints the difference.
  }
  return false;
}

// "<check>: the derivation lists no terms" when it has no listing.
std::string no_terms() {
  return "the derivation lists no terms (field terms): list each term of the dynamics (" +
         join(derivation::force_term_names(), ", ") + ") and of the cost (" +
         join(derivation::cost_term_names(), ", ") + ") by name with the parameters it uses.";
}

Check TermFamily::dynamics(const std::optional<std::vector<Term>>& terms) {
  Check c = start("dynamics_terms", "state_odes", "random_points");
  if (!terms) return c.fail(no_terms()), c;
  if (!read_frame(c)) return c;
  std::vector<Contribution> parts;
  std::vector<ex> expected(ctx.states.size(), 0);
  for (std::size_t i = 0, k = 0; i < ctx.states.size(); ++i)
    if (ctx.kinds[static_cast<std::size_t>(ctx.slot(ctx.states[i]))] == Kind::Position) expected[i] = v_[k++];
  for (const auto& t : *terms) {
    if (t.kind != "force") continue;
    const auto part = force(t, *terms, c);
    if (!part) return c;
    for (std::size_t i = 0; i < expected.size(); ++i) expected[i] += part->rate[i];
    parts.push_back(*part);
  }
  if (!c.pass) return c;
  for (std::size_t i = 0; i < ctx.states.size(); ++i) {
    const double worst = mismatch(ctx.state_rhs[i], expected[i], c);
    c.max_rel = std::max(c.max_rel, worst);
    if (worst > kTol && c.pass) diagnose(c, i, expected, parts);
  }
  return c;
}

// The running and endpoint costs against the one cost term: fuel or initial_mass L = Tmax/c (u -
// eps u (1 - u)), delta_v (an engine of constant mass without an exhaust velocity) L = Tmax/mass (u -
// eps u (1 - u)), time L = 1; final_radius phi = -|r|, final_energy phi = -(|v|^2/2 - mu/|r|)
// (maximized), with L = 0. The other term's endpoint cost is 0.
Check TermFamily::cost(const std::optional<std::vector<Term>>& terms) {
  Check c = start("cost_terms", "hamiltonian", "random_points");
  if (!terms) return c.fail(no_terms()), c;
  std::vector<const Term*> costs;
  for (const auto& t : *terms)
    if (t.kind == "cost") costs.push_back(&t);
  if (costs.size() != 1)
    return c.fail("the derivation lists " + std::to_string(costs.size()) + " cost terms; the cost is one of " +
                  join(derivation::cost_term_names(), ", ") + "."),
           c;
  const Term& t = *costs[0];
  ex running = 1, endpoint = 0;
  if (t.name == "fuel" || t.name == "delta_v" || t.name == "initial_mass") {
    // With an engine whose flow is no ratio of two parameters (solar-electric) the cost lists the
    // engine's parameters and its flow is the engine's recomputed full-throttle flow.
    const recompute::Recomputation* engine = nullptr;
    if (t.name != "delta_v")
      for (const auto& f : *terms) {
        const recompute::Recomputation* r = recompute::find(f.name);
        if (f.kind == "force" && f.parameters == t.parameters && r && r->full_flow) engine = r;
      }
    const auto q = parameters_of(t, {engine ? t.parameters.size() : 2}, c);
    if (!q) return c;
    if (ctx.throttle.empty()) return c.fail("the cost term " + t.name + " needs a throttle control."), c;
    if (engine && !read_frame(c)) return c;
    const ex u = ctx.sym(ctx.throttle), eps = ctx.sym(ctx.eps);
    const ex flow = engine ? engine->full_flow(frame(*terms), *q) : (*q)[0] / (*q)[1];
    running = flow * (u - eps * u * (1 - u));
  } else if (t.name == "final_radius" || t.name == "final_energy") {
    const auto q = parameters_of(t, {t.name == "final_energy" ? 1u : 0u}, c);
    if (!q || !read_frame(c)) return c;
    const ex r = frame(*terms).radius();
    running = 0;
    endpoint = t.name == "final_radius" ? -r : -((v_[0] * v_[0] + v_[1] * v_[1] + v_[2] * v_[2]) / 2 - (*q)[0] / r);
  } else if (!t.parameters.empty()) {
    return c.fail("the cost term time has no parameters; it lists " + join(t.parameters, ", ") + "."), c;
  }
  c.max_rel = mismatch(ctx.running_cost, running, c);
  if (c.max_rel > kTol && c.pass)
    c.fail("dynamics.running_cost is not the cost term " + t.name + "'s L = " + print(running) + ": it differs by " +
           short_print(tidy(ctx.running_cost - running)) + ".");
  const double endpoint_rel = mismatch(ctx.endpoint_cost, endpoint, c);
  if (endpoint_rel > kTol && c.pass)
    c.fail("dynamics.endpoint_cost is not the cost term " + t.name + "'s phi = " + print(endpoint) +
           ": it differs by " + short_print(tidy(ctx.endpoint_cost - endpoint)) + ".");
  c.max_rel = std::max(c.max_rel, endpoint_rel);
  return c;
}

std::vector<Check> TermFamily::run() {
  sample();
  checks.push_back(dynamics(ctx.doc.terms));
  checks.push_back(cost(ctx.doc.terms));
  return checks;
}

}  // namespace

std::unique_ptr<Family> terms_family(const Context& ctx) {
  return std::make_unique<TermFamily>(ctx);
}

}  // namespace helios::verify::detail

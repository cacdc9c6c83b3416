// The dynamics and the running cost as the sums of the terms the derivation lists (its field
// "terms"), each term recomputed here from its parameters in the verifier's own way: gravity
// terms as the gradient of their potential (two_body mu/|r|; j2 -J2 mu R^2/(2 r^3) (3 z^2/r^2 - 1);
// third_body mu3 (1/|r3 - r| - r.r3/|r3|^3) with r3 rotated from the orbit's plane), the thruster
// Tmax u a/m with the mass flow -Tmax u/c (of constant mass: Tmax u a/mass, no mass flow), the sail ac (rref/r)^2
// (n.rhat)^2 n, a solar-electric engine T(r) u a/m with -T(r) u/c and T(r) = 2 eta P_in(r)/c of its own (the
// fuel's flow T(r)/c), a user acceleration as listed. Checks: dynamics_terms (state_rhs equals the kinematics plus the
// forces' sum) and cost_terms (running_cost equals the cost term). A failure names the term: one missing, one with the
// wrong sign, one whose parameters are not the derivation's, or a part no term accounts for.
#include <cmath>
#include <map>
#include <optional>
#include <random>

#include "family.hpp"
#include "helios/derivation/terms.hpp"
#include "sail.hpp"

namespace helios::verify::detail {
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
  void sample();
  std::optional<std::vector<ex>> parameters_of(const Term& t, std::size_t count, Check& c) const;
  std::optional<Contribution> force(const Term& t, const std::vector<Term>& all, Check& c) const;
  bool engine(const Term& t, const std::vector<ex>& q, Check& c, std::vector<ex>& a, Contribution& out) const;
  std::vector<ex> gradient(const ex& potential) const;
  std::vector<ex> third_body(const std::vector<ex>& q, Check& c, const std::string& body) const;
  ex solar_electric_thrust(const std::vector<ex>& q) const;
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

// The symbols of a term's listed parameters, `count` of them, each a parameter of the derivation.
std::optional<std::vector<ex>> TermFamily::parameters_of(const Term& t, std::size_t count, Check& c) const {
  if (t.parameters.size() != count) {
    c.fail("term " + t.name + " lists " + std::to_string(t.parameters.size()) + " parameter(s), it needs " +
           std::to_string(count) + ".");
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

std::vector<ex> TermFamily::gradient(const ex& potential) const {
  return {potential.diff(GiNaC::ex_to<symbol>(r_[0])), potential.diff(GiNaC::ex_to<symbol>(r_[1])),
          potential.diff(GiNaC::ex_to<symbol>(r_[2]))};
}

// A third body on its circular orbit: r3 = Rz(W) Rx(i) (a cos u, a sin u, 0), u = u0 + n t, its
// potential's gradient; the mean motion's value must be sqrt((mu + mu3)/a^3).
std::vector<ex> TermFamily::third_body(const std::vector<ex>& q, Check& c, const std::string& body) const {
  const ex &mu3 = q[0], &a = q[1], &inc = q[2], &W = q[3];
  if (!ctx.slots.count("t")) c.fail("term third_body (" + body + "): the dynamics do not depend on the time t.");
  const ex t = ctx.slots.count("t") ? ctx.sym("t") : ex(0);
  const ex u = q[4] + q[5] * t;
  const ex px = a * GiNaC::cos(u), py = a * GiNaC::sin(u);
  const ex yi = py * GiNaC::cos(inc), zi = py * GiNaC::sin(inc);
  const std::vector<ex> r3 = {GiNaC::cos(W) * px - GiNaC::sin(W) * yi, GiNaC::sin(W) * px + GiNaC::cos(W) * yi, zi};
  ex d2 = 0, rr3 = 0;
  for (int k = 0; k < 3; ++k) {
    d2 += GiNaC::pow(r3[k] - r_[k], 2);
    rr3 += r_[k] * r3[k];
  }
  return gradient(mu3 * (1 / GiNaC::sqrt(d2) - rr3 / GiNaC::pow(a, 3)));
}

// The value of a parameter of the derivation (a constant).
double value_of(const Context& ctx, const ex& symbol_) {
  return ctx.values[static_cast<std::size_t>(ctx.slot(GiNaC::ex_to<symbol>(symbol_).get_name()))];
}

// A solar-electric engine's full thrust, written here from the physics, not taken from pmp: the
// arrays' power falls as the inverse square of the Sun's distance d (in AU, the length unit), the
// bus takes its share (where a bus is, what is left floored at zero: the soft positive part of width
// 1% of the bus), the engine at most Pmax (the smooth minimum of width Pw), and the jet power
// eta P_in is T c / 2. q = P0, Pbus, eta, c[, Pmax, Pw].
ex TermFamily::solar_electric_thrust(const std::vector<ex>& q) const {
  const ex d = GiNaC::sqrt(r_[0] * r_[0] + r_[1] * r_[1] + r_[2] * r_[2]);
  const ex available = q[0] * GiNaC::pow(d, -2) - q[1];
  // max(x, 0) softened over a width w
  const auto soft_positive = [](const ex& x, const ex& w) { return (x + GiNaC::sqrt(x * x + w * w)) / 2; };
  const bool bus = value_of(ctx, q[1]) > 0;
  ex input = available;
  if (bus) input = soft_positive(available, q[1] / 100);
  if (q.size() == 6) {
    // At most Pmax: less the soft excess over it. Where a bus is, plus that excess at no power, so
    // that no power gives no thrust.
    if (bus)
      input += soft_positive(-q[4], q[5]) - soft_positive(available - q[4], q[5]);
    else
      input = q[4] - soft_positive(q[4] - available, q[5]);
  }
  return 2 * q[2] * input / q[3];
}

// The central body's mu: the parameter of the listed two_body term.
std::optional<ex> central_mu(const Context& ctx, const std::vector<Term>& all) {
  for (const auto& t : all)
    if (t.name == "two_body" && t.parameters.size() == 1 && ctx.slots.count(t.parameters[0]))
      return ctx.sym(t.parameters[0]);
  return std::nullopt;
}

// Whether a force term is an engine (TermFamily::engine).
bool engine_name(const std::string& name) {
  return name == "thrust" || name == "full_thrust" || name.rfind("constant_mass_", 0) == 0 ||
         name == "solar_electric_thrust";
}

// One force term's contribution to the velocities' (and the mass's) rates.
std::optional<Contribution> TermFamily::force(const Term& t, const std::vector<Term>& all, Check& c) const {
  static const std::map<std::string, std::size_t> counts = {{"two_body", 1},
                                                            {"j2", 2},
                                                            {"solar_sail", 2},
                                                            {"thrust", 2},
                                                            {"full_thrust", 2},
                                                            {"user_acceleration", 0},
                                                            {"third_body", 6},
                                                            {"constant_mass_thrust", 2},
                                                            {"constant_mass_full_thrust", 2},
                                                            {"solar_electric_thrust", 4}};
  // An engine of constant mass lists Tmax and its mass, and the exhaust velocity where a specific
  // impulse prices its propellant (used by the cost alone).
  const bool constant_mass = t.name.rfind("constant_mass_", 0) == 0;
  // A solar-electric engine lists P0, Pbus, eta, c and, with a cap, Pmax and the cap's width Pw.
  const bool sep = t.name == "solar_electric_thrust";
  const auto q = parameters_of(t,
                               (constant_mass && t.parameters.size() == 3) || (sep && t.parameters.size() == 6)
                                   ? t.parameters.size()
                                   : counts.at(t.name),
                               c);
  if (!q) return std::nullopt;
  Contribution out{t.name + (t.body.empty() ? "" : " (" + t.body + ")") + (t.label.empty() ? "" : " (" + t.label + ")"),
                   std::vector<ex>(ctx.states.size(), 0), *q};
  std::vector<ex> a;
  const ex r = GiNaC::sqrt(r_[0] * r_[0] + r_[1] * r_[1] + r_[2] * r_[2]);
  const auto mu = central_mu(ctx, all);
  if ((t.name == "j2" || t.name == "third_body") && !mu) {
    c.fail("term " + t.name + " needs the central body's mu, the parameter of a two_body term.");
    return std::nullopt;
  }
  if (t.name == "two_body") {
    a = gradient((*q)[0] / r);
  } else if (t.name == "j2") {
    const ex z = r_[2];
    a = gradient(-(*q)[0] * (*mu) * (*q)[1] * (*q)[1] / (2 * GiNaC::pow(r, 3)) * (3 * z * z / (r * r) - 1));
  } else if (t.name == "third_body") {
    a = third_body(*q, c, t.body);
    const double n = value_of(ctx, (*q)[5]), a3 = value_of(ctx, (*q)[1]);
    const double want = std::sqrt((value_of(ctx, *mu) + value_of(ctx, (*q)[0])) / (a3 * a3 * a3));
    if (rel_diff(n, want) > kTol)
      c.fail("term third_body (" + t.body + "): its mean motion " + t.parameters[5] + " = " + num(n) +
             " is not sqrt((mu + mu3)/a^3) = " + num(want) + ".");
  } else if (engine_name(t.name)) {
    if (!engine(t, *q, c, a, out)) return std::nullopt;
  } else if (t.name == "solar_sail") {
    if (ctx.sails.size() != 3) {
      c.fail("term solar_sail needs three sail_normal controls.");
      return std::nullopt;
    }
    ex nr = 0;
    for (int k = 0; k < 3; ++k) nr += ctx.sym(ctx.sails[k]) * r_[k];
    for (const auto& n : ctx.sails)
      a.push_back((*q)[0] * GiNaC::pow((*q)[1], 2) * nr * nr * ctx.sym(n) / GiNaC::pow(r, 4));
  } else {  // user_acceleration: its components as listed
    try {
      for (std::size_t k = 0; k < 3; ++k)
        a.push_back(
            ctx.statement(t.acceleration[k], "terms (" + t.label + ").acceleration[" + std::to_string(k) + "]"));
    } catch (const std::exception& e) {
      c.fail("term user_acceleration (" + t.label + "): " + e.what() + ".");
      return std::nullopt;
    }
  }
  for (std::size_t i = 0, k = 0; i < ctx.states.size() && k < 3; ++i)
    if (ctx.kinds[static_cast<std::size_t>(ctx.slot(ctx.states[i]))] == Kind::Velocity) out.rate[i] = a[k++];
  return out;
}

// An engine term's acceleration a and mass rate (into out.rate), its parameters q; false (with the
// reason in c) where the controls or the states do not fit it.
bool TermFamily::engine(const Term& t, const std::vector<ex>& q, Check& c, std::vector<ex>& a,
                        Contribution& out) const {
  if (t.name == "thrust") {
    if (ctx.throttle.empty() || ctx.directions.size() != 3 || mass_ < 0) {
      c.fail("term thrust needs a throttle, three direction controls and a mass state.");
      return false;
    }
    const ex u = ctx.sym(ctx.throttle);
    for (const auto& d : ctx.directions) a.push_back(q[0] * u * ctx.sym(d) / m_);
    out.rate[static_cast<std::size_t>(mass_)] = -q[0] * u / q[1];
  } else if (t.name == "full_thrust") {  // u = 1 throughout: no throttle control
    if (!ctx.throttle.empty() || ctx.directions.size() != 3 || mass_ < 0) {
      c.fail("term full_thrust needs three direction controls, a mass state and no throttle (it is 1 throughout).");
      return false;
    }
    for (const auto& d : ctx.directions) a.push_back(q[0] * ctx.sym(d) / m_);
    out.rate[static_cast<std::size_t>(mass_)] = -q[0] / q[1];
  } else if (t.name.rfind("constant_mass_", 0) == 0) {  // Tmax u a / mass, no mass state and no mass flow
    const bool full = t.name == "constant_mass_full_thrust";
    if (ctx.throttle.empty() != full || ctx.directions.size() != 3 || mass_ >= 0) {
      c.fail("term " + t.name + " needs three direction controls, " + (full ? "no throttle" : "a throttle") +
             " and no mass state (its mass is the parameter " + t.parameters[1] + ").");
      return false;
    }
    if (rel_diff(value_of(ctx, q[1]), 1.0) > kTol)
      c.fail("term " + t.name + ": its mass " + t.parameters[1] + " = " + num(value_of(ctx, q[1])) +
             " is not 1, the mass unit (the constant mass sets it).");
    const ex u = full ? ex(1) : ctx.sym(ctx.throttle);
    for (const auto& d : ctx.directions) a.push_back(q[0] * u * ctx.sym(d) / q[1]);
  } else {  // T(r) u a / m and -T(r) u / c, T(r) recomputed here (solar_electric_thrust below)
    if (ctx.throttle.empty() || ctx.directions.size() != 3 || mass_ < 0) {
      c.fail("term solar_electric_thrust needs a throttle, three direction controls and a mass state.");
      return false;
    }
    if (q.size() == 6 && rel_diff(value_of(ctx, q[5]), 0.01 * value_of(ctx, q[4])) > kTol)
      c.fail("term solar_electric_thrust: its cap width " + t.parameters[5] + " = " + num(value_of(ctx, q[5])) +
             " is not 1% of its maximum input power " + t.parameters[4] + ".");
    const ex u = ctx.sym(ctx.throttle), T = solar_electric_thrust(q);
    for (const auto& d : ctx.directions) a.push_back(T * u * ctx.sym(d) / m_);
    out.rate[static_cast<std::size_t>(mass_)] = -T * u / q[3];
  }
  return true;
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
const char* kNoTerms =
    "the derivation lists no terms (field terms): list each term of the dynamics (two_body, j2, solar_sail, thrust, "
    "full_thrust, constant_mass_thrust, constant_mass_full_thrust, solar_electric_thrust, user_acceleration, "
    "third_body) and of the cost "
    "(fuel, delta_v, time, initial_mass, final_radius, final_energy) by name with the parameters it uses.";

Check TermFamily::dynamics(const std::optional<std::vector<Term>>& terms) {
  Check c = start("dynamics_terms", "state_odes", "random_points");
  if (!terms) return c.fail(kNoTerms), c;
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
  if (!terms) return c.fail(kNoTerms), c;
  std::vector<const Term*> costs;
  for (const auto& t : *terms)
    if (t.kind == "cost") costs.push_back(&t);
  if (costs.size() != 1)
    return c.fail("the derivation lists " + std::to_string(costs.size()) +
                  " cost terms; the cost is one of fuel, delta_v, time, initial_mass, final_radius, final_energy."),
           c;
  const Term& t = *costs[0];
  ex running = 1, endpoint = 0;
  if (t.name == "fuel" || t.name == "delta_v" || t.name == "initial_mass") {
    // With a solar-electric engine the fuel's flow is T(r)/c, listed with the engine's parameters.
    const bool sep = t.name != "delta_v" && (t.parameters.size() == 4 || t.parameters.size() == 6);
    const auto q = parameters_of(t, sep ? t.parameters.size() : 2, c);
    if (!q) return c;
    if (ctx.throttle.empty()) return c.fail("the cost term " + t.name + " needs a throttle control."), c;
    if (sep && !read_frame(c)) return c;
    const ex u = ctx.sym(ctx.throttle), eps = ctx.sym(ctx.eps);
    running = (sep ? solar_electric_thrust(*q) / (*q)[3] : (*q)[0] / (*q)[1]) * (u - eps * u * (1 - u));
  } else if (t.name == "final_radius" || t.name == "final_energy") {
    const auto q = parameters_of(t, t.name == "final_energy" ? 1 : 0, c);
    if (!q || !read_frame(c)) return c;
    const ex r = GiNaC::sqrt(r_[0] * r_[0] + r_[1] * r_[1] + r_[2] * r_[2]);
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

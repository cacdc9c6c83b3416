// third_body: a point mass on its circular orbit, r3 = Rz(W) Rx(i) (a cos u, a sin u, 0) with
// u = u0 + n t, the gradient of its potential mu3 (1/|r3 - r| - r.r3/|r3|^3) (direct and indirect
// parts); the mean motion's value must be sqrt((mu + mu3)/a^3).
#include <cmath>

#include "recompute.hpp"

namespace helios::verify::detail::recompute {
namespace {

std::optional<Rates> rates(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) {
  const std::string who = "third_body (" + t.body + ")";
  const auto mu = x.central_mu(who, c);
  if (!mu) return std::nullopt;
  const Context& ctx = x.ctx;
  const ex &mu3 = q[0], &a = q[1], &inc = q[2], &W = q[3];
  if (!ctx.slots.count("t")) c.fail("term " + who + ": the dynamics do not depend on the time t.");
  const ex time = ctx.slots.count("t") ? ctx.sym("t") : ex(0);
  const ex u = q[4] + q[5] * time;
  const ex px = a * GiNaC::cos(u), py = a * GiNaC::sin(u);
  const ex yi = py * GiNaC::cos(inc), zi = py * GiNaC::sin(inc);
  const std::vector<ex> r3 = {GiNaC::cos(W) * px - GiNaC::sin(W) * yi, GiNaC::sin(W) * px + GiNaC::cos(W) * yi, zi};
  ex d2 = 0, rr3 = 0;
  for (int k = 0; k < 3; ++k) {
    d2 += GiNaC::pow(r3[k] - x.r[k], 2);
    rr3 += x.r[k] * r3[k];
  }
  const double n = x.value(q[5]), a3 = x.value(q[1]);
  const double want = std::sqrt((x.value(*mu) + x.value(q[0])) / (a3 * a3 * a3));
  if (rel_diff(n, want) > kTol)
    c.fail("term " + who + ": its mean motion " + t.parameters[5] + " = " + num(n) +
           " is not sqrt((mu + mu3)/a^3) = " + num(want) + ".");
  return Rates{x.gradient(mu3 * (1 / GiNaC::sqrt(d2) - rr3 / GiNaC::pow(a, 3)))};
}

}  // namespace

std::vector<Recomputation> third_body() {
  return {{"third_body", rates}};
}

}  // namespace helios::verify::detail::recompute

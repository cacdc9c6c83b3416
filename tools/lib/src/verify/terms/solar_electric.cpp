// solar_electric_thrust: T(r) u a/m with the mass flow -T(r) u/c, T(r) = 2 eta P_in(r)/c written
// here from the physics, not taken from pmp: the arrays' power falls as the inverse square of the
// Sun's distance d (in AU, the length unit), the bus takes its share (where a bus is, what is left
// floored at zero: the soft positive part of width 1% of the bus), the engine at most Pmax (the
// smooth minimum of width Pw), and the jet power eta P_in is T c / 2. q = P0, Pbus, eta, c[, Pmax, Pw].
#include "recompute.hpp"

namespace helios::verify::detail::recompute {
namespace {

ex full_thrust(const Frame& x, const std::vector<ex>& q) {
  const ex d = x.radius();
  const ex available = q[0] * GiNaC::pow(d, -2) - q[1];
  // max(y, 0) softened over a width w
  const auto soft_positive = [](const ex& y, const ex& w) { return (y + GiNaC::sqrt(y * y + w * w)) / 2; };
  const bool bus = x.value(q[1]) > 0;
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

std::optional<Rates> rates(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) {
  const Context& ctx = x.ctx;
  if (ctx.throttle.empty() || ctx.directions.size() != 3 || x.mass < 0) {
    c.fail("term solar_electric_thrust needs a throttle, three direction controls and a mass state.");
    return std::nullopt;
  }
  if (q.size() == 6 && rel_diff(x.value(q[5]), 0.01 * x.value(q[4])) > kTol)
    c.fail("term solar_electric_thrust: its cap width " + t.parameters[5] + " = " + num(x.value(q[5])) +
           " is not 1% of its maximum input power " + t.parameters[4] + ".");
  const ex u = ctx.sym(ctx.throttle), T = full_thrust(x, q);
  Rates out;
  for (const auto& d : ctx.directions) out.acceleration.push_back(T * u * ctx.sym(d) / x.m);
  out.mass_rate = -T * u / q[3];
  return out;
}

}  // namespace

std::vector<Recomputation> solar_electric() {
  return {{"solar_electric_thrust", rates,
           [](const Frame& x, const std::vector<ex>& q) { return full_thrust(x, q) / q[3]; }}};
}

}  // namespace helios::verify::detail::recompute

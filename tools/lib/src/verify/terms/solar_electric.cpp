// solar_electric_thrust: T(r) u a/m with the mass flow -T(r) u/c, T(r) = 2 eta P_in(r)/c written
// here from the physics, not taken from pmp: the arrays' power falls as the inverse square of the
// Sun's distance d (in AU, the length unit), the bus takes its share (where a bus is, what is left
// floored at zero: the soft positive part of width 1% of the bus), the engine at most Pmax (the
// smooth minimum of width Pw), and the jet power eta P_in is T c / 2. q = P0, Pbus, eta, c[, Pmax, Pw].
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

ex input_power(const Frame& x, const ex& P0, const ex& Pbus, const ex& Pmax, const ex& Pw) {
  const ex d = x.radius();
  const ex available = P0 * GiNaC::pow(d, -2) - Pbus;
  // max(y, 0) softened over a width w
  const auto soft_positive = [](const ex& y, const ex& w) { return (y + GiNaC::sqrt(y * y + w * w)) / 2; };
  const bool bus = x.value(Pbus) > 0;
  ex input = available;
  if (bus) input = soft_positive(available, Pbus / 100);
  if (!Pmax.is_zero()) {
    // At most Pmax: less the soft excess over it. Where a bus is, plus that excess at no power, so
    // that no power gives no thrust.
    if (bus)
      input += soft_positive(-Pmax, Pw) - soft_positive(available - Pmax, Pw);
    else
      input = Pmax - soft_positive(Pmax - available, Pw);
  }
  return input;
}

namespace {

ex full_thrust(const Frame& x, const std::vector<ex>& q) {
  return 2 * q[2] * input_power(x, q[0], q[1], q.size() == 6 ? q[4] : ex(0), q.size() == 6 ? q[5] : ex(0)) / q[3];
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

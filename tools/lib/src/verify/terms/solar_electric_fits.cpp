// solar_electric_fitted_thrust: T u a/m with the mass flow -F u, T and F the thruster's fits in its
// input power P, written here from the physics, not taken from pmp: P is solar_electric_thrust's
// (the arrays' power at the Sun's distance less the bus, capped at the top of the fits' range Pmax
// over Pw = 1% of it), T = sum_k T_k P^k and F = sum_k F_k P^k, both switched off below the range's
// bottom Pmin (where one is listed) by the logistic step of width Pn = 1% of Pmin.
// q = P0, Pbus, Pmax, Pw, T0..T4, F0..F4[, Pmin, Pn].
#include "recompute.hpp"

namespace helios::verify::detail::recompute {
namespace {

constexpr std::size_t kFirstThrust = 4, kFirstFlow = 9, kStep = 14;

// The fit whose coefficients start at q[first], at the input power, switched off below Pmin.
ex fitted(const Frame& x, const std::vector<ex>& q, std::size_t first) {
  const ex P = input_power(x, q[0], q[1], q[2], q[3]);
  ex sum = 0;
  for (std::size_t k = 5; k-- > 0;) sum = sum * P + q[first + k];  // Horner
  if (q.size() > kStep) sum /= 1 + GiNaC::exp((q[kStep] - P) / q[kStep + 1]);
  return sum;
}

std::optional<Rates> rates(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) {
  const Context& ctx = x.ctx;
  if (ctx.throttle.empty() || ctx.directions.size() != 3 || x.mass < 0) {
    c.fail("term solar_electric_fitted_thrust needs a throttle, three direction controls and a mass state.");
    return std::nullopt;
  }
  for (const std::size_t at : {std::size_t{2}, kStep})
    if (q.size() > at + 1 && rel_diff(x.value(q[at + 1]), 0.01 * x.value(q[at])) > kTol)
      c.fail("term solar_electric_fitted_thrust: its width " + t.parameters[at + 1] + " = " + num(x.value(q[at + 1])) +
             " is not 1% of " + t.parameters[at] + ".");
  const ex u = ctx.sym(ctx.throttle), T = fitted(x, q, kFirstThrust);
  Rates out;
  for (const auto& d : ctx.directions) out.acceleration.push_back(T * u * ctx.sym(d) / x.m);
  out.mass_rate = -fitted(x, q, kFirstFlow) * u;
  return out;
}

}  // namespace

std::vector<Recomputation> solar_electric_fits() {
  return {{"solar_electric_fitted_thrust", rates,
           [](const Frame& x, const std::vector<ex>& q) { return fitted(x, q, kFirstFlow); }}};
}

}  // namespace helios::verify::detail::recompute

// The thrusters of constant thrust: thrust Tmax u a/m with the mass flow -Tmax u/c; full_thrust at
// u = 1 (no throttle control); of constant mass (constant_mass_thrust, constant_mass_full_thrust)
// Tmax u a/mass with the mass a parameter, 1 (the mass unit), and no mass state or flow.
#include "recompute.hpp"

namespace helios::verify::detail::recompute {
namespace {

std::optional<Rates> variable_mass(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) {
  const Context& ctx = x.ctx;
  const bool full = t.name == "full_thrust";
  if (ctx.throttle.empty() != full || ctx.directions.size() != 3 || x.mass < 0) {
    c.fail(full ? "term full_thrust needs three direction controls, a mass state and no throttle (it is 1 throughout)."
                : "term thrust needs a throttle, three direction controls and a mass state.");
    return std::nullopt;
  }
  const ex u = full ? ex(1) : ctx.sym(ctx.throttle);
  Rates out;
  for (const auto& d : ctx.directions) out.acceleration.push_back(q[0] * u * ctx.sym(d) / x.m);
  out.mass_rate = -q[0] * u / q[1];
  return out;
}

// Lists Tmax and its mass, and the exhaust velocity where a specific impulse prices its propellant
// (used by the cost alone).
std::optional<Rates> constant_mass(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) {
  const Context& ctx = x.ctx;
  const bool full = t.name == "constant_mass_full_thrust";
  if (ctx.throttle.empty() != full || ctx.directions.size() != 3 || x.mass >= 0) {
    c.fail("term " + t.name + " needs three direction controls, " + (full ? "no throttle" : "a throttle") +
           " and no mass state (its mass is the parameter " + t.parameters[1] + ").");
    return std::nullopt;
  }
  if (rel_diff(x.value(q[1]), 1.0) > kTol)
    c.fail("term " + t.name + ": its mass " + t.parameters[1] + " = " + num(x.value(q[1])) +
           " is not 1, the mass unit (the constant mass sets it).");
  const ex u = full ? ex(1) : ctx.sym(ctx.throttle);
  Rates out;
  for (const auto& d : ctx.directions) out.acceleration.push_back(q[0] * u * ctx.sym(d) / q[1]);
  return out;
}

}  // namespace

std::vector<Recomputation> thrust() {
  return {{"thrust", variable_mass},
          {"full_thrust", variable_mass},
          {"constant_mass_thrust", constant_mass},
          {"constant_mass_full_thrust", constant_mass}};
}

}  // namespace helios::verify::detail::recompute

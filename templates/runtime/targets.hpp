// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, targets (templates/runtime/targets.hpp): where the targets are: the
// ephemeris model, its rate, and a coasting target's state.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

// Ephemeris mode "jpl_lp": a planet's heliocentric state at normalized time t after the epoch of
// t0, in normalized units.
// A body of kProblem.orbit_bodies is propagated on its Keplerian orbit instead.
namespace {
const OrbitBody* orbit_body(const std::string& body) {
  for (int k = 0; k < kProblem.num_orbit_bodies; ++k)
    if (body == kProblem.orbit_bodies[k].name) return &kProblem.orbit_bodies[k];
  return nullptr;
}
}  // namespace

std::array<double, 6> ephemeris_state(const std::string& body, double t) {
  if (const OrbitBody* b = orbit_body(body)) {
    const double* el = b->elements;
    const helios::astro::Elements elements{el[0], el[1], el[2], el[3], el[4], el[5]};
    return helios::astro::propagate(helios::astro::elements_to_state(elements, kProblem.mu), t - el[6], kProblem.mu);
  }
  const auto s = helios::astro::jpl_lp_state(helios::astro::planet_from_name(body),
                                             kProblem.epoch_mjd2000 + t * kProblem.time_unit_days);
  return {s[0] / kProblem.length_unit_km,  s[1] / kProblem.length_unit_km,  s[2] / kProblem.length_unit_km,
          s[3] / kProblem.speed_unit_km_s, s[4] / kProblem.speed_unit_km_s, s[5] / kProblem.speed_unit_km_s};
}

// Time derivative of the ephemeris model itself, as a free event time's transversality condition
// needs. A body of kProblem.orbit_bodies moves exactly on its Kepler orbit: (v, -mu r/|r|^3). A
// JPL low-precision planet's elements drift, so its rate is not the Kepler velocity the model
// reports: the model's exact derivative, drift included (astro::jpl_lp_state_rate).
std::array<double, 6> ephemeris_rate(const std::string& body, double t) {
  if (orbit_body(body)) {
    const auto s = ephemeris_state(body, t);
    const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), k = -kProblem.mu / (r * r * r);
    return {s[3], s[4], s[5], k * s[0], k * s[1], k * s[2]};
  }
  const auto d = helios::astro::jpl_lp_state_rate(helios::astro::planet_from_name(body),
                                                  kProblem.epoch_mjd2000 + t * kProblem.time_unit_days);
  const double to_position = kProblem.time_unit_days / kProblem.length_unit_km;
  const double to_velocity = kProblem.time_unit_days / kProblem.speed_unit_km_s;
  return {d[0] * to_position, d[1] * to_position, d[2] * to_position,
          d[3] * to_velocity, d[4] * to_velocity, d[5] * to_velocity};
}

// A coasting target's state at t1 from its state y0 at t0, integrated to 1e-14.
std::array<double, 6> coast_state(const std::array<double, 6>& y0, double t0, double t1) {
  Dop853 stepper(6);
  std::array<double, 6> y = y0, f0{}, ynew{}, fnew{};
  if (!kModules.coast_dynamics)
    throw std::runtime_error(
        "the program has a coasting target but its module table (kModules) names no coast_dynamics");
  auto rhs = [](double, const double* yy, double* dy) { kModules.coast_dynamics(yy, dy); };
  double t = t0, h = 1e-3 * (1 + std::fabs(t1 - t0));
  const double direction = t1 >= t0 ? 1.0 : -1.0;
  for (int steps = 0; direction * (t1 - t) > 0; ++steps) {
    if (steps > 1000000) throw numerical_error("coasting target: integrator exceeded its step budget");
    const bool last = h >= direction * (t1 - t);
    const double step = last ? t1 - t : direction * h;
    rhs(t, y.data(), f0.data());
    const double err = stepper.step(rhs, t, y.data(), f0.data(), step, ynew.data(), fnew.data(), 1e-14, 1e-14);
    if (!(err <= 1.0)) {
      h *= Dop853::step_factor(err);
      if (h < 1e-15 * (1 + std::fabs(t))) throw numerical_error("coasting target: step size underflow");
      continue;
    }
    t = last ? t1 : t + step;
    y = ynew;
    h *= Dop853::step_factor(err);
  }
  return y;
}

// On a Dual time: the value and its derivative through t (d state = rate dt, d rate = rate' dt).
namespace {
std::array<Dual, 6> through_time(const std::array<double, 6>& value, const std::array<double, 6>& rate, const Dual& t) {
  std::array<Dual, 6> r;
  for (int i = 0; i < 6; ++i) r[i] = ad::chain(t, value[i], rate[i]);
  return r;
}
}  // namespace

std::array<Dual, 6> ephemeris_state(const std::string& body, const Dual& t) {
  return through_time(ephemeris_state(body, t.v), ephemeris_rate(body, t.v), t);
}

// The rate's own rate: for an orbit body exactly, (a, da/dt) with a = -mu r/|r|^3 and
// da/dt = -mu (v/|r|^3 - 3 r (r.v)/|r|^5); for a JPL low-precision planet, the fourth-order
// central difference of its exact rate (h = 0.1 day: truncation near 1e-11 of the value, round-off
// near 1e-12).
std::array<Dual, 6> ephemeris_rate(const std::string& body, const Dual& t) {
  const auto rate = ephemeris_rate(body, t.v);
  std::array<double, 6> second{};
  if (orbit_body(body)) {
    const auto s = ephemeris_state(body, t.v);
    const double r2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2], r = std::sqrt(r2);
    const double k = -kProblem.mu / (r2 * r), rv = s[0] * s[3] + s[1] * s[4] + s[2] * s[5];
    for (int i = 0; i < 3; ++i) {
      second[i] = k * s[i];
      second[3 + i] = k * (s[3 + i] - 3 * s[i] * rv / r2);
    }
  } else {
    const double h = 0.1 / kProblem.time_unit_days;
    const auto p1 = ephemeris_rate(body, t.v + h), m1 = ephemeris_rate(body, t.v - h);
    const auto p2 = ephemeris_rate(body, t.v + 2 * h), m2 = ephemeris_rate(body, t.v - 2 * h);
    for (int i = 0; i < 6; ++i) second[i] = (8 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12 * h);
  }
  return through_time(rate, second, t);
}

// A coasting target's state moves with t1 at its own (autonomous) rate.
std::array<Dual, 6> coast_state(const std::array<double, 6>& y0, double t0, const Dual& t1) {
  const auto y1 = coast_state(y0, t0, t1.v);
  std::array<double, 6> rate{};
  kModules.coast_dynamics(y1.data(), rate.data());
  return through_time(y1, rate, t1);
}

}  // namespace helios_rt

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
    const helios::astro::Elements elements{b->a, b->e, b->i_rad, b->raan_rad, b->argp_rad, b->mean_anomaly_rad};
    return helios::astro::propagate(helios::astro::elements_to_state(elements, kProblem.mu), t - b->epoch, kProblem.mu);
  }
  const auto s = helios::astro::jpl_lp_state(helios::astro::planet_from_name(body),
                                             kProblem.epoch_mjd2000 + t * kProblem.time_unit_days);
  return {s[0] / kProblem.length_unit_km,  s[1] / kProblem.length_unit_km,  s[2] / kProblem.length_unit_km,
          s[3] / kProblem.speed_unit_km_s, s[4] / kProblem.speed_unit_km_s, s[5] / kProblem.speed_unit_km_s};
}

// Time derivative of the ephemeris model itself, as a free event time's transversality condition
// needs. A body of kProblem.orbit_bodies moves exactly on its Kepler orbit: (v, -mu r/|r|^3). A
// JPL low-precision planet's elements drift, so its rate is not the Kepler velocity the model
// reports: a fourth-order central difference.
std::array<double, 6> ephemeris_rate(const std::string& body, double t) {
  if (orbit_body(body)) {
    const auto s = ephemeris_state(body, t);
    const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), k = -kProblem.mu / (r * r * r);
    return {s[3], s[4], s[5], k * s[0], k * s[1], k * s[2]};
  }
  const double h = 1e-3 / kProblem.time_unit_days;  // 1e-3 day: truncation ~1e-13, round-off ~1e-12
  const auto p1 = ephemeris_state(body, t + h), m1 = ephemeris_state(body, t - h);
  const auto p2 = ephemeris_state(body, t + 2 * h), m2 = ephemeris_state(body, t - 2 * h);
  std::array<double, 6> d{};
  for (int i = 0; i < 6; ++i) d[i] = (8 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12 * h);
  return d;
}

// A coasting target's state at t1 from its state y0 at t0, integrated to 1e-14.
std::array<double, 6> coast_state(const std::array<double, 6>& y0, double t0, double t1) {
  Dop853 stepper(6);
  std::array<double, 6> y = y0, f0{}, ynew{}, fnew{};
  if (!coast_dynamics) throw std::runtime_error("the program has a coasting target but no coast_dynamics");
  auto rhs = [](double, const double* yy, double* dy) { coast_dynamics(yy, dy); };
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

}  // namespace helios_rt

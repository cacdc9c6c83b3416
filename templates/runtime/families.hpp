// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, families (templates/runtime/families.hpp): the transfer-angle
// continuation, by which the search looks for the neighbours of an extremal along its family.
//
// The extremals of a rendezvous with many revolutions form a family ordered by the revolutions
// they sweep (the objective often monotone along it), and random starts may never land in the
// basin of the best member. A member with one revolution fewer (or more) is reached from a known
// one by turning the target: the rows compare the end state, rotated by -theta about the
// departure's angular momentum (state and costates alike: Propagator::end_rotation), with the
// target, so they ask for the target turned by theta. theta goes from 0 to -2 pi (one revolution
// fewer) or 2 pi (one more) by continuation, each step predicted along the path's tangent and
// required to sweep its step in theta / 2 pi revolutions more than the last (within a quarter;
// with a free final time the target's own motion adds a little). At
// |theta| = 2 pi the turned target is the target itself: the rotation is switched off and the
// solution, solved once more, is an extremal of the problem as stated with one revolution fewer
// (more). Nothing of the intermediate problems reaches the answer: they are a path to a start.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The rotation by angle a about the unit vector k (row-major), by Rodrigues' formula.
inline std::array<double, 9> rotation_about(const std::array<double, 3>& k, double a) {
  const double c = std::cos(a), s = std::sin(a), v = 1 - c;
  return {c + v * k[0] * k[0],        v * k[0] * k[1] - s * k[2], v * k[0] * k[2] + s * k[1],
          v * k[1] * k[0] + s * k[2], c + v * k[1] * k[1],        v * k[1] * k[2] - s * k[0],
          v * k[2] * k[0] - s * k[1], v * k[2] * k[1] + s * k[0], c + v * k[2] * k[2]};
}

// The unit angular momentum of a trajectory's first sample (the axis of Shape::revolutions).
inline bool departure_axis(const RecordedPath& path, std::array<double, 3>& k) {
  if (path.samples.empty()) return false;
  const auto& y = path.samples.front().y;
  k = {y[1] * y[5] - y[2] * y[4], y[2] * y[3] - y[0] * y[5], y[0] * y[4] - y[1] * y[3]};
  const double n = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
  if (!(n > 0)) return false;
  for (double& c : k) c /= n;
  return true;
}

// The transfer-angle continuation (see the top of this file) of x, a solution of the shooting
// function at eps, to one sweeping `direction` (+1 or -1) revolutions more. True with x replaced by
// it, solved at eps to `accept` with the rotation off; every solve is appended to `steps` (stage
// "transfer angle", value theta in degrees) and counted in `evaluations`.
template <class Admissible>
bool turn_one_revolution(const Settings& s, std::vector<double>& x, double eps, int direction, double accept,
                         Admissible& admissible, std::vector<ContinuationStep>& steps, int& evaluations) {
  if (!end_rotation_possible()) return false;
  std::array<double, 3> axis{};
  try {
    if (!departure_axis(recorded_path(s, x, eps, INFINITY), axis)) return false;
  } catch (const numerical_error&) {
    return false;
  }
  double revolutions = shape_of(s, x, eps).revolutions;
  std::array<double, 9> R = rotation_about(axis, 0.0);
  bool rotated = true;
  const Function turned = [&](const double* z, double e, Propagator& prop, double* F, double* J) {
    prop.end_rotation = rotated ? &R : nullptr;
    try {
      shooting_function_and_jacobian(z, e, prop, F, J);
    } catch (...) {
      prop.end_rotation = nullptr;
      throw;
    }
    prop.end_rotation = nullptr;
  };
  Shooter shooter(s, turned, kContinuationStart);
  const auto at_angle = [&](double theta) { R = rotation_about(axis, -theta); };
  const auto solve_at = [&](std::vector<double>& z, double theta, double tolerance) {
    int info = 0;
    double res = 0;
    const bool ok = shooter.solve(z, eps, tolerance, info, res) && admissible(z.data());
    steps.push_back({"transfer angle", theta * 180 / M_PI, ok, res, shooter.last_step_evaluations});
    return ok;
  };
  const double target = direction * 2 * M_PI, smallest = 2 * M_PI / 256;
  double theta = 0, step = direction * 2 * M_PI / 8;
  std::vector<double> tangent;
  bool predicted = false;
  while (theta != target && wall_seconds() <= s.time_limit_s) {
    const double next = std::fabs(target - theta) <= std::fabs(step) ? target : theta + step;
    std::vector<double> trial = x;
    if (predicted)
      for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent[i] * (next - theta);
    at_angle(next);
    bool ok = solve_at(trial, next, s.accept_residual);
    const double now = ok ? shape_of(s, trial, eps).revolutions : 0;
    if (ok && std::fabs(now - revolutions - (next - theta) / (2 * M_PI)) > 0.25)
      ok = steps.back().converged = false;  // another branch

    if (!ok) {
      step *= 0.5;
      if (std::fabs(step) < smallest) break;
      continue;
    }
    x = trial;
    theta = next;
    revolutions = now;
    step = std::clamp(step * 1.5, -2 * M_PI / 4, 2 * M_PI / 4);
    // The tangent: dF/dtheta by a difference over 1e-6 rad.
    std::vector<double> F0(x.size()), F1(x.size());
    const double d = 1e-6 * direction;
    predicted = shooter.evaluate_at(x.data(), eps, F0.data());
    at_angle(theta + d);
    predicted = predicted && shooter.evaluate_at(x.data(), eps, F1.data());
    at_angle(theta);
    if (predicted) {
      for (std::size_t i = 0; i < x.size(); ++i) F1[i] = (F1[i] - F0[i]) / d;
      predicted = path_tangent(shooter, x, eps, F1, tangent);
    }
  }
  bool arrived = false;
  if (theta == target) {
    rotated = false;  // the turned target is the target: the problem as stated
    arrived = solve_at(x, theta, accept);
  }
  evaluations += shooter.evaluations;
  return arrived;
}

}  // namespace

}  // namespace helios_rt

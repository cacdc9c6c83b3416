// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, homotopy (templates/runtime/homotopy.hpp): continuation in eps (and in
// any homotopy parameter) down to 0, and the objective of a solution.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

// Any step of a continuation stays on its branch (see homotopy_to_zero's on_branch).
struct AnyBranch {
  bool operator()(const std::vector<double>&, const std::vector<double>&, double) const { return true; }
};

// Solves at settings.eps_start from the guess x, then continues in eps down to 0 with an adaptive
// step in log(eps) and retreat on failure. A step whose solution `on_branch(from, to, eps)` rejects
// (hybrd jumped to another extremal's branch) counts as failed. True when eps = 0 is reached (x
// and res are then its solution; r.x_start the first N variables of the solution at eps_start).
template <class Admissible, class OnBranch = AnyBranch>
bool homotopy_to_zero(const Settings& s, Shooter& shooter, std::vector<double>& x, Result& r, Admissible&& admissible,
                      double& res, OnBranch&& on_branch = OnBranch{}) {
  int info = 0;
  double eps = s.eps_start;
  if (!homotopy_step(shooter, x, eps, s.accept_residual, r, admissible, info, res)) return false;
  r.x_start.assign(x.begin(), x.begin() + problem::kNumVars);
  double log_step = std::log(1.0 / s.eps_first_ratio);
  double zero_below = s.eps_min;  // eps at or below which the next step goes to eps = 0
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = eps <= zero_below;
    const double next = to_zero ? 0.0 : std::max(eps * std::exp(-log_step), 0.5 * zero_below);
    std::vector<double> trial = x;
    const double accept = to_zero ? s.final_residual : s.accept_residual;
    bool ok = homotopy_step(shooter, trial, next, accept, r, admissible, info, res);
    if (ok && !on_branch(x, trial, next)) ok = r.homotopy.back().converged = false;
    if (ok) {
      x = trial;
      eps = next;
      r.info = info;
      if (to_zero) return true;
      log_step = std::min(log_step * 1.5, std::log(20.0));
    } else if (to_zero) {
      zero_below = 0.01 * eps;  // the bang-bang problem is still too far: smooth less first
      if (zero_below < 1e-12) return false;
    } else {
      log_step *= 0.5;
      if (log_step < std::log(1.02)) return false;
    }
  }
  return false;
}

// A solution re-propagated with every step recorded (steps of at most max_step) and every switch;
// throws numerical_error where the integration fails.
struct RecordedPath {
  std::vector<Sample> samples;
  std::vector<Switch> switches;
};
inline RecordedPath recorded_path(const Settings& s, const std::vector<double>& x, double eps, double max_step) {
  RecordedPath path;
  Propagator prop(s);
  prop.samples = &path.samples;
  prop.switches = &path.switches;
  prop.max_step = max_step;
  std::vector<double> F(problem::kNumVars);
  shooting_function(x.data(), eps, prop, F.data());
  return path;
}

// The objective of a converged x (smaller is better): the propellant of a minimum-fuel or
// minimum-initial-mass problem (summed over the arcs: a dropped lander is not propellant), the
// flight time tf - t0 of a minimum-time one.
inline double objective_of(const Settings& s, const std::vector<double>& x) {
  std::vector<Sample> samples;
  try {
    samples = recorded_path(s, x, 0.0, INFINITY).samples;
  } catch (const numerical_error&) {
    return INFINITY;
  }
  if (samples.empty()) return INFINITY;
  if (problem::kMinimumFuel && problem::kMassIndex >= 0) {
    double propellant = 0;
    for (std::size_t i = 1; i < samples.size(); ++i)
      if (samples[i].arc == samples[i - 1].arc)
        propellant += samples[i - 1].y[problem::kMassIndex] - samples[i].y[problem::kMassIndex];
    return propellant;
  }
  return samples.back().t - samples.front().t;
}

// Continuation in a homotopy parameter from `start` down to 0 (as homotopy_to_zero does in eps):
// steps in log(value) that grow after a success and halve after a failure, the last step to 0
// from below start * 1e-10. `step(value)` solves there from the last solution and keeps it on
// success.
template <class Step>
bool continue_to_zero(const Settings& s, double start, Step&& step) {
  if (!step(start)) return false;
  double value = start, log_step = std::log(1.0 / s.eps_first_ratio), zero_below = start * 1e-10;
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = value <= zero_below;
    const double next = to_zero ? 0.0 : std::max(value * std::exp(-log_step), 0.5 * zero_below);
    if (step(next)) {
      if (to_zero) return true;
      value = next;
      log_step = std::min(log_step * 1.5, std::log(20.0));
    } else if (to_zero) {
      zero_below *= 0.01;
      if (zero_below < start * 1e-16) return false;
    } else {
      log_step *= 0.5;
      if (log_step < std::log(1.02)) return false;
    }
  }
  return false;
}

}  // namespace helios_rt

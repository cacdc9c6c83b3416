// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, homotopy (templates/runtime/homotopy.hpp): continuation in eps (and in
// any homotopy parameter) down to 0, and the shape and objective of a solution.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// Any step of a continuation stays on its branch (see homotopy_to_zero's on_branch).
struct AnyBranch {
  bool operator()(const std::vector<double>&, double) const { return true; }
};

// The tangent dx/deps of the eps path at its solution x: -J^-1 dF/deps, with the exact Jacobian
// J and dF/deps a difference over 1e-4 eps toward 0. False (no predictor) without an exact
// Jacobian, at eps = 0, or where either fails.
inline bool eps_tangent(Shooter& shooter, const std::vector<double>& x, double eps, std::vector<double>& dx) {
  if (!(eps > 0)) return false;
  std::vector<double> F(x.size()), dF(x.size());
  const double d = 1e-4 * eps;
  if (!shooter.evaluate_at(x.data(), eps, F.data()) || !shooter.evaluate_at(x.data(), eps - d, dF.data())) return false;
  for (std::size_t i = 0; i < x.size(); ++i) dF[i] = (F[i] - dF[i]) / d;
  return path_tangent(shooter, x, eps, dF, dx);
}

// Solves at settings.eps_start from the guess x, then continues in eps down to 0 with an adaptive
// step in log(eps) and retreat on failure. A step whose solution `on_branch(to, eps)` rejects
// (hybrd jumped to another extremal's branch) counts as failed. True when eps = 0 is reached (x
// and res are then its solution; r.x_start the first N variables of the solution at eps_start).
template <class Admissible, class OnBranch = AnyBranch>
bool homotopy_to_zero(const Settings& s, Shooter& shooter, std::vector<double>& x, Result& r, Admissible&& admissible,
                      double& res, OnBranch&& on_branch = OnBranch{}) {
  int info = 0;
  double eps = s.eps_start;
  if (!homotopy_step(shooter, x, eps, s.accept_residual, r, admissible, info, res)) return false;
  r.x_start.assign(x.begin(), x.begin() + kProblem.num_vars);
  double log_step = std::log(1.0 / s.eps_first_ratio);
  double zero_below = s.eps_min;  // eps at or below which the next step goes to eps = 0
  std::vector<double> tangent;
  bool predicted = eps_tangent(shooter, x, eps, tangent);
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = eps <= zero_below;
    const double next = to_zero ? 0.0 : std::max(eps * std::exp(-log_step), 0.5 * zero_below);
    std::vector<double> trial = x;
    if (predicted)
      for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent[i] * (next - eps);
    const double accept = to_zero ? s.final_residual : s.accept_residual;
    bool ok = homotopy_step(shooter, trial, next, accept, r, admissible, info, res);
    if (ok && !on_branch(trial, next)) ok = r.homotopy.back().converged = false;
    if (ok) {
      x = trial;
      eps = next;
      r.info = info;
      if (to_zero) return true;
      predicted = eps_tangent(shooter, x, eps, tangent);
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

// A solution re-propagated with every step recorded (steps of at most max_step) and every switch,
// continued from `nodes` where given (multiple shooting, each arc in `segments` parts: nodes.hpp),
// of the companion problem where fuel_weight > 0; throws numerical_error where the integration
// fails.
struct RecordedPath {
  std::vector<Sample> samples;
  std::vector<Switch> switches;
  std::vector<Propagator::SideValue> side_values;  // the side conditions g > 0 at x
};
inline RecordedPath recorded_path(const Settings& s, const std::vector<double>& x, double eps, double max_step,
                                  const std::vector<double>& nodes = {}, int segments = 1, double fuel_weight = 0) {
  RecordedPath path;
  Propagator prop(s);
  prop.fuel_weight = fuel_weight;
  prop.samples = &path.samples;
  prop.switches = &path.switches;
  prop.max_step = max_step;
  std::vector<double> z = x, F(x.size() + nodes.size());
  z.insert(z.end(), nodes.begin(), nodes.end());
  solution_function(z.data(), nodes.size(), eps, segments, prop, F.data());
  path.side_values = prop.side_values;
  return path;
}

// The objective is the propellant (minimum fuel, minimum initial mass), or for an engine of
// constant mass its L1 cost: the propellant it would burn, or the delta-v (cost_is_delta_v).
inline bool objective_is_propellant() {
  return kProblem.objective == Objective::propellant && (kProblem.mass_index >= 0 || constant_mass());
}

// The objective is a Mayer term on the final state (the final radius or energy, maximized).
inline bool objective_is_final_state() {
  return kProblem.objective == Objective::final_radius || kProblem.objective == Objective::final_energy;
}

// The Mayer term phi(y) of a final-state objective at the state y (normalized).
inline double final_state_cost(const double* y) {
  const double r = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  if (kProblem.objective == Objective::final_radius) return -r;
  return -((y[3] * y[3] + y[4] * y[4] + y[5] * y[5]) / 2 - kProblem.mu / r);
}

// The named unit of a fuel cost (kg of propellant, or m/s of delta-v for an engine of constant mass
// without an exhaust velocity) where `fuel`, else of a time (days), per normalized unit.
inline double fuel_cost_unit(bool fuel) {
  if (!fuel) return kProblem.time_unit_days;
  return cost_is_delta_v() ? kProblem.speed_unit_km_s * 1e3 : kProblem.mass_unit_kg;
}

// The key of the objective in named units in solution.json.
inline const char* objective_key() {
  switch (kProblem.objective) {
    case Objective::final_radius:
      return "final_radius_km";
    case Objective::final_energy:
      return "final_energy_km2_s2";
    default:
      return !objective_is_propellant() ? "tof_days" : cost_is_delta_v() ? "delta_v_m_s" : "propellant_kg";
  }
}

// A normalized objective in its named unit: kg of propellant, days, or the final radius [km] or
// orbital energy [km^2/s^2] (the objective is their negative).
inline double objective_in_named_unit(double objective) {
  switch (kProblem.objective) {
    case Objective::final_radius:
      return -objective * kProblem.length_unit_km;
    case Objective::final_energy:
      return -objective * kProblem.speed_unit_km_s * kProblem.speed_unit_km_s;
    default:
      return objective * fuel_cost_unit(objective_is_propellant());
  }
}

// The Shape of a converged x at eps (the first three states are the position). At eps = 0 its
// cost is the objective: the propellant summed over the arcs (a dropped lander is not
// propellant), the flight time, or the final state's Mayer term. The companion problem of a minimum-time one
// (fuel_weight > 0) costs its propellant.
inline Shape shape_of(const Settings& s, const std::vector<double>& x, double eps, double fuel_weight = 0) {
  Shape out;
  RecordedPath path;
  try {
    path = recorded_path(s, x, eps, (kProblem.tf - kProblem.t0) / 1000, {}, 1, fuel_weight);
  } catch (const numerical_error&) {
    return out;
  }
  const std::vector<Sample>& samples = path.samples;
  if (samples.size() < 2) return out;
  out.switches = static_cast<int>(path.switches.size());
  for (const auto& side : path.side_values)
    if (!(side.g > 0) && out.off_side.empty()) out.off_side = side.meaning;
  const auto& y0 = samples.front().y;
  std::array<double, 3> h{y0[1] * y0[5] - y0[2] * y0[4], y0[2] * y0[3] - y0[0] * y0[5], y0[0] * y0[4] - y0[1] * y0[3]};
  double hn = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  if (!(hn > 0)) h = {0, 0, 1}, hn = 1;
  double swept = 0, smoothed = 0, burned = 0, propellant = 0;
  const bool propellant_objective = objective_is_propellant() || fuel_weight > 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const auto &a = samples[i - 1].y, &b = samples[i].y;
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    swept += std::atan2((cx * h[0] + cy * h[1] + cz * h[2]) / hn, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    if (propellant_objective) {
      if (samples[i].arc != samples[i - 1].arc) continue;
      if (kProblem.mass_index >= 0) propellant += a[kProblem.mass_index] - b[kProblem.mass_index];
      if (kProblem.throttle_index >= 0) {
        const double dt = samples[i].t - samples[i - 1].t;
        const double ua = samples[i - 1].control[kProblem.throttle_index],
                     ub = samples[i].control[kProblem.throttle_index];
        smoothed += 0.5 * dt * (ua - eps * ua * (1 - ua) + ub - eps * ub * (1 - ub));
        burned += 0.5 * dt * (ua + ub);
        // No mass state (a constant mass): the L1 cost, the throttle's integral at its rate. A sample
        // holds the mode of the step that follows it (a switch's sample the new one), so at eps = 0
        // the left sums are exact; with eps > 0 the throttle is continuous and the trapezoid is.
        if (kProblem.mass_index < 0)
          propellant += full_throttle_cost_rate() * (eps == 0 ? dt * ua : 0.5 * dt * (ua + ub));
      }
    }
  }
  out.revolutions = swept / (2 * M_PI);
  if (objective_is_final_state() && fuel_weight == 0)
    out.cost = final_state_cost(samples.back().y.data());
  else if (!propellant_objective)
    out.cost = samples.back().t - samples.front().t;
  else if (eps == 0)
    out.cost = propellant;
  else
    out.cost = burned > 0 ? propellant * smoothed / burned : 0.0;  // the mass flow is proportional to u
  return out;
}

// The objective of a converged x (smaller is better).
inline double objective_of(const Settings& s, const std::vector<double>& x) {
  return shape_of(s, x, 0.0).cost;
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

}  // namespace

}  // namespace helios_rt

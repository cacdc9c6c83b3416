// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, minimum time (templates/runtime/minimum_time.hpp): a minimum-time
// problem with a throttle, solved from its minimum-fuel companion.
//
// Random costates land in a minimum-time problem's basin rarely (a fraction of a percent of the
// starts for an Earth-Mars transfer at some dates, none of 200 at others). Physics offers a better
// start. Price the throttle as fuel: H_c = H + w lambda0 (Tmax/c)(u - eps u (1 - u)), w = 1 (the
// companion; Multipliers::fuel_weight), and hold the final time at tf_h instead of asking
// H(tf) = 0. The added term depends on the throttle and lambda0 only, so the state and costate
// equations, the thrust direction and every other row stay the problem's own; only the throttle
// law changes, to the minimum-fuel one (its slopes shifted by w lambda0 (Tmax/c)(1 -+ eps)). With
// tf held the constant running cost of minimum time is irrelevant: the companion IS the
// minimum-fuel problem at a fixed time of flight tf_h, smoothed by eps (at eps = 1 an energy-like
// problem whose random starts converge easily). As tf_h decreases, its throttle saturates; at the
// shortest tf_h at which the rendezvous is still possible the only admissible control is full
// thrust, the trajectory is the minimum-time one, and the costates differ from the minimum-time
// problem's only in lambda0 (which the released H(tf) row then fixes). So:
//   1. the companion is searched at eps = 1 with tf held at the window's end or earlier
//      (companion_hold; draws until saturated, as the search's own starts);
//   2. each distinct companion solution is continued down in tf_h (at eps = 1, steps predicted
//      along the path's tangent, growing after a success and halving after a failure) until no
//      shorter tf_h converges;
//   3. from there the minimum-time problem itself is solved (w = 0, tf free). Each arrival is an
//      extremal of the problem as stated; the search compares them with those of its own starts.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// A free final time's shooting variable (tf_frac: tf = tf_min + (tf_max - tf_min) tf_frac) and
// row (transversality_tf: H(tf) + dPhi/dtf = 0), by the derivation's names; -1 where there are none.
struct FreeFinalTime {
  int variable = -1, row = -1;
};
inline FreeFinalTime free_final_time() {
  FreeFinalTime f;
  for (int i = 0; i < kProblem.num_vars; ++i) {
    if (std::string(kProblem.variable_names[i]) == "tf_frac") f.variable = i;
    if (std::string(kProblem.equation_names[i]) == "transversality_tf") f.row = i;
  }
  return f;
}

// Whether the problem has a minimum-fuel companion: the objective is the time, the final time is
// free, and the throttle burns mass at a rate of its own (full_mass_flow).
inline bool has_fuel_companion() {
  const FreeFinalTime f = free_final_time();
  return kProblem.objective == Objective::time && f.variable >= 0 && f.row >= 0 && full_mass_flow() > 0;
}

// The final time the companion is held at first, as a fraction of its window: the window's end,
// but no later than 95 % of the time full thrust takes to burn the whole initial mass (a
// minimum-time flight thrusts throughout, so it is shorter than that; random costates that thrust
// throughout a longer flight would run out of mass).
inline double companion_hold() {
  const double burnout = 1 / full_mass_flow();  // the initial mass is the mass unit
  const double window = kProblem.tf - kProblem.tf_min;
  if (!(window > 0)) return 1;
  return std::clamp((std::min(kProblem.tf, 0.95 * burnout) - kProblem.tf_min) / window, 0.0, 1.0);
}

// x with the held final time inserted at `at` (z: the other variables), and z from x.
inline std::vector<double> with_held(const std::vector<double>& z, int at, double value) {
  std::vector<double> x = z;
  x.insert(x.begin() + at, value);
  return x;
}
inline std::vector<double> without_held(const std::vector<double>& x, int at) {
  std::vector<double> z = x;
  z.erase(z.begin() + at);
  return z;
}

// The companion's shooting function on the N - 1 variables other than the final time, which is
// held at `hold` (a window fraction): the problem's rows but the final time's, with the throttle
// priced as fuel. (Holding it by a row x[tf_frac] - hold of the full system would let hybrid
// steps move it; without it the companion is exactly the minimum-fuel shooting system.)
inline Function companion_function(const FreeFinalTime& f, const double& hold) {
  return [f, &hold](const double* z, double eps, Propagator& prop, double* F, double* J) {
    const int N = kProblem.num_vars;
    std::vector<double> x = with_held(std::vector<double>(z, z + N - 1), f.variable, hold);
    std::vector<double> full(static_cast<std::size_t>(N)), full_J(J ? static_cast<std::size_t>(N * N) : 0);
    prop.fuel_weight = 1;
    try {
      shooting_function_and_jacobian(x.data(), eps, prop, full.data(), J ? full_J.data() : nullptr);
    } catch (...) {
      prop.fuel_weight = 0;
      throw;
    }
    prop.fuel_weight = 0;
    for (int i = 0, r = 0; i < N; ++i) {
      if (i == f.row) continue;
      F[r] = full[i];
      if (J)
        for (int j = 0, c = 0; j < N; ++j)
          if (j != f.variable) J[r + (c++) * (N - 1)] = full_J[i + j * N];
      ++r;
    }
  };
}

// What the companion's path reached: the shortest held final time (a window fraction) and the
// minimum-time extremal solved from there.
struct CompanionArrival : PathArrival {
  double held = 1;
};

// Steps 2 and 3 above from a companion solution x (all N variables, tf_frac = hold) at
// eps_companion.
template <class Admissible>
CompanionArrival companion_to_minimum_time(const Settings& s, const std::vector<double>& x, double hold,
                                           double eps_companion, Admissible& admissible, int& evaluations) {
  const FreeFinalTime f = free_final_time();
  CompanionArrival out;
  double held = hold;
  Shooter companion(s, companion_function(f, held), kContinuationStart);
  const auto admissible_z = [&](const std::vector<double>& z) {
    return admissible(with_held(z, f.variable, held).data());
  };
  std::vector<double> z = without_held(x, f.variable);
  const double scale = std::max(hold, 1e-3);
  held = follow_parameter(
      s, companion, z, eps_companion, [&](double v) { held = v; }, hold, 0.0, -1e-7,
      {0.05 * scale, 1e-4 * scale, 0.2}, "minimum fuel, tf held (window fraction)", out.steps, admissible_z,
      [](const std::vector<double>&) { return false; });
  out.held = held;
  evaluations += companion.evaluations;
  // Step 3: the problem itself, tf free, from the companion's last solution.
  Shooter itself(s, kContinuationStart);
  int info = 0;
  double res = 0;
  std::vector<double> full = with_held(z, f.variable, held);
  out.arrived = itself.solve(full, 0.0, s.final_residual, info, res) && admissible(full.data());
  out.steps.push_back({"minimum time, tf free", full[f.variable], out.arrived, res, itself.last_step_evaluations});
  evaluations += itself.evaluations;
  if (out.arrived) {
    out.x = full;
    out.F = itself.last_F;
    out.max_residual = res;
    out.info = info;
  }
  return out;
}

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the companion route (templates/runtime/search/companion.hpp): a
// minimum-time problem with a throttle, solved from its minimum-fuel companion.
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

// Whether the problem has a minimum-fuel companion: the objective is the time, the final time is
// free, and the throttle has a fuel cost at a rate of its own (full_throttle_cost_rate: the mass it
// burns, or the L1 cost of an engine of constant mass).
inline bool has_fuel_companion() {
  const TimeWindow f = free_final_time();
  return kProblem.objective == Objective::time && f.variable >= 0 && f.row >= 0 && full_throttle_cost_rate() > 0;
}

// The final time the companion is held at first, as a fraction of its window: the window's end,
// but no later than 95 % of the time full thrust takes to burn the whole initial mass (a
// minimum-time flight thrusts throughout, so it is shorter than that; random costates that thrust
// throughout a longer flight would run out of mass), and no later than 1.5 times the minimum time
// the time scale estimates (`estimate`, normalized; NaN: none), where a flight comfortably longer
// than the minimum converges easily.
inline double companion_hold(double estimate) {
  const double burnout = burnout_time();  // infinite for an engine of constant mass
  const double window = kProblem.tf - kProblem.tf_min;
  if (!(window > 0)) return 1;
  double end = std::min(kProblem.tf, kProblem.t0 + 0.95 * burnout);
  if (estimate > 0) end = std::min(end, kProblem.t0 + 1.5 * estimate);
  return std::clamp((end - kProblem.tf_min) / window, 0.0, 1.0);
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
inline Function companion_function(const TimeWindow& f, const double& hold) {
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
  const TimeWindow f = free_final_time();
  CompanionArrival out;
  double held = hold;
  Shooter companion(s, companion_function(f, held), kContinuationStart);
  const auto admissible_z = [&](const std::vector<double>& z) {
    return admissible(with_held(z, f.variable, held).data());
  };
  std::vector<double> z = without_held(x, f.variable);
  const double scale = std::max(hold, 1e-3);
  held = follow_parameter(
      s, companion, z, eps_companion, [&](double v) { held = v; }, hold, 0.0, -1e-7, {0.05 * scale, 1e-4 * scale, 0.2},
      "minimum fuel, tf held (window fraction)", out.steps, admissible_z,
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

// The route: the companion's starts at eps = 1 with tf held (companion_hold), drawn until
// saturated or their cap; each distinct solution, cheapest first, continued down in tf and released
// into the problem itself.
class CompanionRoute : public Route {
 public:
  const char* name() const override { return "minimum-fuel companion"; }
  std::string skip(const SearchContext& c) const override {
    if (!c.coarse.search_fuel_companion) return "search_fuel_companion is off";
    if (!has_fuel_companion() && kProblem.objective == Objective::time && *varying_flow_reason())
      return varying_flow_reason();
    if (!has_fuel_companion())
      return kProblem.objective == Objective::time && kProblem.throttle_index >= 0 && full_throttle_cost_rate() <= 0
                 ? "the throttle has no fuel cost at a rate of its own (its mass flow depends on the state)"
                 : "not a minimum-time problem with a throttle that burns mass at a free final time";
    if (c.many_revolutions_expected())
      return "the time scale expects " + number_text(c.rec().time_scale.revolutions, 3) +
             " revolutions: the thrust route reaches them";
    return "";
  }

  std::string run(SearchContext& c) override {
    SearchRecord& rec = c.rec();
    const TimeWindow f = free_final_time();
    const double hold = companion_hold(c.estimated_time()), eps = 1;
    std::vector<StartExtremal>& list = rec.companion_solutions;
    bool cut = false;
    draw_until_saturated(
        c.coarse, c.threads, kCompanionStream, list, rec.companion_draws, rec.companion_converged, cut,
        start_cap(c.coarse), c.started,
        [&](int, std::mt19937_64& rng) {
          StartRun run;
          run.x.assign(kProblem.num_vars, 0.0);
          c.guess(rng, run.x.data());
          std::vector<double> z = without_held(run.x, f.variable);
          Shooter shooter(c.coarse, companion_function(f, hold));
          int info = 0;
          run.ok = shooter.solve(z, eps, c.coarse.accept_residual, info, run.res);
          run.x = with_held(z, f.variable, hold);
          run.ok = run.ok && c.admissible(run.x.data());
          if (run.ok) run.shape = shape_of(c.coarse, run.x, eps, 1.0);
          c.count(shooter.evaluations);
          return run;
        },
        [&](const StartRun& run, int k) { c.pool.enter_start(list, run, k); },
        [&](int k) { c.progress.tick(std::to_string(k) + " starts of the minimum-fuel companion"); });
    rec.cut_by_time = rec.cut_by_time || cut;
    rec.companion_tf_days =
        (kProblem.tf_min + (kProblem.tf - kProblem.tf_min) * hold - kProblem.t0) * kProblem.time_unit_days;
    c.progress.stage(std::to_string(rec.companion_draws) +
                     " starts of the minimum-fuel companion (the final time held at " +
                     days_text(rec.companion_tf_days, 6) + "): " + std::to_string(rec.companion_converged) +
                     " converged, " + std::to_string(list.size()) + " distinct");
    const std::vector<int> order = lowest_cost(list, list.size());
    std::vector<CompanionArrival> arrivals(order.size());
    parallel_for(static_cast<int>(order.size()), c.threads, [&](int i) {
      if (c.out_of_time()) return;
      int evaluations = 0;
      arrivals[i] = companion_to_minimum_time(c.coarse, list[order[i]].x, hold, eps, c.admissible, evaluations);
      c.count(evaluations);
    });
    int arrived = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
      StartExtremal& from = list[order[i]];
      from.continued = true;
      CompanionArrival& a = arrivals[i];
      if (!a.arrived) continue;
      ++arrived;
      from.arrived = c.pool.enter(
          name(), arrival_extremal(c.coarse, a,
                                   "minimum time released from the minimum-fuel companion's solution " +
                                       std::to_string(order[i]) + ", continued down to tf held at window fraction " +
                                       number_text(a.held, 5)));
    }
    const double best = best_objective(rec);
    c.progress.stage("minimum time from the companion: " + std::to_string(rec.extremals.size()) +
                     " distinct extremals" + (std::isfinite(best) ? ", best " + objective_text(best) : ""));
    return std::to_string(rec.companion_draws) + " companion starts (tf held at " +
           days_text(rec.companion_tf_days, 6) + "), " + std::to_string(list.size()) + " distinct, " +
           std::to_string(arrived) + " released to minimum time";
  }
};

}  // namespace

}  // namespace helios_rt

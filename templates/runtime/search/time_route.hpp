// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the time route (templates/runtime/search/time_route.hpp): a
// minimum-fuel problem at a fixed final time solved from its minimum-time extremal.
// ---------------------------------------------------------------------------------------------
// Below the shortest final time t_min at which the transfer is possible there is none; at t_min
// the only admissible control is full thrust, and the minimum-fuel extremal there is abnormal
// (lambda0 = 0): its costates are those of the minimum-time extremal (whose own cost multiplier
// enters only its H(tf) row, not the control). As the final time grows from t_min, coasting arcs
// open and lambda0 grows. So the minimum-fuel extremals at a fixed time form families that start at
// the minimum-time extremals; the one continued from the minimum-time optimum is the natural
// candidate (Caillau, Gergaud and Noailles on the GTO to GEO transfer), and it does not depend on a
// random start landing in a small basin.
//
// The shooting function of the fuel problem serves both ends. With lambda0 held at a and the final
// time free in lambda0's slot (tf = s tf_unit: the held-multiplier system), its solutions at a = 0
// are the minimum-time extremals and at a > 0 minimum-fuel extremals at the final time they reach.
// The route, for a fuel problem whose targets do not move on the calendar:
//   1. from a minimum-fuel solution at eps_start, the final time is continued down (lambda0 free)
//      while its steps converge, then a is brought down to 0 (the final time free): the
//      minimum-time extremal;
//   2. from it, a is continued up from 0 at eps_start while coasting arcs open, then the final time
//      itself (lambda0 free) up to the problem's;
//   3. there eps is continued to 0: an extremal of the problem.
// The final time is the program's parameter (knobs.hpp): one path at a time (the route runs alone).
#pragma once

namespace helios_rt {

namespace {

// The stages of the route's steps (solution.json's continuation; schemas/solution.schema.json).
constexpr const char* kFinalTimeDown = "minimum fuel, the final time down [days]";
constexpr const char* kMinimumTime = "minimum time (lambda0 = 0), the final time free [days]";
constexpr const char* kLambda0Held = "lambda0 held, the final time free (lambda0)";
constexpr const char* kFinalTimeUp = "minimum fuel, the final time up [days]";

// Whether the problem has the route: minimum propellant at a fixed final time (a parameter), with
// a throttle that has a fuel cost (its flow at a constant rate or not) and lambda0 a variable, and
// targets that do not move on the calendar (no epoch, no body on an orbit, no coasting target: a
// final time moved elsewhere would meet them elsewhere).
inline bool has_time_route() {
  return kProblem.objective == Objective::propellant && free_final_time().variable < 0 && throttle_has_fuel_cost() &&
         lambda0_variable() >= 0 && scalar_parameter("kTf") != nullptr && targets_fixed_in_time();
}

// The held-multiplier system: the shooting function with lambda0 held at `held` and, in lambda0's
// slot, the final time as a fraction s of the problem's (tf = s tf.final_time_unit()); dF/ds by a difference.
inline Function held_multiplier_function(ProgramKnobs& tf, int l0, const double& held) {
  return [&tf, l0, &held](const double* z, double eps, Propagator& prop, double* F, double* J) {
    const int N = kProblem.num_vars;
    std::vector<double> x(z, z + N);
    const double s = x[l0];
    x[l0] = held;
    tf.set_final_time(s * tf.final_time_unit());
    shooting_function_and_jacobian(x.data(), eps, prop, F, J);
    if (J) {
      std::vector<double> shifted(static_cast<std::size_t>(N));
      const double h = 1e-7 * std::max(1.0, std::fabs(s));
      tf.set_final_time((s + h) * tf.final_time_unit());
      shooting_function_and_jacobian(x.data(), eps, prop, shifted.data(), nullptr);
      for (int i = 0; i < N; ++i) J[i + l0 * N] = (shifted[i] - F[i]) / h;
      tf.set_final_time(s * tf.final_time_unit());
    }
  };
}

// What the route reached from one fuel solution: the minimum-time extremal (its final time in the
// problem's normalized units, NaN where step 1 failed) and the extremal at eps = 0 of step 3.
struct TimeRouteArrival : PathArrival {
  double tf_min = NAN;
  std::vector<HomotopyStep> homotopy;  // eps from eps_start to 0 at the problem's final time
};

// Step 1 from the fuel solution x (at eps_start, the problem's final time): the minimum-time
// extremal as held-multiplier variables z (s in lambda0's slot); false where it was not reached.
// The final time comes down while its steps converge; near t_min it stops being a parameter
// (s(lambda0) is flat where the thrust stays full, a fold in the final time), so from where its
// steps first fail lambda0 itself is held and brought down to 0, the final time free: at 0 the
// path is at the minimum-time extremal. The continuations run at `along` (loose_settings where
// the path winds few times), the minimum-time extremal is solved at s.
inline bool minimum_time_from_fuel_solution(const Settings& s, const Settings& along, ProgramKnobs& tf,
                                            std::vector<double> x, double eps, std::vector<double>& z,
                                            TimeRouteArrival& out, int& evaluations) {
  const int l0 = lambda0_variable();
  Shooter fuel(along, kContinuationStart);
  const double day = 1 / kProblem.time_unit_days, own_days = tf.final_time_unit() / day;
  const double reached = day * follow_parameter(
                                   along, fuel, x, eps, [&](double days) { tf.set_final_time(days * day); }, own_days,
                                   0.0, -1e-7 * own_days, {0.05 * own_days, 0.01 * own_days, 0.2 * own_days},
                                   kFinalTimeDown, out.steps, [&](const std::vector<double>& y) { return y[l0] >= 0; },
                                   [](const std::vector<double>&) { return false; });
  evaluations += fuel.evaluations;
  double held = x[l0];
  Shooter time(along, held_multiplier_function(tf, l0, held), kContinuationStart);
  z = x;
  z[l0] = reached / tf.final_time_unit();
  const double from = held;
  held = follow_parameter(
      along, time, z, eps, [&](double v) { held = v; }, from, 0.0, -1e-7 * std::max(from, 1e-3),
      {0.25 * from, 1e-4 * from, from}, kLambda0Held, out.steps,
      [&](const std::vector<double>& y) { return y[l0] > 0; }, [](const std::vector<double>&) { return false; });
  int info = 0;
  double res = 0;
  Shooter minimum(s, held_multiplier_function(tf, l0, held), kContinuationStart);
  const bool ok = held == 0 && minimum.solve(z, 0.0, s.accept_residual, info, res) && z[l0] > 0;
  out.steps.push_back(
      {kMinimumTime, z[l0] * tf.final_time_unit() * kProblem.time_unit_days, ok, res, minimum.last_step_evaluations});
  evaluations += time.evaluations + minimum.evaluations;
  if (ok) out.tf_min = z[l0] * tf.final_time_unit();
  tf.set_final_time(tf.final_time_unit());
  return ok;
}

// The revolutions of the minimum-time extremal z (held-multiplier variables).
inline double minimum_time_revolutions(const Settings& s, ProgramKnobs& tf, const std::vector<double>& z) {
  const int l0 = lambda0_variable();
  std::vector<double> x = z;
  x[l0] = 0;
  tf.set_final_time(z[l0] * tf.final_time_unit());
  const double revolutions = shape_of(s, x, 0.0).revolutions;
  tf.set_final_time(tf.final_time_unit());
  return revolutions;
}

// Steps 2 and 3 from the minimum-time extremal z, at eps_start (the smooth problem every start is
// solved at: at eps = 0 the path stalls where a coasting arc is born): lambda0 held at a, continued
// up from 0 until coasting has lengthened the flight by kOpening of what separates it from the
// problem's final time (s(a) is flat while the thrust stays full, then rises, and may fold back: a
// is a parameter only near the start); then the final time itself, lambda0 free, up to the
// problem's; there eps is continued down to 0 (homotopy_to_zero). The continuations at eps_start
// run at `along`, eps's at s.
template <class Admissible>
void fuel_path_from_minimum_time(const Settings& s, const Settings& along, ProgramKnobs& tf, std::vector<double> z,
                                 Admissible& admissible, TimeRouteArrival& out, int& evaluations) {
  constexpr double kOpening = 0.02;
  const int l0 = lambda0_variable();
  const double eps = s.eps_start, opened = z[l0] + kOpening * (1 - z[l0]);
  double held = 0;
  Shooter opening(along, held_multiplier_function(tf, l0, held), kContinuationStart);
  const double a = follow_parameter(
      along, opening, z, eps, [&](double v) { held = v; }, 0.0, 0.999, 1e-7, {1e-3, 1e-7, 0.05}, kLambda0Held,
      out.steps, [&](const std::vector<double>& y) { return y[l0] > 0; },
      [&](const std::vector<double>& y) { return y[l0] >= opened; });
  evaluations += opening.evaluations;
  if (!(z[l0] >= opened) || z[l0] > 1) {
    tf.set_final_time(tf.final_time_unit());
    return;
  }
  Shooter up(along, kContinuationStart);
  std::vector<double> x = z;
  x[l0] = a;
  const double day = 1 / kProblem.time_unit_days, own_days = tf.final_time_unit() / day, from_days = z[l0] * own_days;
  tf.set_final_time(from_days * day);
  const double reached_days = follow_parameter(
      along, up, x, eps, [&](double days) { tf.set_final_time(days * day); }, from_days, own_days, 1e-7 * own_days,
      {0.02 * own_days, 1e-5 * own_days, 0.2 * own_days}, kFinalTimeUp, out.steps,
      [&](const std::vector<double>& y) { return y[l0] > 0; }, [](const std::vector<double>&) { return false; });
  tf.set_final_time(tf.final_time_unit());
  Shooter itself(s, kContinuationStart);
  if (reached_days == own_days) {
    Result path;
    double res = 0;
    out.arrived = homotopy_to_zero(
        s, itself, x, path, [&](const double* y) { return admissible(y); }, res);
    out.homotopy = path.homotopy;
    if (out.arrived) {
      out.x = x;
      out.F = itself.last_F;
      out.max_residual = res;
      out.info = path.info;
    }
  }
  evaluations += up.evaluations + itself.evaluations;
}

// The minimum-time problem itself, searched: starts on the held-multiplier system (lambda0 held at
// 0, the final time free in its slot, drawn log-uniformly between a tenth of the program's final
// time and the program's), drawn until saturated. Its extremals (cost: the final time as a fraction
// of the program's) are the minimum-time extremals of every family the starts reach, where
// continuing one fuel extremal down in its final time reaches its own family's only. The
// held-multiplier system writes the program's final time (one for the whole program) at every
// evaluation, so these starts run on one thread.
struct MinimumTimeSearch {
  std::vector<StartExtremal> found;
  bool saturated = false;
};

inline MinimumTimeSearch search_minimum_time(SearchContext& c) {
  const int l0 = lambda0_variable();
  const double held = 0;
  MinimumTimeSearch out;
  int drawn = 0, converged = 0;
  bool cut = false;
  const DrawStop stop = draw_until_saturated(
      c.coarse, 1, kMinimumTimeStream, out.found, drawn, converged, cut, start_cap(c.coarse), c.started,
      [&](int, std::mt19937_64& rng) {
        StartRun run;
        run.x.assign(kProblem.num_vars, 0.0);
        c.guess(rng, run.x.data());
        run.x[l0] = std::pow(10.0, std::uniform_real_distribution<double>(-1.0, 0.0)(rng));
        Shooter shooter(c.coarse, held_multiplier_function(c.knobs, l0, held));
        int info = 0;
        run.ok = shooter.solve(run.x, 0.0, c.coarse.accept_residual, info, run.res) && run.x[l0] > 0;
        c.knobs.reset_final_time();
        if (run.ok) {
          run.shape.revolutions = minimum_time_revolutions(c.coarse, c.knobs, run.x);
          run.shape.cost = run.x[l0];
        }
        c.count(shooter.evaluations);
        return run;
      },
      [&](const StartRun& run, int k) { c.pool.enter_start(out.found, run, k); },
      [&](int k) { c.progress.tick(std::to_string(k) + " starts of the minimum-time problem"); });
  out.saturated = stop == DrawStop::kSaturated;
  c.rec().cut_by_time = c.rec().cut_by_time || cut;
  c.progress.stage(std::to_string(drawn) + " starts of the minimum-time problem: " + std::to_string(converged) +
                   " converged, " + std::to_string(out.found.size()) + " distinct" +
                   (out.saturated ? ", saturated" : ", not saturated"));
  return out;
}

// The route (see the top of this file), at the integrator's own tolerance, one path at a time:
// from each of kTimeRouteSources lowest-cost extremals of the starts at eps_start down to a
// minimum-time extremal, and from each distinct one up to the problem's final time and on to
// eps = 0, the arrivals entered into the pool. Where every minimum-time extremal so reached winds
// more than kFewRevolutions times (or none was reached), the minimum time is also sought at a
// raised thrust and continued down to the problem's (by_raised_thrust).
class TimeRoute : public Route {
 public:
  const char* name() const override { return "minimum-time route"; }
  std::string skip(const SearchContext& c) const override {
    if (!has_time_route()) return "not a minimum-fuel problem at a fixed final time with targets fixed in time";
    if (c.nested) return "inside a search at a raised thrust";
    const std::string& when = c.coarse.search_fuel_from_time;
    if (when == "never") return "search_fuel_from_time is never";
    if (when == "auto" && settled(c.rec())) return "search_fuel_from_time is auto and the search settled the problem";
    return "";
  }

  std::string run(SearchContext& c) override {
    c.rec().method += "; minimum fuel also continued from the minimum-time extremals";
    double fewest = INFINITY;
    for (const int k : lowest_cost(c.rec().start_extremals, kTimeRouteSources)) {
      if (c.out_of_time()) break;
      TimeRouteArrival a;
      std::vector<double> z;
      int evaluations = 0;
      const bool reached =
          minimum_time_from_fuel_solution(c.coarse, loose_settings(c.coarse), c.knobs, c.rec().start_extremals[k].x,
                                          c.coarse.eps_start, z, a, evaluations);
      c.count(evaluations);
      if (reached) fewest = std::min(fewest, minimum_time_revolutions(c.coarse, c.knobs, z));
      path(c, "the extremal at eps_start " + std::to_string(k), reached ? &z : nullptr, a);
    }
    if (c.coarse.search_thrust_continuation && c.knobs.thrust_scalable() && !(fewest <= kFewRevolutions))
      by_raised_thrust(c);
    if (kProblem.final_coast_keeps_target) minimum_time_starts(c);
    int arrived = 0;
    double t_min = INFINITY;
    for (const auto& p : c.rec().time_route_paths) {
      arrived += p.extremal >= 0;
      if (std::isfinite(p.tf_min_days)) t_min = std::min(t_min, p.tf_min_days);
    }
    std::string line = std::to_string(c.rec().time_route_paths.size()) + " paths, " + std::to_string(arrived) +
                       " arrived at the problem's final time";
    if (kProblem.final_coast_keeps_target && std::isfinite(t_min) && full_throttle_cost_rate() > 0) {
      // The minimum-time transfer burns throughout; completed by a coast on the target it is a
      // feasible transfer at the problem's final time, which no returned extremal may cost more than
      // (its cost is the rate times t_min: none is known where the flow follows the distance).
      c.rec().coast_bound = full_throttle_cost_rate() * t_min / kProblem.time_unit_days;
      line += "; the minimum time " + days_text(t_min) + " and a coast cost " + objective_text(c.rec().coast_bound);
    }
    return line;
  }

 private:
  static constexpr std::size_t kTimeRouteSources = 3;

  // Where the minimum time bounds the answer (minimum time plus a coast), the problem's own starts
  // give the minimum-time extremals of their families only, and the one the final time comes down
  // to need not be the shortest (GTO to GEO at 60 N in 1.5 t_min: the starts reach only the family
  // of two revolutions, which comes down to 21.54 h; the shortest, 14.80 h, is one revolution).
  // So the minimum-time problem itself is searched (search_minimum_time), and each of its
  // lowest-cost extremals is taken up to the problem's final time.
  void minimum_time_starts(SearchContext& c) {
    MinimumTimeSearch search = search_minimum_time(c);
    for (const int k : lowest_cost(search.found, kTimeRouteSources)) {
      if (c.out_of_time()) break;
      TimeRouteArrival a;
      std::vector<double> z = search.found[k].x;
      path(c, "the minimum-time start " + std::to_string(search.found[k].first_start), &z, a);
    }
  }

  // The minimum time at a raised thrust: the fuel problem searched there (search_at_raised_thrust:
  // its final time scaled inversely, so it winds fewer times), its lowest-cost extremals at eps_start
  // taken down to minimum-time extremals there, and those continued down the thrust to the
  // problem's (continue_thrust_down along the minimum-time system), then up to its final time.
  void by_raised_thrust(SearchContext& c) {
    double factor = 1;
    std::vector<ContinuationStep> raising;
    const Result raised = search_at_raised_thrust(c, factor, raising);
    c.rec().time_route.insert(c.rec().time_route.end(), raising.begin(), raising.end());
    const double sigma = std::log(factor);
    const std::string where = " of the search at " + number_text(c.knobs.thrust_N(sigma)) + " N";
    const int l0 = lambda0_variable();
    const double held = 0;
    ThrustPath along{held_multiplier_function(c.knobs, l0, held), nullptr,
                     [&](const std::vector<double>& z) { return minimum_time_revolutions(c.coarse, c.knobs, z); },
                     [l0](const std::vector<double>& z, double) { return z[l0]; }};
    auto positive_time = [&](const double* z) { return z[l0] > 0; };
    const auto tick = [&](double thrust_N, double revolutions) {
      c.progress.tick("minimum time down the thrust: " + number_text(thrust_N) + " N of " +
                      number_text(c.knobs.own_thrust_N()) + " N, " + number_text(revolutions, 4) + " revolutions");
    };
    std::vector<double> seen;  // the minimum times reached at the raised thrust (fractions)
    for (const int k : lowest_cost(raised.search.start_extremals, kTimeRouteSources)) {
      if (c.out_of_time() || raised.status != Status::kConverged) break;
      c.knobs.scale_thrust(sigma);
      TimeRouteArrival a;
      std::vector<double> z;
      int evaluations = 0;
      bool reached = minimum_time_from_fuel_solution(c.fine, c.fine, c.knobs, raised.search.start_extremals[k].x,
                                                     c.coarse.eps_start, z, a, evaluations);
      const bool repeated =
          reached && std::any_of(seen.begin(), seen.end(), [&](double f) { return std::fabs(f - z[l0]) <= 1e-7 * f; });
      if (reached && !repeated) {
        seen.push_back(z[l0]);
        PathArrival down = continue_thrust_down(c.fine, c.knobs, z, sigma, positive_time, evaluations, tick, along);
        a.steps.insert(a.steps.end(), down.steps.begin(), down.steps.end());
        reached = down.arrived;
        if (reached) z = down.x;
      }
      c.knobs.restore();
      c.count(evaluations);
      if (!repeated) path(c, "the extremal at eps_start " + std::to_string(k) + where, reached ? &z : nullptr, a);
    }
    c.knobs.restore();
  }

  // One path of the route from its minimum-time extremal z at the problem's thrust (null: none was
  // reached; its steps in `a`): up to the problem's final time unless that minimum time was reached
  // before, recorded, and its arrival entered into the pool.
  void path(SearchContext& c, const std::string& from, const std::vector<double>* z, TimeRouteArrival& a) {
    SearchRecord& rec = c.rec();
    SearchRecord::TimeRoutePath path;
    path.from = from;
    if (z) {
      const int l0 = lambda0_variable();
      path.tf_min_days = (*z)[l0] * c.knobs.final_time_unit() * kProblem.time_unit_days;
      path.revolutions = minimum_time_revolutions(c.coarse, c.knobs, *z);
      for (const auto& p : rec.time_route_paths)
        if (std::fabs(p.tf_min_days - path.tf_min_days) <= 1e-7 * path.tf_min_days) path.reached_before = true;
      if (!path.reached_before) {
        int evaluations = 0;
        // Where the minimum-time extremal winds few times, its path to eps = 0 on the looser
        // integration and eps continued at the search's tolerance (its arrival is polished with the
        // others); over many revolutions only the integrator's own resolves the path.
        const bool few = path.revolutions <= kScaleRevolutions;
        fuel_path_from_minimum_time(few ? c.coarse : c.fine, few ? loose_settings(c.coarse) : c.fine, c.knobs, *z,
                                    c.admissible, a, evaluations);
        c.count(evaluations);
      }
    }
    rec.time_route.insert(rec.time_route.end(), a.steps.begin(), a.steps.end());
    const std::string t_min = std::isfinite(path.tf_min_days) ? "t_min " + days_text(path.tf_min_days)
                                                              : std::string("no minimum time reached");
    if (a.arrived) {
      Extremal entry = arrival_extremal(c.coarse, a,
                                        "single shooting, minimum fuel continued from the minimum-time extremal (" +
                                            t_min + ") reached from " + from);
      entry.homotopy = a.homotopy;
      const Shape shape = entry.shape;
      path.extremal = c.pool.enter(name(), std::move(entry));
      c.progress.stage("minimum fuel from the minimum-time extremal (" + t_min + ", from " + from +
                       "): " + objective_text(shape.cost) + ", " + number_text(shape.revolutions, 5) + " revolutions");
    } else {
      c.progress.stage("minimum time from " + from + ": " + t_min +
                       (path.reached_before ? ", reached before"
                        : z                 ? "; minimum fuel from it did not reach the problem's final time"
                                            : ""));
    }
    rec.time_route_paths.push_back(path);
  }
};

}  // namespace

}  // namespace helios_rt

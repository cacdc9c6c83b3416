// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the time-scale route (templates/runtime/search/scale.hpp): a
// minimum-time problem whose window allows many revolutions, measured first at a raised thrust.
//
// A user bounds a minimum-time flight loosely ("at most 100 days"), and where the window allows
// many revolutions nothing tells the search how long the transfer takes: random guesses of the
// final time spread over the window, the companion is held at its end, and both mostly try flights
// many times too long. Raise the thrust by the factor F at which the whole window (no later than
// the engine burns all the mass) winds at most kFewRevolutions times about the central body
// (the problem family of the thrust route, thrust.hpp: the window scaled by 1/F) and search there:
// every flight the search tries is short, so its starts are cheap and reliable. Its minimum time
// t_F, with the flight time inversely proportional to the thrust, estimates the problem's own:
// F t_F, some F t_F / P revolutions of the departure's period P. Where that is few revolutions, the problem's own
// search starts from it (the companion held at 1.5 F t_F, the starts' final times drawn about it); where it is many,
// the starts there are skipped (they rarely converge and cost the most) and the thrust route continues the search at F
// down to the problem's thrust.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The window is searched at the problem's own thrust where it allows at most this many revolutions.
constexpr double kScaleRevolutions = 4 * kFewRevolutions;

// The orbital period of the departure (normalized), from a short trajectory of a start's guess
// (its final time at the window's start, or just after the departure): its first state's
// osculating orbit. NaN where it is not bound or cannot be had.
inline double departure_period(SearchContext& c) {
  std::mt19937_64 rng = start_generator(c.coarse.seed, 0, kScaleStream);
  std::vector<double> x(static_cast<std::size_t>(kProblem.num_vars), 0.0);
  c.guess(rng, x.data());
  const double window = kProblem.tf - kProblem.tf_min;
  x[free_final_time().variable] = kProblem.tf_min > kProblem.t0 ? 0.0 : std::min(1.0, 1e-3 / window);
  RecordedPath path;
  try {
    path = recorded_path(c.coarse, x, c.coarse.eps_start, INFINITY);
  } catch (const numerical_error&) {
    return NAN;
  }
  if (path.samples.empty()) return NAN;
  const auto& y = path.samples.front().y;
  const double r = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  const double v2 = y[3] * y[3] + y[4] * y[4] + y[5] * y[5];
  const double a = 1 / (2 / r - v2 / kProblem.mu);
  return a > 0 ? 2 * M_PI * std::sqrt(a * a * a / kProblem.mu) : NAN;
}

// The longest flight the window allows: its end, but no later than full thrust burns the mass.
inline double longest_flight() {
  return std::min(kProblem.tf - kProblem.t0, 0.95 * burnout_time());
}

class TimeScaleRoute : public Route {
 public:
  const char* name() const override { return "time scale at a raised thrust"; }
  std::string skip(const SearchContext& c) const override {
    if (!c.coarse.search_thrust_continuation) return "search_thrust_continuation is off";
    if (c.nested) return "inside a search at a raised thrust";
    if (kProblem.objective != Objective::time || free_final_time().variable < 0)
      return "not a minimum-time problem with a free final time";
    if (!targets_fixed_in_time()) return "a target moves on the calendar: a raised thrust would meet it elsewhere";
    if (!c.knobs.thrust_scalable()) return "the program has no maximum thrust to scale";
    return "";
  }

  std::string run(SearchContext& c) override {
    const double period = departure_period(c);
    if (!(period > 0)) return "the departure's orbit is not bound: no revolutions to count";
    const double window_revolutions = longest_flight() / period;
    if (window_revolutions <= kScaleRevolutions)
      return "the window allows " + number_text(window_revolutions, 3) +
             " revolutions at most: the search at the problem's thrust is reliable";
    SearchRecord::TimeScale& scale = c.rec().time_scale;
    scale.factor = std::min(raise_factor(window_revolutions), std::exp2(kMaxThrustDoublings));
    const double sigma = std::log(scale.factor);
    c.knobs.scale_thrust(sigma);
    c.progress.stage("the window allows " + number_text(window_revolutions, 3) + " revolutions: thrust raised to " +
                     number_text(c.knobs.thrust_N(sigma)) + " N (x" + number_text(scale.factor) +
                     ") to measure the time scale");
    c.scale_search = nested_search(c);
    c.knobs.restore();
    c.count(c.scale_search.evaluations);
    ContinuationStep step{"raised thrust: the search there [N]", c.knobs.thrust_N(sigma),
                          c.scale_search.status == Status::kConverged, INFINITY, c.scale_search.evaluations};
    if (c.scale_search.status != Status::kConverged) {
      c.rec().thrust_continuation.push_back(step);
      return "the search at " + number_text(c.knobs.thrust_N(sigma)) + " N found no transfer: no time scale";
    }
    const Extremal& best = c.scale_search.search.extremals[c.scale_search.search.returned];
    step.max_residual = best.max_residual;
    step.revolutions = best.shape.revolutions;
    c.rec().thrust_continuation.push_back(step);
    scale.raised_tf_days = best.tf_days;
    scale.saturated = c.scale_search.search.saturated;
    scale.raised_revolutions = best.shape.revolutions;
    scale.estimate_days = scale.factor * best.tf_days;
    // Revolutions at the departure's period: an orbit raised on the way turns slower, so this errs
    // toward many (the thrust route), where the starts would risk failing.
    scale.revolutions = scale.estimate_days / (period * kProblem.time_unit_days);
    const std::string line = "minimum time " + days_text(best.tf_days, 6) + " at " +
                             number_text(c.knobs.thrust_N(sigma)) + " N (x" + number_text(scale.factor) + "): about " +
                             days_text(scale.estimate_days, 3) + " and " + number_text(scale.revolutions, 3) +
                             " revolutions at " + number_text(c.knobs.own_thrust_N()) + " N";
    c.progress.stage(line);
    return line;
  }
};

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the bound route (templates/runtime/search/bound.hpp): where the routes
// before it returned nothing, the minimum time sought past the stated bound, so that a problem
// whose bound is below its minimum time ends infeasible with that minimum instead of failed.
//
// A minimum-time problem: its window's end is opened to the longest flight the engine can make
// (95 % of the time full thrust burns the whole mass; 16 times the window without a mass flow) and
// the problem searched again there with every route but this one. Its returned extremal is the
// minimum time: beyond the stated end, it proves the problem infeasible (the record says the
// search settled it); within, the first search missed it, and it is an extremal of the problem as
// stated, entered into the pool.
//
// A minimum-fuel problem at a fixed final time: the final time is doubled until starts converge
// (at most kMaxOpenings times, never past the burnout), and each of the lowest-cost solutions there
// continued down in the final time to the minimum-time extremal of its family (time_route.hpp),
// and the minimum-time problem searched there by its own starts (search_minimum_time): the shortest
// of them, longer than the stated time, proves the problem infeasible; shorter, the fuel extremal
// is continued up from it to the stated time and entered into the pool. Targets that move on the
// calendar are met where they are at each final time, so this route serves a fixed-date rendezvous
// too.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

class BoundRoute : public Route {
 public:
  const char* name() const override { return "minimum time past the bound"; }
  std::string skip(const SearchContext& c) const override {
    if (c.nested || c.knobs.opened()) return "inside another search";
    if (best_index(c.rec()) >= 0) return "an extremal within the bound was reached";
    if (!c.knobs.final_time_movable()) return "the program's final time is not a parameter";
    if (free_final_time().variable >= 0) {
      if (kProblem.objective != Objective::time) return "not a minimum-time problem";
      if (!(opened_end() > kProblem.tf * (1 + 1e-9))) return "the window already ends where the engine burns out";
      return "";
    }
    if (!objective_is_propellant() || !throttle_has_fuel_cost() || lambda0_variable() < 0)
      return "not a minimum-fuel problem with a throttle that has a fuel cost";
    return "";
  }

  std::string run(SearchContext& c) override {
    const std::string line = free_final_time().variable >= 0 ? open_window(c) : lengthen_final_time(c);
    c.knobs.reset_base();
    c.progress.stage(line);
    return line;
  }

 private:
  static constexpr int kMaxOpenings = 6;
  static constexpr std::size_t kSources = 3;

  // The longest flight's end for a minimum-time problem (absolute, normalized).
  static double opened_end() {
    const double flow = full_throttle_cost_rate();
    return kProblem.t0 + (flow > 0 && !constant_mass() ? 0.95 / flow : 16 * (kProblem.tf - kProblem.t0));
  }

  std::string open_window(SearchContext& c) {
    SearchRecord& rec = c.rec();
    const double bound = kProblem.tf, end = opened_end(), tf_min = kProblem.tf_min;
    const double day = kProblem.time_unit_days;
    rec.bound_days = (bound - kProblem.t0) * day;
    const std::string how = "the window opened to " + days_text((end - kProblem.t0) * day, 6);
    c.progress.stage("nothing within the window: " + how + " to find the minimum time");
    c.knobs.open_final_time(end);
    const Result opened = Search(c.fine, c.guess, c.admissible, c.knobs, false, transfer_routes()).solve();
    c.count(opened.evaluations);
    if (opened.status != Status::kConverged) return how + ": no transfer found there either";
    const Extremal& best = opened.search.extremals[opened.search.returned];
    rec.minimum_time_days = best.tf_days;
    // Settled where the starts there saturated, at the problem's thrust or at the time scale's.
    rec.minimum_time_settled = opened.search.saturated || opened.search.time_scale.saturated;
    rec.minimum_time_how = how + ", the search there returned it by " + best.route +
                           (rec.minimum_time_settled ? ", its starts saturated" : ", its starts not saturated");
    if (helios::solve::beyond_bound(best.tf_days, rec.bound_days))
      return "minimum time " + days_text(best.tf_days) + ", " + how;
    // Within the stated window: the problem's own extremal, its final time as a fraction of the window.
    c.knobs.reset_base();
    Extremal entry = best;
    const int at = free_final_time().variable;
    entry.x[at] = (tf_min + (end - tf_min) * best.x[at] - tf_min) / (bound - tf_min);
    entry.shape = shape_of(c.coarse, entry.x, 0.0);
    entry.method += " (found with " + how + ")";
    c.pool.enter(name(), std::move(entry));
    return "minimum time " + days_text(best.tf_days) + " within the window, found with " + how;
  }

  std::string lengthen_final_time(SearchContext& c) {
    SearchRecord& rec = c.rec();
    const double own = c.knobs.final_time_unit(), day = kProblem.time_unit_days;
    const double burnout = kProblem.t0 + 0.95 * burnout_time();
    rec.bound_days = (own - kProblem.t0) * day;
    for (int k = 1; k <= kMaxOpenings && !c.out_of_time(); ++k) {
      const double longer = kProblem.t0 + (own - kProblem.t0) * std::exp2(k);
      if (longer > burnout) break;
      c.knobs.open_final_time(longer);
      c.progress.stage("nothing at the stated final time: the final time lengthened to " +
                       days_text((longer - kProblem.t0) * day, 6) + " to find the minimum time");
      std::vector<std::unique_ptr<Route>> routes;
      routes.push_back(std::make_unique<StartsRoute>());
      const Result there = Search(c.fine, c.guess, c.admissible, c.knobs, true, std::move(routes)).solve();
      c.count(there.evaluations);
      if (there.search.start_extremals.empty()) continue;
      return from_longer(
          c, there.search, longer,
          "the final time lengthened to " + days_text((longer - kProblem.t0) * day, 6) +
              (there.search.saturated ? ", where the starts saturated" : ", where the starts did not saturate"));
    }
    return "no start converged at any final time up to the burnout: no minimum time found";
  }

  // The minimum time from the solutions at the lengthened final time `longer`, then the fuel
  // extremal up from it to the stated time where it is shorter.
  std::string from_longer(SearchContext& c, const SearchRecord& there, double longer, const std::string& how) {
    SearchRecord& rec = c.rec();
    const int l0 = lambda0_variable();
    std::vector<double> shortest;
    for (const int k : lowest_cost(there.start_extremals, kSources)) {
      TimeRouteArrival a;
      std::vector<double> z;
      int evaluations = 0;
      const bool reached = minimum_time_from_fuel_solution(c.fine, c.fine, c.knobs, there.start_extremals[k].x,
                                                           c.coarse.eps_start, z, a, evaluations);
      c.count(evaluations);
      rec.time_route.insert(rec.time_route.end(), a.steps.begin(), a.steps.end());
      if (reached && (shortest.empty() || z[l0] < shortest[l0])) shortest = z;
    }
    // A fuel extremal continued down reaches its own family's minimum time only; the minimum-time
    // problem's own starts there reach the others (an NSTAR-like Earth-Mars rendezvous at 350 kg:
    // 638 days down the one family the fuel starts found, 388.9 days by the starts).
    std::string by = "continued down to the shortest final time that converges";
    const MinimumTimeSearch itself = search_minimum_time(c);
    for (const int k : lowest_cost(itself.found, 1))
      if (shortest.empty() || itself.found[k].x[l0] < shortest[l0]) {
        shortest = itself.found[k].x;
        by = "the minimum-time problem searched there";
      }
    if (shortest.empty()) return how + ": no minimum time reached from the solutions there nor by its own starts";
    const double t_min = shortest[l0] * longer;  // the held system's final time, a fraction of `longer`
    rec.minimum_time_days = (t_min - kProblem.t0) * kProblem.time_unit_days;
    rec.minimum_time_settled = itself.saturated;
    rec.minimum_time_how = how + ", then " + by +
                           (itself.saturated ? " (the minimum-time problem's starts saturated)"
                                             : " (the minimum-time problem's starts did not saturate)");
    if (helios::solve::beyond_bound(rec.minimum_time_days, rec.bound_days))
      return "minimum time " + days_text(rec.minimum_time_days) + " (" + how + ")";
    // Shorter than the stated time: the fuel extremal continued up from the minimum time to it.
    c.knobs.reset_base();
    shortest[l0] = t_min / c.knobs.final_time_unit();
    TimeRouteArrival a;
    int evaluations = 0;
    fuel_path_from_minimum_time(c.fine, c.fine, c.knobs, shortest, c.admissible, a, evaluations);
    c.count(evaluations);
    rec.time_route.insert(rec.time_route.end(), a.steps.begin(), a.steps.end());
    if (!a.arrived)
      return "minimum time " + days_text(rec.minimum_time_days) +
             "; minimum fuel from it did not reach the stated time";
    Extremal entry = arrival_extremal(c.coarse, a,
                                      "single shooting, minimum fuel continued from the minimum-time extremal (t_min " +
                                          days_text(rec.minimum_time_days) + ", " + how + ")");
    entry.homotopy = a.homotopy;
    c.pool.enter(name(), std::move(entry));
    return "minimum time " + days_text(rec.minimum_time_days) +
           ", minimum fuel continued up from it to the stated time";
  }
};

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the search's pipeline (templates/runtime/search/pipeline.hpp). A
// converged shooting solution is an extremal, not necessarily the optimum: on multi-revolution
// transfers the extremal a random start reaches is a matter of chance. So every solve is a search:
// the routes registered for the problem (route.hpp) run in order over one pool of extremals
// (pool.hpp), each deciding from what the routes before it found whether it applies, and the
// chooser (chooser.hpp) decides the answer and the verdict from the pool alone. The search runs at
// search_settings (the integrator at search_tol) and polishes every extremal at the integrator's
// own tolerance before the choice. Every stopping rule counts work; the run's time limit is the
// safety net, and the record says when it was reached.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The routes that look for transfers within the window, in order (a nested search, at a raised
// thrust, skips those that would call it again). A new route is its file and a line here.
inline std::vector<std::unique_ptr<Route>> transfer_routes() {
  std::vector<std::unique_ptr<Route>> routes;
  routes.push_back(std::make_unique<TimeScaleRoute>());
  routes.push_back(std::make_unique<CompanionRoute>());
  routes.push_back(std::make_unique<StartsRoute>());
  routes.push_back(std::make_unique<FamiliesRoute>());
  routes.push_back(std::make_unique<ThrustRoute>());
  return routes;
}

// The routes of a problem without interior events: the transfer routes, then the minimum-time
// route, the windows' edges and the bound (whose search past the window runs the transfer routes).
inline std::vector<std::unique_ptr<Route>> eventless_routes() {
  std::vector<std::unique_ptr<Route>> routes = transfer_routes();
  routes.push_back(std::make_unique<TimeRoute>());
  routes.push_back(std::make_unique<EdgeRoute>());
  routes.push_back(std::make_unique<BoundRoute>());
  return routes;
}

Result nested_search(SearchContext& parent, double estimate) {
  Search search(parent.fine, parent.guess, parent.admissible, parent.knobs, true, eventless_routes());
  if (estimate > 0) search.estimate_time(estimate);
  return search.solve();
}

}  // namespace

// Problems without interior events: the global search. With a warm start (a sweep's converged
// neighbour) the search runs only when the warm solve fails and the settings allow it (not warm_only).
Result homotopy_solve(const Settings& s, const Guess& initial_guess, const Admissible& admissible) {
  ProgramKnobs knobs;
  if (s.warm_start.empty()) return Search(s, initial_guess, admissible, knobs, false, eventless_routes()).solve();
  Result warm = warm_solve(s, admissible);
  if (warm.status == Status::kConverged || s.warm_only) return warm;
  Result r = Search(s, initial_guess, admissible, knobs, false, eventless_routes()).solve();
  r.start = "cold-after-warm-failed";
  r.start_detail = warm.detail;
  r.evaluations += warm.evaluations;
  return r;
}

// Problems with interior events: complete attempts (attempts.hpp).
Result events_homotopy_solve(const Settings& fine, const LegPlan& legs, const EventPlan& events,
                             const Guess& initial_guess, const Admissible& admissible) {
  ProgramKnobs knobs;
  std::vector<std::unique_ptr<Route>> routes;
  routes.push_back(std::make_unique<AttemptsRoute>(legs, events));
  routes.push_back(std::make_unique<EdgeRoute>());
  Result r = Search(fine, initial_guess, admissible, knobs, false, std::move(routes)).solve();
  if (r.status != Status::kConverged) r.method = r.search.method;
  if (!fine.warm_start.empty())
    r.start_detail = "a warm start is not used on problems with interior events: the search starts cold";
  return r;
}

}  // namespace helios_rt

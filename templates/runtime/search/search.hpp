// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, one search (templates/runtime/search/search.hpp): its routes run in
// order over one pool of extremals, each deciding from what the routes before it found whether it
// applies, then every extremal polished at the integrator's own tolerance and the answer and the
// verdict decided by the chooser (chooser.hpp) from the pool alone. The routes a problem runs are
// registered in pipeline.hpp; a route may run a search of its own (at a raised thrust, in an
// opened window).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// One search: its routes run in order over one pool, then the extremals polished, the best chosen
// and the verdict given.
class Search {
 public:
  Search(const Settings& fine, const Guess& guess, const Admissible& admissible, ProgramKnobs& knobs, bool nested,
         std::vector<std::unique_ptr<Route>> routes)
      : fine_(fine),
        coarse_(search_settings(fine)),
        pool_(r_.search),
        context_(fine_, coarse_, guess, admissible, pool_, knobs, progress_, nested),
        routes_(std::move(routes)) {
    r_.search.threads = context_.threads;
    r_.search.method = "routes over one pool of extremals:";
    for (const auto& route : routes_) r_.search.method += std::string(" ") + route->name() + ";";
  }

  // The minimum time is known to be about `estimate` (normalized): the companion and the starts
  // start from it (scale.hpp).
  void estimate_time(double estimate) { r_.search.time_scale.estimate_days = estimate * kProblem.time_unit_days; }

  Result solve() {
    SearchRecord& rec = r_.search;
    for (const auto& route : routes_) {
      SearchRecord::RouteRun run;
      run.name = route->name();
      run.outcome = context_.out_of_time() ? std::string("not run: the time limit was reached") : route->skip(context_);
      if (run.outcome.empty()) {
        const int before = context_.evaluations();
        run.ran = true;
        run.outcome = route->run(context_);
        run.evaluations = context_.evaluations() - before;
        run.added = pool_.added_by(route->name());
      }
      rec.routes.push_back(run);
    }
    finish();
    return r_;
  }

 private:
  // The extremals polished at the integrator's tolerance, the best into r, else the verdict.
  void finish() {
    SearchRecord& rec = r_.search;
    pool_.polish(fine_, coarse_);
    rec.seconds = wall_seconds() - context_.started;
    rec.time_limit_hit = out_of_time(fine_);
    const Choice choice =
        choose(rec, "by " + std::to_string(rec.routes.size()) + " routes (" + std::to_string(rec.starts) + " starts)");
    rec.returned = choice.returned;
    rec.reason = choice.reason;
    say_if_not_saturated();
    const Verdict v = verdict(
        rec, [](double days) { return days_text(days); }, objective_text,
        "no route reached an extremal at eps = 0 (" + std::to_string(rec.starts) + " starts, " +
            std::to_string(rec.converged_start) + " converged at eps_start)");
    r_.status = v.status;
    r_.detail = v.detail;
    r_.attempts = rec.starts;
    r_.evaluations = context_.evaluations();
    r_.iterations = rec.starts + rec.continued;
    if (rec.returned >= 0) {
      take_extremal();
      progress_.stage("returned extremal " + std::to_string(rec.returned) + ": " + rec.reason);
    } else {
      progress_.stage(std::string(status_text(r_.status)) + ": " + r_.detail);
    }
  }

  // Copies the returned extremal into r.
  void take_extremal() {
    const Extremal& e = r_.search.extremals[r_.search.returned];
    r_.method = e.method;
    r_.info = e.info;
    r_.x = e.x;
    r_.x_start = e.x_start;
    r_.F = e.F;
    r_.window_edges = e.window_edges;
    r_.edge_transversality = e.edge_transversality;
    r_.eps = 0;
    r_.max_residual = e.max_residual;
    r_.homotopy = e.homotopy;
    r_.legs = e.legs;
    r_.continuation = e.continuation;
  }

  // Says on stderr when the starts stopped before they were saturated, why, and what would let
  // them go on.
  void say_if_not_saturated() {
    const SearchRecord& rec = r_.search;
    if (rec.saturated || rec.stopped.empty()) return;
    const bool capped = rec.stopped.rfind("the cap", 0) == 0;
    const int converged =
        rec.eventless_draws > 0 || rec.converged_start == 0 ? rec.converged_final : rec.converged_start;
    progress_.stage("not saturated: " + std::to_string(converged) + " of " + std::to_string(rec.starts) +
                    " starts converged, and the chance that another finds a new extremal is " +
                    number_text(rec.unseen, 3) + " (saturated: at most " + number_text(coarse_.search_saturation, 3) +
                    "); stopped by " + rec.stopped + ". " +
                    (rec.returned >= 0       ? "The best extremal found is returned"
                     : rec.extremals.empty() ? "Nothing was found"
                                             : "None of the extremals found may be returned") +
                    "; " +
                    (capped                      ? "a larger search_starts (or max_attempts)"
                     : coarse_.search_time_s > 0 ? "a larger search_time_s (or none)"
                                                 : "a larger time_limit_s") +
                    " lets the search go on.");
  }

  const Settings fine_, coarse_;
  Result r_;
  Pool pool_;
  Progress progress_;
  SearchContext context_;
  std::vector<std::unique_ptr<Route>> routes_;
};

}  // namespace

}  // namespace helios_rt

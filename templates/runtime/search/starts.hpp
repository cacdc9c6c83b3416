// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the starts route (templates/runtime/search/starts.hpp): seeded random
// starts, each solved at eps_start (eps = 1: the smooth, energy-like problem), drawn until
// saturated (draws.hpp) or their cap; the converged ones told apart (revolutions, throttle mode
// changes, the shooting variables) and ranked by their own cost at eps_start, a lower bound of the
// objective their branch reaches at eps = 0; every one whose cost could still beat the best
// objective found continued in eps to 0, cheapest first. While nothing has arrived at eps = 0,
// more starts are drawn, past saturation (the estimate counts what was reached at eps_start, and
// none of it reached eps = 0), up to the cap.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

class StartsRoute : public Route {
 public:
  const char* name() const override { return "starts"; }
  std::string skip(const SearchContext& c) const override {
    if (c.many_revolutions_expected())
      return "the time scale expects " + number_text(c.rec().time_scale.revolutions, 3) +
             " revolutions: starts rarely converge there, the thrust route reaches them";
    return "";
  }

  std::string run(SearchContext& c) override {
    SearchRecord& rec = c.rec();
    explore(c, start_cap(c.coarse), false);
    continue_promising(c);
    // While nothing has arrived: as many starts again (kMinDraws at least), past saturation and
    // search_starts, up to max_attempts (at most kMoreStarts unless search_starts is larger); not
    // in a nested search, whose caller has its own routes to go on with.
    const int most = c.nested ? 0 : std::min(c.coarse.max_attempts, std::max(start_cap(c.coarse), kMoreStarts));
    while (rec.extremals.empty() && rec.starts < most && !c.out_of_time()) {
      explore(c, std::min(most, rec.starts + std::max(kMinDraws, rec.starts)), true);
      continue_promising(c);
    }
    return std::to_string(rec.starts) + " starts, " + std::to_string(rec.converged_start) +
           " converged at eps_start, " + std::to_string(rec.start_extremals.size()) + " distinct, " +
           std::to_string(rec.continued) + " continued to eps = 0; " + rec.stopped;
  }

 private:
  static std::string eps_text(const SearchContext& c) { return number_text(c.coarse.eps_start, 3); }

  // Draws starts until they are saturated (unless `past_saturation`) or `cap` starts were drawn;
  // records why they stopped.
  void explore(SearchContext& c, int cap, bool past_saturation) {
    SearchRecord& rec = c.rec();
    const DrawStop stop = draw_until_saturated(
        c.coarse, c.threads, kStartStream, rec.start_extremals, rec.starts, rec.converged_start, rec.cut_by_time, cap,
        c.started, [&](int, std::mt19937_64& rng) { return start(c, rng); },
        [&](const StartRun& run, int k) { c.pool.enter_start(rec.start_extremals, run, k); },
        [&](int k) { c.progress.tick(std::to_string(k) + " starts at eps = " + eps_text(c)); }, past_saturation);
    rec.unseen = unseen_chance(rec.start_extremals, rec.starts);
    rec.saturated = saturated(c.coarse, rec.start_extremals, rec.starts);
    char why[160];
    if (stop == DrawStop::kSaturated || (rec.saturated && stop == DrawStop::kCap))
      std::snprintf(why, sizeof why, "saturated: the chance that another start finds a new extremal is %.3g <= %.3g",
                    rec.unseen, c.coarse.search_saturation);
    else if (stop == DrawStop::kCap)
      std::snprintf(why, sizeof why, "the cap of %d starts (search_starts, max_attempts)", cap);
    else if (c.coarse.search_time_s > 0)
      std::snprintf(why, sizeof why, "the time cap search_time_s (%g s) or the time limit (time_limit_s %.0f s)",
                    c.coarse.search_time_s, c.coarse.time_limit_s);
    else
      std::snprintf(why, sizeof why, "the time limit (time_limit_s %.0f s)", c.coarse.time_limit_s);
    rec.stopped = why;
    c.progress.stage(std::to_string(rec.starts) + " starts at eps = " + eps_text(c) + ": " +
                     std::to_string(rec.converged_start) + " converged, " + std::to_string(rec.start_extremals.size()) +
                     " distinct extremals; " + rec.stopped);
  }

  // Start k at eps_start from the guess its generator draws.
  static StartRun start(SearchContext& c, std::mt19937_64& rng) {
    StartRun run;
    run.x.assign(kProblem.num_vars, 0.0);
    c.guess(rng, run.x.data());
    draw_final_time(c, rng, run.x);
    // Most starts fail: each is first solved on the looser integration (loose_settings), and only
    // one that converges there is solved again at the search's tolerance, from where it arrived.
    const Settings loose = loose_settings(c.coarse);
    Shooter rough(loose);
    rough.stop_below(loose.accept_residual);
    int info = 0;
    run.ok = rough.solve(run.x, loose.eps_start, loose.accept_residual, info, run.res);
    c.count(rough.evaluations);
    if (!run.ok) return run;
    // Where it lands next to an extremal the starts before this batch reached (the list is read
    // only while a batch runs, so this does not depend on the thread count), it is that extremal
    // again: counted as its twin, without solving it again or taking its shape.
    if (const StartExtremal* twin = near_twin(c.rec().start_extremals, run.x)) {
      run.x = twin->x;
      run.shape = twin->shape;
      run.res = twin->max_residual;
      return run;
    }
    Shooter shooter(c.coarse, kContinuationStart);
    run.ok =
        shooter.solve(run.x, c.coarse.eps_start, c.coarse.accept_residual, info, run.res) && c.admissible(run.x.data());
    if (run.ok) run.shape = shape_of(c.coarse, run.x, c.coarse.eps_start);
    c.count(shooter.evaluations);
    return run;
  }

  // Where the time scale estimated the minimum time t (scale.hpp), a free final time is drawn
  // log-uniformly in [t/2, 2t] (within the window) instead of the guess's spread over the window.
  static void draw_final_time(const SearchContext& c, std::mt19937_64& rng, std::vector<double>& x) {
    const int at = free_final_time().variable;
    const double t = c.estimated_time(), window = kProblem.tf - kProblem.tf_min;
    if (at < 0 || !(t > 0) || !(window > 0)) return;
    const double tf = kProblem.t0 + t * std::exp2(std::uniform_real_distribution<double>(-1.0, 1.0)(rng));
    x[at] = std::clamp((tf - kProblem.tf_min) / window, 0.0, 1.0);
  }

  // Continues the eps_start extremals not continued yet, lowest cost first, search_continued at a
  // time (a fixed batch: the pruning between batches must not depend on the thread count). The
  // cost of an extremal at eps_start is a lower bound of the objective its branch reaches at
  // eps = 0 (along a smooth branch dJ/deps = -integral u (1 - u) dt <= 0, the envelope theorem),
  // so one whose cost is not below the best objective found cannot beat it: it is marked pruned
  // instead (all are continued with search_continue_all). While none has arrived, the next ones go
  // regardless.
  void continue_promising(SearchContext& c) {
    SearchRecord& rec = c.rec();
    const std::size_t size = static_cast<std::size_t>(std::max(1, c.coarse.search_continued));
    for (;;) {
      std::vector<int> order = untried(rec);
      if (order.empty() || c.out_of_time()) return;
      const double best = best_objective(rec);
      std::vector<int> batch;
      for (const int i : order) {
        if (batch.size() >= size) break;
        if (!c.coarse.search_continue_all && std::isfinite(best) && rec.start_extremals[i].shape.cost >= best) {
          rec.start_extremals[i].pruned = true;
          continue;
        }
        batch.push_back(i);
      }
      if (batch.empty()) return;
      continue_start_extremals(c, name(), batch);
    }
  }

  // The eps_start extremals not continued (or pruned) yet, lowest cost first.
  static std::vector<int> untried(const SearchRecord& rec) {
    std::vector<int> order;
    for (std::size_t i = 0; i < rec.start_extremals.size(); ++i)
      if (!rec.start_extremals[i].continued && !rec.start_extremals[i].pruned) order.push_back(static_cast<int>(i));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return rec.start_extremals[a].shape.cost < rec.start_extremals[b].shape.cost;
    });
    return order;
  }
};

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the attempts route (templates/runtime/search/attempts.hpp): problems
// with interior events, searched over complete attempts independent of one another. When every
// event is passable, the problem without them is searched first (the events-off draws) and attempt
// k continues onto the events from its distinct solutions in turn (k mod their number; the first
// attempt from each places the epochs where it passes closest to the targets); an attempt that does
// not converge so tries the legs (continuation.hpp, legs.hpp). The converged ones enter the pool;
// attempts go on past search_attempts while none has converged, or while the extremals reached do
// not look saturated (some extremal reached by one attempt only), in batches of search_attempts.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

class AttemptsRoute : public Route {
 public:
  AttemptsRoute(const LegPlan& legs, const EventPlan& events) : legs_(legs), events_(events) {}
  const char* name() const override { return "complete attempts"; }
  std::string skip(const SearchContext&) const override { return ""; }

  std::string run(SearchContext& c) override {
    const Settings& s = c.coarse;
    SearchRecord& rec = c.rec();
    rec.method = events_.passable ? "the problem with its events off searched first; then complete attempts, each a "
                                    "continuation onto the events from its distinct solutions in turn, else legs, then "
                                    "multiple shooting"
                                  : "complete attempts: legs, then multiple shooting, then single shooting";
    if (events_.passable) eventless_search(c);
    const int eventless = static_cast<int>(rec.start_extremals.size());
    const int batch = std::max(1, s.search_attempts);
    int next = 0;
    std::atomic<int> done{0};
    while (!c.out_of_time() && next < s.max_attempts && (next < s.search_attempts || !saturated(c))) {
      const int to = std::min(s.max_attempts, next + batch);
      std::vector<Result> results(static_cast<std::size_t>(to - next));
      std::vector<char> ran(results.size(), 0);
      parallel_for(to - next, c.threads, [&](int i) {
        if (c.out_of_time()) return;
        attempt(c, next + i, eventless, results[i]);
        ran[i] = 1;
        c.progress.tick(std::to_string(next + ++done) + " attempts done");
      });
      for (int i = 0; i < to - next; ++i) {
        if (!ran[i]) {
          rec.cut_by_time = true;
          continue;
        }
        if (eventless > 0) {
          rec.start_extremals[(next + i) % eventless].continued = true;
          ++rec.continued;
        }
        record_attempt(c, next + i, eventless, results[i]);
      }
      done = 0;
      next = to;
      const double best = best_objective(rec);
      c.progress.stage(std::to_string(rec.starts) + " attempts: " + std::to_string(rec.converged_final) +
                       " converged, " + std::to_string(rec.extremals.size()) + " distinct extremals" +
                       (std::isfinite(best) ? ", best " + objective_text(best) : ""));
    }
    rec.saturated = saturated(c);
    rec.unseen = unseen_chance(rec.extremals, rec.starts);
    rec.stopped = rec.saturated            ? "saturated: every extremal reached by more than one attempt"
                  : next >= s.max_attempts ? "the cap of " + std::to_string(s.max_attempts) + " attempts (max_attempts)"
                                           : "the time limit (time_limit_s)";
    return std::to_string(rec.starts) + " attempts, " + std::to_string(rec.extremals.size()) + " distinct extremals; " +
           rec.stopped;
  }

 private:
  bool saturated(const SearchContext& c) const {
    const SearchRecord& rec = c.rec();
    return c.coarse.search_saturation > 0 && rec.starts >= c.coarse.search_attempts && !rec.extremals.empty() &&
           unseen_chance(rec.extremals, rec.starts) <= c.coarse.search_saturation;
  }

  // The problem with its events off solved from draws j = 0, 1, ... (one scale-free random guess
  // each, from the generator of (seed, j) on a stream of its own) in batches of kSearchBatch on the
  // search's threads, until a batch has converged draws or search_attempts x leg_attempts draws
  // were made. Its distinct solutions go into rec.start_extremals (converged_start,
  // eventless_draws), lowest cost at eps_start first, with the solve that found each
  // (eventless_solves_).
  void eventless_search(SearchContext& c) {
    const Settings& s = c.coarse;
    SearchRecord& rec = c.rec();
    std::vector<ContinuationStep> found_by;
    const int most = std::max(1, s.search_attempts) * std::max(1, s.leg_attempts);
    while (rec.eventless_draws < most && rec.converged_start == 0 && !c.out_of_time()) {
      const int from = rec.eventless_draws, to = std::min(most, from + kSearchBatch);
      std::vector<Result> solves(static_cast<std::size_t>(to - from));
      std::vector<std::vector<double>> x(solves.size());
      std::vector<char> ran(solves.size(), 0), ok(solves.size(), 0);
      parallel_for(to - from, c.threads, [&](int i) {
        if (c.out_of_time()) return;
        std::mt19937_64 rng = start_generator(s.seed, from + i, kEventlessStream);
        int e = 0;
        ok[i] = eventless_draw(s, events_, c.guess, c.admissible, rng, from + i, x[i], solves[i], e);
        ran[i] = 1;
        c.count(e);
      });
      for (int i = 0; i < to - from; ++i) {
        if (!ran[i]) {
          rec.cut_by_time = true;
          continue;
        }
        ++rec.eventless_draws;
        if (!ok[i]) continue;
        ++rec.converged_start;
        StartRun run;
        run.x = x[i];
        run.shape = shape_of(s, x[i], s.eps_start);
        run.res = solves[i].continuation.back().max_residual;
        const std::size_t before = rec.start_extremals.size();
        c.pool.enter_start(rec.start_extremals, run, from + i);
        if (rec.start_extremals.size() > before) found_by.push_back(solves[i].continuation.back());
      }
    }
    const std::vector<int> order = lowest_cost(rec.start_extremals, rec.start_extremals.size());
    std::vector<StartExtremal> sorted;
    for (const int i : order) {
      sorted.push_back(std::move(rec.start_extremals[i]));
      eventless_solves_.push_back(found_by[i]);
    }
    rec.start_extremals = std::move(sorted);
    c.progress.stage(std::to_string(rec.eventless_draws) +
                     " draws with the events off: " + std::to_string(rec.converged_start) + " converged, " +
                     std::to_string(rec.start_extremals.size()) + " distinct");
  }

  // Attempt k: from the events-off solutions in turn (lowest cost first), else by legs.
  void attempt(SearchContext& c, int k, int eventless, Result& a) {
    const Settings& s = c.coarse;
    std::mt19937_64 rng = start_generator(s.seed, k);
    Shooter single(s);
    a.attempts = k + 1;  // legs_attempt: attempt 1 starts in the middle of every window
    int evaluations = 0;
    if (eventless > 0) {
      a.continuation.push_back(eventless_solves_[k % eventless]);
      continuation_attempt(s, events_, c.guess, c.admissible, rng, c.rec().start_extremals[k % eventless].x,
                           k / eventless, a, evaluations);
    }
    if (a.status != Status::kConverged && !c.out_of_time())
      legs_attempt(s, legs_, c.guess, c.admissible, rng, single, a, evaluations);
    c.count(evaluations + single.evaluations);
  }

  // Attempt k's outcome into the pool: a converged one's extremal told apart from those already
  // reached (or counted with its twin), and the events-off solution it continued marked as arrived.
  void record_attempt(SearchContext& c, int k, int eventless, Result& a) {
    SearchRecord& rec = c.rec();
    ++rec.starts;
    if (a.status != Status::kConverged) return;
    Extremal entry;
    entry.x = a.x;
    entry.shape = shape_of(c.coarse, a.x, 0.0);
    entry.F = a.F;
    entry.x_start = a.x_start;
    entry.max_residual = a.max_residual;
    entry.info = a.info;
    entry.method = a.method;
    entry.homotopy = std::move(a.homotopy);
    entry.legs = std::move(a.legs);
    entry.continuation = std::move(a.continuation);
    const int i = c.pool.enter(name(), std::move(entry), k);
    rec.extremals[i].from.push_back(k);
    if (eventless > 0 && rec.start_extremals[k % eventless].arrived < 0) rec.start_extremals[k % eventless].arrived = i;
  }

  const LegPlan& legs_;
  const EventPlan& events_;
  std::vector<ContinuationStep> eventless_solves_;
};

}  // namespace

}  // namespace helios_rt

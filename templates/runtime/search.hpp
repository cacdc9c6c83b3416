// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, global search (templates/runtime/search.hpp): the last
// header of runtime.hpp. A converged shooting solution is an extremal, not necessarily the optimum: on
// multi-revolution transfers the extremal a random start reaches is a matter of chance. So the
// solve is a search:
//   1. starts: seeded guesses, each solved at eps_start (eps = 1: the smooth, energy-like
//      problem), in batches on `threads` threads, until search_starts or until the distinct
//      extremals look complete (a Good-Turing estimate below search_saturation);
//   2. the converged ones are told apart by what makes them different (revolutions about the
//      central body, throttle mode changes, the shooting variables) and ranked by their own cost
//      at eps_start;
//   3. the search_continued lowest-cost distinct extremals are continued in eps to 0 (then the
//      next ones, while none has arrived), and the distinct extremals at eps = 0 are compared:
//      the lowest objective is returned.
// Problems with interior events search the same way over search_attempts complete attempts
// (each a continuation onto the events from a solution of the problem without them, searched
// first, or a solve by legs: events_homotopy_solve). The search integrates at search_tol and
// polishes every extremal at eps = 0 at the integrator's own tolerance before comparing. Start k draws
// its guess from a generator seeded by (seed, k), and the outcomes are merged in start order, so
// the search is deterministic for a given seed whatever the thread count, unless its time budget
// (search_time_s, time_limit_s) cuts it, which the record says.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// A stream of draws other than the starts' own (0): the events-off draws (eventless_search).
constexpr std::uint64_t kEventlessStream = 1;

// The generator of start k (of a stream): SplitMix64 of (seed, k, stream), so a start's guess does
// not depend on which thread runs it or on how many starts came before.
inline std::mt19937_64 start_generator(unsigned seed, int k, std::uint64_t stream = 0) {
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) + static_cast<std::uint64_t>(k) + 0x9e3779b97f4a7c15ull +
                    stream * 0xd1b54a32d192ed03ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return std::mt19937_64(z ^ (z >> 31));
}

// Runs work(k) for k = 0 .. n-1 on up to `threads` threads, each index once. The active set of
// the bounds is thread-local: each worker starts with the caller's. The first exception a work
// item throws stops the others' next items and is rethrown here.
template <class Work>
void parallel_for(int n, int threads, Work&& work) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const BoundState bounds = bound_state();
  const auto loop = [&](bool worker) {
    if (worker) bound_state() = bounds;
    for (int k; (k = next++) < n;) {
      try {
        work(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(threads, n); ++t) {
    try {
      pool.emplace_back(loop, true);
    } catch (const std::system_error&) {
      break;  // no more threads to be had (a process limit): the others share the work
    }
  }
  loop(false);
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

// One line on stderr per stage and at most one every two seconds in between, so a user waiting
// for a long search sees it working.
class Progress {
 public:
  void stage(const std::string& line) { print(line, true); }
  void tick(const std::string& line) { print(line, false); }

 private:
  void print(const std::string& line, bool always) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const double now = wall_seconds();
    if (!always && now - last_ < 2.0) return;
    last_ = now;
    std::fprintf(stderr, "search: %s (%.1f s)\n", line.c_str(), now);
    std::fflush(stderr);
  }
  std::mutex mutex_;
  double last_ = -INFINITY;
};

// Two converged solutions are one extremal when their structure agrees (revolutions, switches)
// and their shooting variables or their cost do.
inline bool same_extremal(const std::vector<double>& xa, const Shape& a, const std::vector<double>& xb,
                          const Shape& b) {
  if (a.switches != b.switches || std::fabs(a.revolutions - b.revolutions) > 1e-3) return false;
  double dx = 0, size = 1;
  for (std::size_t i = 0; i < xa.size(); ++i) {
    dx = std::max(dx, std::fabs(xa[i] - xb[i]));
    size = std::max(size, std::fabs(xa[i]));
  }
  return dx <= 1e-6 * size || std::fabs(a.cost - b.cost) <= 1e-9 * std::max(1e-3, std::fabs(a.cost));
}

// Adds a converged solution to the distinct ones (`list` of StartExtremal or Extremal); returns
// its index.
template <class List>
int merge_extremal(List& list, const std::vector<double>& x, const Shape& shape, int start,
                   typename List::value_type&& entry) {
  for (std::size_t i = 0; i < list.size(); ++i)
    if (same_extremal(list[i].x, list[i].shape, x, shape)) {
      ++list[i].reached;
      return static_cast<int>(i);
    }
  entry.x = x;
  entry.shape = shape;
  entry.first_start = start;
  entry.reached = 1;
  list.push_back(std::move(entry));
  return static_cast<int>(list.size()) - 1;
}

// The extremal at eps = 0 with the lowest objective, the first reached among equals (-1: none).
// Only a polished one counts.
inline int best_index(const SearchRecord& rec) {
  int best = -1;
  for (std::size_t i = 0; i < rec.extremals.size(); ++i)
    if (rec.extremals[i].polished && (best < 0 || rec.extremals[i].shape.cost < rec.extremals[best].shape.cost))
      best = static_cast<int>(i);
  return best;
}

// The settings the search runs at: the integrator at search_tol (never tighter than its own), and
// eps = 0 accepted at accept_residual, since every extremal found is polished afterwards.
inline Settings search_settings(const Settings& s) {
  Settings coarse = s;
  if (s.search_tol > 0) {
    coarse.rtol = std::max(s.rtol, s.search_tol);
    coarse.atol = std::max(s.atol, s.search_tol);
  }
  if (coarse.rtol != s.rtol || coarse.atol != s.atol)
    coarse.final_residual = std::max(s.final_residual, s.accept_residual);
  return coarse;
}

// Each distinct extremal at eps = 0 found at the search's tolerance, solved again at the
// integrator's own (`fine`) from there, where the search's was looser: a single shooting solve at
// eps = 0 to final_residual, recorded in its homotopy, its shape (and objective) taken again.
// One that does not converge is kept in the record, marked, and not returned.
inline void polish_extremals(const Settings& fine, const Settings& coarse, SearchRecord& rec) {
  if (coarse.rtol == fine.rtol && coarse.atol == fine.atol) return;
  for (Extremal& e : rec.extremals) {
    if (wall_seconds() > fine.time_limit_s) {
      e.polished = false;
      continue;
    }
    Shooter shooter(fine, kContinuationStart);
    std::vector<double> x = e.x;
    int info = 0;
    double res = 0;
    Result step;
    const auto anything = [](const double*) { return true; };
    e.polished = homotopy_step(shooter, x, 0.0, fine.final_residual, step, anything, info, res);
    e.homotopy.insert(e.homotopy.end(), step.homotopy.begin(), step.homotopy.end());
    if (!e.polished) continue;
    e.x = x;
    e.F = shooter.last_F;
    e.max_residual = res;
    e.info = info;
    e.shape = shape_of(fine, x, 0.0);
  }
}

// The returned extremal: the best, and why.
inline void choose_best(SearchRecord& rec, const std::string& what) {
  rec.returned = best_index(rec);
  if (rec.returned < 0) return;
  const std::size_t n = rec.extremals.size();
  rec.reason =
      n == 1 ? "the only extremal reached at eps = 0 " + what
             : "the lowest objective of the " + std::to_string(n) + " distinct extremals reached at eps = 0 " + what;
}

// Copies the returned extremal into r.
inline void take_extremal(Result& r) {
  const Extremal& e = r.search.extremals[r.search.returned];
  r.status = "converged";
  r.detail.clear();
  r.method = e.method;
  r.info = e.info;
  r.x = e.x;
  r.x_start = e.x_start;
  r.F = e.F;
  r.eps = 0;
  r.max_residual = e.max_residual;
  r.homotopy = e.homotopy;
  r.legs = e.legs;
  r.continuation = e.continuation;
}

// An objective in named units for the progress lines.
inline std::string objective_text(double objective) {
  char buf[64];
  std::snprintf(buf, sizeof buf, objective_is_propellant() ? "%.6g kg of propellant" : "%.6g days",
                objective_in_named_unit(objective));
  return buf;
}

// Starts are drawn and merged in batches of this many.
constexpr int kSearchBatch = 8;

inline int search_threads(const Settings& s) {
  if (s.threads > 0) return s.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
}

inline bool search_time_left(const Settings& s, double started) {
  return wall_seconds() <= s.time_limit_s && (s.search_time_s <= 0 || wall_seconds() - started <= s.search_time_s);
}

// The best objective among the distinct extremals at eps = 0 (INFINITY: none yet).
inline double best_objective(const SearchRecord& rec) {
  const int best = best_index(rec);
  return best < 0 ? INFINITY : rec.extremals[best].shape.cost;
}

// After a search at `coarse` (search_settings(fine)): its extremals polished at `fine`, the best
// into r, else why there is none (`what_failed`, or the time).
inline void finish_search(const Settings& fine, const Settings& coarse, Result& r, double started,
                          const std::string& how, const std::string& what_failed, Progress& progress) {
  SearchRecord& rec = r.search;
  polish_extremals(fine, coarse, rec);
  rec.seconds = wall_seconds() - started;
  choose_best(rec, how);
  if (rec.returned >= 0) {
    take_extremal(r);
    progress.stage("returned extremal " + std::to_string(rec.returned) + ": " + rec.reason);
  } else if (wall_seconds() > fine.time_limit_s) {
    r.status = "timeout";
    r.detail = "time limit reached before convergence";
  } else if (!rec.extremals.empty()) {
    r.detail = "none of the " + std::to_string(rec.extremals.size()) +
               " extremals the search reached at eps = 0 converged again at the integrator's tolerance";
  } else {
    r.detail = what_failed;
  }
}

// Problems without interior events: the multi-start search at eps_start, the lowest-cost distinct
// extremals continued to eps = 0, the best kept (see the top of this file).
template <class Guess, class Admissible>
class MultiStart {
 public:
  // The search runs at `coarse` (search_settings(fine)); its extremals are polished at `fine`.
  MultiStart(const Settings& fine, const Settings& coarse, Guess& guess, Admissible& admissible)
      : fine_(fine), s_(coarse), guess_(guess), admissible_(admissible), rec_(r_.search), started_(wall_seconds()) {
    rec_.threads = search_threads(coarse);
    rec_.method = "multi-start at eps = " + eps_text() + ", the lowest-cost distinct extremals continued to eps = 0";
  }

  Result solve() {
    int next_start = 0;
    bool first_round = true;
    while (time_left() && next_start < s_.max_attempts) {
      next_start = explore(next_start, first_round);
      // The most promising first; while none arrives, the next ones, a thread's worth at a time.
      const std::vector<int> order = untried();
      for (std::size_t taken = 0; taken < order.size() && time_left() && rec_.extremals.empty();) {
        const std::size_t end =
            std::min(order.size(), taken + (first_round ? std::max(1, s_.search_continued) : rec_.threads));
        continue_extremals(std::vector<int>(order.begin() + taken, order.begin() + end));
        taken = end;
        first_round = false;
      }
      first_round = false;
      if (!rec_.extremals.empty()) break;
    }
    r_.attempts = rec_.starts;
    r_.evaluations = evaluations_;
    r_.iterations = rec_.starts + rec_.continued;
    finish_search(fine_, s_, r_, started_,
                  "from " + std::to_string(rec_.continued) + " of " + std::to_string(rec_.start_extremals.size()) +
                      " distinct extremals at eps_start, found by " + std::to_string(rec_.starts) + " starts",
                  "no start reached eps = 0 (" + std::to_string(rec_.starts) + " starts, " +
                      std::to_string(rec_.converged_start) + " converged at eps_start)",
                  progress_);
    return r_;
  }

 private:
  struct StartRun {
    bool ok = false;
    std::vector<double> x;  // empty: not run (the time ran out)
    Shape shape;
    double res = INFINITY;
  };

  std::string eps_text() const { return std::to_string(s_.eps_start).substr(0, 4); }
  bool time_left() const { return search_time_left(s_, started_); }
  void count(int evaluations) {
    const std::lock_guard<std::mutex> lock(mutex_);
    evaluations_ += evaluations;
  }

  // Starts from next_start in batches of kSearchBatch (merged in order, so the stop does not
  // depend on the threads) until search_starts (the first round; later rounds a quarter of it),
  // or until the extremals at eps_start look complete: at least kSearchBatch converged and the
  // chance of a new one below search_saturation. Returns the next start.
  int explore(int next_start, bool first_round) {
    const int limit =
        std::min(s_.max_attempts, first_round ? std::max(1, s_.search_starts)
                                              : next_start + std::max(rec_.threads, s_.search_starts / 4));
    while (next_start < limit && time_left()) {
      const int to = std::min(limit, next_start + kSearchBatch);
      run_starts(next_start, to);
      next_start = to;
      if (rec_.converged_start >= kSearchBatch && unseen() < s_.search_saturation) break;
    }
    progress_.stage(std::to_string(rec_.starts) + " starts at eps = " + eps_text() + ": " +
                    std::to_string(rec_.converged_start) + " converged, " +
                    std::to_string(rec_.start_extremals.size()) + " distinct extremals");
    return next_start;
  }

  // Good-Turing: the chance that the next converged start reaches an extremal not seen yet is
  // about the share of converged starts whose extremal was reached once.
  double unseen() const {
    int once = 0;
    for (const auto& e : rec_.start_extremals) once += e.reached == 1;
    return rec_.converged_start > 0 ? static_cast<double>(once) / rec_.converged_start : 1.0;
  }

  // Start k at eps_start.
  StartRun start(int k) {
    StartRun run;
    std::mt19937_64 rng = start_generator(s_.seed, k);
    run.x.assign(kProblem.num_vars, 0.0);
    guess_(rng, run.x.data());
    Shooter shooter(s_);
    int info = 0;
    run.ok = shooter.solve(run.x, s_.eps_start, s_.accept_residual, info, run.res) && admissible_(run.x.data());
    if (run.ok) run.shape = shape_of(s_, run.x, s_.eps_start);
    count(shooter.evaluations);
    return run;
  }

  // Starts [from, to), in parallel, merged in start order into the distinct eps_start extremals.
  void run_starts(int from, int to) {
    std::vector<StartRun> runs(static_cast<std::size_t>(to - from));
    std::atomic<int> converged{0};
    parallel_for(to - from, rec_.threads, [&](int i) {
      if (!time_left()) return;
      runs[i] = start(from + i);
      converged += runs[i].ok;
      progress_.tick(std::to_string(rec_.starts + i + 1) + " starts at eps = " + eps_text() + ", " +
                     std::to_string(rec_.converged_start + converged.load()) + " converged");
    });
    for (int i = 0; i < to - from; ++i) {
      if (runs[i].x.empty()) {
        rec_.cut_by_time = true;
        continue;
      }
      ++rec_.starts;
      if (!runs[i].ok) continue;
      ++rec_.converged_start;
      StartExtremal entry;
      entry.max_residual = runs[i].res;
      merge_extremal(rec_.start_extremals, runs[i].x, runs[i].shape, from + i, std::move(entry));
    }
  }

  // The eps_start extremal `which` continued to eps = 0: true with `e` filled when it arrived.
  // Each eps step starts hybrd's trust region next to the last solution and must keep the
  // branch's revolutions: hybrd can land on another extremal's branch (seen on S13: from the
  // 3-revolution branch to the 4-revolution one), and the path would then report that extremal as
  // this one's continuation.
  bool continue_one(int which, Extremal& e) {
    const StartExtremal& from = rec_.start_extremals[which];
    Shooter shooter(s_, kContinuationStart);
    Result path;
    std::vector<double> x = from.x;
    double res = 0, revolutions = from.shape.revolutions;
    const auto on_branch = [&](const std::vector<double>& to, double eps) {
      const double now = shape_of(s_, to, eps).revolutions;
      if (std::fabs(now - revolutions) > 0.25) return false;
      revolutions = now;
      char line[96];
      std::snprintf(line, sizeof line, "continuing the extremal at eps_start %d: eps = %.3g", which, eps);
      progress_.tick(line);
      return true;
    };
    const bool ok = homotopy_to_zero(s_, shooter, x, path, admissible_, res, on_branch);
    count(shooter.evaluations);
    if (!ok) return false;
    e.x = x;
    e.x_start = path.x_start;
    e.F = shooter.last_F;
    e.max_residual = res;
    e.info = path.info;
    e.homotopy = path.homotopy;
    e.shape = shape_of(s_, x, 0.0);  // its cost is the objective
    e.method =
        "single shooting, eps continuation from the extremal at eps_start of start " + std::to_string(from.first_start);
    return true;
  }

  // Continues the given eps_start extremals to eps = 0 in parallel, merged in the order given.
  void continue_extremals(const std::vector<int>& which) {
    std::vector<Extremal> arrived(which.size());
    std::vector<char> ok(which.size(), 0);
    parallel_for(static_cast<int>(which.size()), rec_.threads, [&](int i) {
      if (time_left()) ok[i] = continue_one(which[i], arrived[i]);
    });
    for (std::size_t i = 0; i < which.size(); ++i) {
      StartExtremal& from = rec_.start_extremals[which[i]];
      from.continued = true;
      ++rec_.continued;
      if (!ok[i]) continue;
      ++rec_.converged_final;
      const int k =
          merge_extremal(rec_.extremals, arrived[i].x, arrived[i].shape, from.first_start, std::move(arrived[i]));
      Extremal& e = rec_.extremals[k];
      e.reached += from.reached - 1;  // every start that reached `from` led here
      e.from.push_back(which[i]);
      from.arrived = k;
    }
    const double best = best_objective(rec_);
    progress_.stage(std::to_string(rec_.continued) + " continued to eps = 0: " + std::to_string(rec_.extremals.size()) +
                    " distinct extremals" + (std::isfinite(best) ? ", best " + objective_text(best) : ""));
  }

  // The eps_start extremals not continued yet, lowest cost first.
  std::vector<int> untried() const {
    std::vector<int> order;
    for (std::size_t i = 0; i < rec_.start_extremals.size(); ++i)
      if (!rec_.start_extremals[i].continued) order.push_back(static_cast<int>(i));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return rec_.start_extremals[a].shape.cost < rec_.start_extremals[b].shape.cost;
    });
    return order;
  }

  const Settings& fine_;
  const Settings& s_;
  Guess& guess_;
  Admissible& admissible_;
  Result r_;
  SearchRecord& rec_;
  const double started_;
  Progress progress_;
  std::mutex mutex_;
  int evaluations_ = 0;
};

// The warm start: the neighbour's shooting variables at eps = 0 as the first guess, in the
// normalized units of the runtime (the length, time and mass units do not depend on the epoch or
// the flight time, so a neighbour's costates at its departure are this cell's guess at its own;
// they are not propagated). First a direct solve at eps = 0, then continuations in eps from
// small smoothing (1e-2, then 1e-1) down to 0, each from the neighbour's variables. The first to
// reach eps = 0 is the result; none: r.detail says so and the caller searches cold.
template <class Admissible>
Result warm_solve(const Settings& s, Admissible& admissible) {
  Result r;
  r.start = "warm";
  r.search.method = "warm start from a neighbour's solution (no search)";
  r.search.threads = 1;
  const double started = wall_seconds();
  int evaluations = 0;
  bool ok = false;
  std::vector<double> x;
  for (const double eps0 : {0.0, 1e-2, 1e-1}) {
    if (wall_seconds() > s.time_limit_s) break;
    x = s.warm_start;
    Result path;
    Shooter shooter(s, kContinuationStart);
    double res = 0;
    int info = 0;
    try {
      if (eps0 == 0) {
        ok = homotopy_step(shooter, x, 0.0, s.final_residual, path, admissible, info, res);
        path.x_start = x;
        path.info = info;
      } else {
        Settings from = s;
        from.eps_start = eps0;
        ok = homotopy_to_zero(from, shooter, x, path, admissible, res);
      }
    } catch (const numerical_error&) {
      ok = false;
    }
    evaluations += shooter.evaluations;
    r.iterations += path.iterations;
    r.homotopy.insert(r.homotopy.end(), path.homotopy.begin(), path.homotopy.end());
    if (!ok) continue;
    r.status = "converged";
    r.x = x;
    r.x_start = path.x_start;
    r.F = shooter.last_F;
    r.eps = 0;
    r.max_residual = res;
    r.info = path.info;
    r.method = eps0 == 0 ? "single shooting at eps = 0 from a neighbour's solution"
                         : "single shooting, eps continuation from " + std::to_string(eps0).substr(0, 4) +
                               " starting at a neighbour's solution";
    break;
  }
  r.evaluations = evaluations;
  r.attempts = 1;
  r.search.seconds = wall_seconds() - started;
  if (!ok) r.detail = "the warm start from the neighbour's solution did not reach eps = 0";
  return r;
}

}  // namespace

// Problems without interior events: the global search (MultiStart). `initial_guess(rng, x)` draws
// a start.
// With a warm start (a sweep's converged neighbour) the search runs only when the warm solve fails.
Result homotopy_solve(const Settings& s, const Guess& initial_guess, const Admissible& admissible) {
  const Settings coarse = search_settings(s);
  if (s.warm_start.empty())
    return MultiStart<const Guess, const Admissible>(s, coarse, initial_guess, admissible).solve();
  Result warm = warm_solve(s, admissible);
  if (warm.status == "converged") return warm;
  Result r = MultiStart<const Guess, const Admissible>(s, coarse, initial_guess, admissible).solve();
  r.start = "cold-after-warm-failed";
  r.start_detail = warm.detail;
  r.evaluations += warm.evaluations;
  return r;
}

// Problems whose events can all be switched off: the problem without them, solved from draws
// j = 0, 1, ... (one scale-free random guess each, from the generator of (seed, j) on a stream of
// its own) in batches of kSearchBatch on the search's threads, until a batch has converged draws
// or search_attempts x leg_attempts draws were made. Its distinct solutions go into
// rec.start_extremals (converged_start, eventless_draws), lowest cost at eps_start first; returns
// the solve that found each.
template <class Guess, class Admissible>
std::vector<ContinuationStep> eventless_search(const Settings& s, const EventPlan& events, Guess& initial_guess,
                                               Admissible& admissible, double started, SearchRecord& rec,
                                               int& evaluations, Progress& progress) {
  std::vector<ContinuationStep> found_by;
  const int most = std::max(1, s.search_attempts) * std::max(1, s.leg_attempts);
  std::mutex count;
  while (rec.eventless_draws < most && rec.converged_start == 0 && search_time_left(s, started)) {
    const int from = rec.eventless_draws, to = std::min(most, from + kSearchBatch);
    std::vector<Result> solves(static_cast<std::size_t>(to - from));
    std::vector<std::vector<double>> x(solves.size());
    std::vector<char> ran(solves.size(), 0), ok(solves.size(), 0);
    parallel_for(to - from, rec.threads, [&](int i) {
      if (!search_time_left(s, started)) return;
      std::mt19937_64 rng = start_generator(s.seed, from + i, kEventlessStream);
      int e = 0;
      ok[i] = eventless_draw(s, events, initial_guess, admissible, rng, from + i, x[i], solves[i], e);
      ran[i] = 1;
      const std::lock_guard<std::mutex> lock(count);
      evaluations += e;
    });
    for (int i = 0; i < to - from; ++i) {
      if (!ran[i]) {
        rec.cut_by_time = true;
        continue;
      }
      ++rec.eventless_draws;
      if (!ok[i]) continue;
      ++rec.converged_start;
      StartExtremal entry;
      entry.max_residual = solves[i].continuation.back().max_residual;
      const std::size_t before = rec.start_extremals.size();
      merge_extremal(rec.start_extremals, x[i], shape_of(s, x[i], s.eps_start), from + i, std::move(entry));
      if (rec.start_extremals.size() > before) found_by.push_back(solves[i].continuation.back());
    }
  }
  std::vector<std::size_t> order(found_by.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rec.start_extremals[a].shape.cost < rec.start_extremals[b].shape.cost;
  });
  std::vector<StartExtremal> sorted;
  std::vector<ContinuationStep> sorted_by;
  for (const std::size_t i : order) {
    sorted.push_back(std::move(rec.start_extremals[i]));
    sorted_by.push_back(found_by[i]);
  }
  rec.start_extremals = std::move(sorted);
  progress.stage(std::to_string(rec.eventless_draws) + " draws with the events off: " +
                 std::to_string(rec.converged_start) + " converged, " + std::to_string(rec.start_extremals.size()) +
                 " distinct");
  return sorted_by;
}

// Problems with interior events: search_attempts complete attempts, independent of one another.
// When every event is passable, the problem without them is searched first (eventless_search) and
// attempt k continues onto the events from its distinct solutions in turn (k mod their number;
// the first attempt from each places the epochs where it passes closest to the targets); an
// attempt that does not converge so tries the legs. The converged ones are told apart and the best
// kept; more attempts follow while none has converged. The attempts run at search_settings(fine);
// the extremals are polished at `fine`.
Result events_homotopy_solve(const Settings& fine, const LegPlan& legs, const EventPlan& events,
                             const Guess& initial_guess, const Admissible& admissible) {
  const Settings s = search_settings(fine);
  Result r;
  if (!s.warm_start.empty())
    r.start_detail = "a warm start is not used on problems with interior events: the search starts cold";
  SearchRecord& rec = r.search;
  rec.threads = search_threads(s);
  rec.method = events.passable ? "the problem with its events off searched first; then complete attempts, each a "
                                 "continuation onto the events from its distinct solutions in turn, else legs, then "
                                 "multiple shooting"
                               : "complete attempts: legs, then multiple shooting, then single shooting";
  r.method = rec.method;
  const double started = wall_seconds();
  Progress progress;
  int evaluations = 0;
  std::mutex count;
  std::atomic<int> done{0};
  // The solve that found each distinct events-off solution (rec.start_extremals).
  const std::vector<ContinuationStep> eventless_solves =
      events.passable ? eventless_search(s, events, initial_guess, admissible, started, rec, evaluations, progress)
                      : std::vector<ContinuationStep>{};
  const int eventless = static_cast<int>(rec.start_extremals.size());
  const auto attempt = [&](int k, Result& a) {
    std::mt19937_64 rng = start_generator(s.seed, k);
    Shooter single(s);
    a.attempts = k + 1;  // legs_attempt: attempt 1 starts in the middle of every window
    int attempt_evaluations = 0;
    if (eventless > 0) {  // the events-off solutions in turn, lowest cost first
      a.continuation.push_back(eventless_solves[k % eventless]);
      continuation_attempt(s, events, initial_guess, admissible, rng, rec.start_extremals[k % eventless].x,
                           k / eventless, a, attempt_evaluations);
    }
    if (a.status != "converged" && search_time_left(s, started))
      legs_attempt(s, legs, initial_guess, admissible, rng, single, a, attempt_evaluations);
    const std::lock_guard<std::mutex> lock(count);
    evaluations += attempt_evaluations + single.evaluations;
  };
  const auto merge = [&](int k, Result& a) {
    ++rec.starts;
    if (a.status != "converged") return;
    ++rec.converged_final;
    Extremal entry;
    entry.F = a.F;
    entry.x_start = a.x_start;
    entry.max_residual = a.max_residual;
    entry.info = a.info;
    entry.method = a.method;
    entry.homotopy = std::move(a.homotopy);
    entry.legs = std::move(a.legs);
    entry.continuation = std::move(a.continuation);
    const int i = merge_extremal(rec.extremals, a.x, shape_of(s, a.x, 0.0), k, std::move(entry));
    rec.extremals[i].from.push_back(k);
    if (eventless > 0 && rec.start_extremals[k % eventless].arrived < 0) rec.start_extremals[k % eventless].arrived = i;
  };
  int next = 0;
  while (search_time_left(s, started) && next < s.max_attempts && (next < s.search_attempts || rec.extremals.empty())) {
    const int to = std::min(s.max_attempts, next < s.search_attempts ? s.search_attempts : next + rec.threads);
    std::vector<Result> results(static_cast<std::size_t>(to - next));
    std::vector<char> ran(results.size(), 0);
    parallel_for(to - next, rec.threads, [&](int i) {
      if (!search_time_left(s, started)) return;
      attempt(next + i, results[i]);
      ran[i] = 1;
      progress.tick(std::to_string(next + ++done) + " attempts done");
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
      merge(next + i, results[i]);
    }
    done = 0;
    next = to;
    const double best = best_objective(rec);
    progress.stage(std::to_string(rec.starts) + " attempts: " + std::to_string(rec.converged_final) + " converged, " +
                   std::to_string(rec.extremals.size()) + " distinct extremals" +
                   (std::isfinite(best) ? ", best " + objective_text(best) : ""));
  }
  r.attempts = rec.starts;
  r.evaluations = evaluations;
  r.iterations = rec.starts;
  finish_search(fine, s, r, started, "from " + std::to_string(rec.starts) + " complete attempts",
                "no attempt reached eps = 0 (" + std::to_string(rec.starts) + " attempts)", progress);
  return r;
}

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, draws (templates/runtime/search/draws.hpp): what every route of the
// search draws its starts with. Start k of a stream gets its guess from a generator of (seed, k,
// stream), starts run in batches of kSearchBatch on the search's threads and are merged in start
// order, and no rule reads the clock, so a search gives the same answer for a given seed on any
// thread count and any load (only the run's time limit, the safety net, can cut it, and the record
// says so). The draws stop when they look saturated:
//
//   Good-Turing: the chance that the next draw reaches a solution not seen yet is estimated by
//   N1 / n, the share of the n draws so far whose solution no other draw reached (a draw that
//   did not converge reaches none). The draws are saturated when at least kMinDraws were made and
//   that estimate is at most search_saturation (never with search_saturation 0). With 128 draws at
//   least, an extremal whose basin holds 2.3 % of the starts is seen with probability 0.95.
//
// The estimate is per draw, not per converged draw: where few starts converge, each draw is
// unlikely to find anything new, and drawing on is cheap evidence of that; where many distinct
// solutions are each reached once, the estimate stays high and the draws go on to their cap.
// Saturation on few converged draws says that starts find little, not that what they found is the
// best: the pipeline then calls the problem unsettled (search/chooser.hpp's settled) and runs its
// other routes.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The streams of draws: the starts of the problem itself (0), the events-off draws of a problem
// with events (1), the starts of a minimum-time problem's companion (2), the guess whose departure
// the time scale reads (3), the starts of a minimum-fuel problem's minimum-time problem (4).
constexpr std::uint64_t kStartStream = 0;
constexpr std::uint64_t kEventlessStream = 1;
constexpr std::uint64_t kCompanionStream = 2;
constexpr std::uint64_t kScaleStream = 3;
constexpr std::uint64_t kMinimumTimeStream = 4;

// The generator of start k (of a stream): SplitMix64 of (seed, k, stream), so a start's guess does
// not depend on which thread runs it or on how many starts came before.
inline std::mt19937_64 start_generator(unsigned seed, int k, std::uint64_t stream = kStartStream) {
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) + static_cast<std::uint64_t>(k) + 0x9e3779b97f4a7c15ull +
                    stream * 0xd1b54a32d192ed03ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return std::mt19937_64(z ^ (z >> 31));
}

// Runs work(k) for k = 0 .. n-1 on up to `threads` threads, each index once. The first exception
// a work item throws stops the others' next items and is rethrown here.
template <class Work>
void parallel_for(int n, int threads, Work&& work) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto loop = [&] {
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
      pool.emplace_back(loop);
    } catch (const std::system_error&) {
      break;  // no more threads to be had (a process limit): the others share the work
    }
  }
  loop();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

// One line on stderr per stage and at most one every two seconds in between, so a user waiting
// for a long search sees what it is doing and how far it got. Only these lines read the clock.
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

// Starts are drawn and merged in batches of this many, and saturation is not declared before
// this many draws. Without search_starts, the starts of one route stop at kDefaultStartCap.
constexpr int kSearchBatch = 8;
constexpr int kMinDraws = 128;
constexpr int kDefaultStartCap = 1024;
// While no route has reached an extremal, the starts go on past saturation up to this many.
constexpr int kMoreStarts = 4 * kMinDraws;

inline int search_threads(const Settings& s) {
  if (s.threads > 0) return s.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
}

// The most starts a route draws: search_starts where set, else kDefaultStartCap, and never more
// than max_attempts.
inline int start_cap(const Settings& s) {
  return std::min(s.max_attempts, s.search_starts > 0 ? s.search_starts : kDefaultStartCap);
}

// The Good-Turing chance that the next of `draws` draws reaches a solution not in `list` (see the
// top of this file); 1 before any draw.
template <class List>
double unseen_chance(const List& list, int draws) {
  int once = 0;
  for (const auto& e : list) once += e.reached == 1;
  return draws > 0 ? static_cast<double>(once) / draws : 1.0;
}

// Whether draws whose distinct solutions are `list` look saturated (see the top of this file).
template <class List>
bool saturated(const Settings& s, const List& list, int drawn) {
  return s.search_saturation > 0 && drawn >= kMinDraws && unseen_chance(list, drawn) <= s.search_saturation;
}

// Whether the run's time limit (the safety net) has passed, or a user's search_time_s since
// `started`.
inline bool out_of_time(const Settings& s, double started = 0) {
  const double now = wall_seconds();
  return now > s.time_limit_s || (s.search_time_s > 0 && now - started > s.search_time_s);
}

// One start's outcome: x solved (empty x: not run, the time limit passed), its shape and residual.
struct StartRun {
  bool ok = false;
  std::vector<double> x;
  Shape shape;
  double res = INFINITY;
};

// Why a run of draws stopped.
enum class DrawStop { kSaturated, kCap, kTime };

// Draws starts from `drawn` on (start k solved by solve_start(k, rng), the generator of (seed, k,
// stream)) in batches of kSearchBatch on `threads` threads, merged in start order by
// `merge(run, k)`, until the draws are saturated (unless `past_saturation`), `cap` starts were
// drawn or the time runs out (out_of_time since `started`); `drawn` and `converged` count them.
// `list` is what saturation is judged on.
template <class List, class SolveStart, class Merge, class Tick>
DrawStop draw_until_saturated(const Settings& s, int threads, std::uint64_t stream, const List& list, int& drawn,
                              int& converged, bool& cut_by_time, int cap, double started, SolveStart&& solve_start,
                              Merge&& merge, Tick&& tick, bool past_saturation = false) {
  for (;;) {
    if (!past_saturation && saturated(s, list, drawn)) return DrawStop::kSaturated;
    if (drawn >= cap) return DrawStop::kCap;
    if (out_of_time(s, started)) return DrawStop::kTime;
    const int from = drawn, to = std::min(cap, from + kSearchBatch);
    std::vector<StartRun> runs(static_cast<std::size_t>(to - from));
    parallel_for(to - from, threads, [&](int i) {
      if (out_of_time(s, started)) return;
      std::mt19937_64 rng = start_generator(s.seed, from + i, stream);
      runs[i] = solve_start(from + i, rng);
      tick(from + i + 1);
    });
    for (int i = 0; i < to - from; ++i) {
      if (runs[i].x.empty()) {
        cut_by_time = true;
        continue;
      }
      ++drawn;
      if (!runs[i].ok) continue;
      ++converged;
      merge(runs[i], from + i);
    }
  }
}

}  // namespace

}  // namespace helios_rt

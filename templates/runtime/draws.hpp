// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, draws (templates/runtime/draws.hpp): what every part of the global
// search draws its starts with. Start k of a stream gets its guess from a generator of (seed, k,
// stream), starts run in batches on the search's threads and are merged in start order, so a
// search is deterministic for a given seed whatever the thread count (unless its time budget cuts
// it, which the record says). Converged starts are told apart (same_extremal), and the draws stop
// when they look saturated:
//
//   Good-Turing: the chance that the next draw reaches a solution not seen yet is estimated by
//   N1 / n, the share of the n draws so far whose solution no other draw reached (a draw that
//   did not converge reaches none). The draws are saturated when at least kMinDraws were made, at
//   least kMinConverged of them converged (where no other source supplies extremals), and that
//   estimate is at most search_saturation (never with search_saturation 0). With 128 draws at
//   least, an extremal whose basin holds 2.3 % of the starts is seen with probability 0.95; where
//   few starts converge (a minimum-time problem's small basins), the converged ones are what
//   the estimate rests on, so there must be enough of them.
//
// The estimate is per draw, not per converged draw: where few starts converge, each draw is
// unlikely to find anything new, and drawing on is cheap evidence of that; where many distinct
// solutions are each reached once, the estimate stays high and the draws go on until the budget.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The streams of draws: the starts of the problem itself (0), the events-off draws of a problem
// with events (1), the starts of a minimum-time problem's companion (2).
constexpr std::uint64_t kStartStream = 0;
constexpr std::uint64_t kEventlessStream = 1;
constexpr std::uint64_t kCompanionStream = 2;

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

// Starts are drawn and merged in batches of this many, and saturation is not declared before
// this many draws.
constexpr int kSearchBatch = 8;
constexpr int kMinDraws = 128;
constexpr int kMinConverged = 16;

inline int search_threads(const Settings& s) {
  if (s.threads > 0) return s.threads;
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
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
bool saturated(const Settings& s, const List& list, int drawn, int converged, int min_converged) {
  return s.search_saturation > 0 && drawn >= kMinDraws && converged >= min_converged &&
         unseen_chance(list, drawn) <= s.search_saturation;
}

// One start's outcome: x solved (empty x: not run, the time ran out), its shape and residual.
struct StartRun {
  bool ok = false;
  std::vector<double> x;
  Shape shape;
  double res = INFINITY;
};

// Draws starts from `drawn` on (start k solved by solve_start(k, rng), the generator of (seed, k,
// stream)) in batches of kSearchBatch on `threads` threads, merged in start order into `list`, until
// the draws are saturated (with `min_converged` converged ones at least), `cap` starts were drawn
// (0: no cap) or `deadline` (wall seconds) passes; `drawn` and `converged` count them. Returns the
// Good-Turing chance of a new solution at the stop.
template <class List, class SolveStart, class Tick>
double draw_until_saturated(const Settings& s, int threads, std::uint64_t stream, List& list, int& drawn,
                            int& converged, bool& cut_by_time, int cap, double deadline, int min_converged,
                            SolveStart&& solve_start, Tick&& tick) {
  while (!saturated(s, list, drawn, converged, min_converged) && (cap <= 0 || drawn < cap) && wall_seconds() < deadline) {
    const int from = drawn, to = cap > 0 ? std::min(cap, from + kSearchBatch) : from + kSearchBatch;
    std::vector<StartRun> runs(static_cast<std::size_t>(to - from));
    parallel_for(to - from, threads, [&](int i) {
      if (wall_seconds() >= deadline) return;
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
      typename List::value_type entry;
      entry.max_residual = runs[i].res;
      merge_extremal(list, runs[i].x, runs[i].shape, from + i, std::move(entry));
    }
  }
  return unseen_chance(list, drawn);
}

}  // namespace

}  // namespace helios_rt

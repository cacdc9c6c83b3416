// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, routes (templates/runtime/search/route.hpp): what a route of the search
// is and what every route shares. A route is one way to reach extremals (random starts, the
// revolution families, a minimum-time problem's minimum-fuel companion, the continuation on the
// thrust, the route from the minimum time, the complete attempts of a problem with events): it
// says whether it applies now (after the routes before it ran) and why not, runs, and puts what it
// reaches into the pool (pool.hpp), never anywhere else. The pipeline (pipeline.hpp) runs the
// routes registered for a problem in order; the chooser (chooser.hpp) decides from the pool.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

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

// A number in a progress line or the record, with `digits` significant digits.
inline std::string number_text(double v, int digits = 6) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// A time in days in the unit a reader of the problem expects: hours below three days, else days.
inline std::string days_text(double days, int digits = 9) {
  return std::fabs(days) < 3 ? number_text(days * 24, digits) + " h" : number_text(days, digits) + " days";
}

// An objective in named units for the progress lines and the record.
inline std::string objective_text(double objective) {
  const double v = objective_in_named_unit(objective);
  if (objective_is_propellant()) return number_text(v) + (cost_is_delta_v() ? " m/s of delta-v" : " kg of propellant");
  if (kProblem.objective == Objective::final_radius) return "a final radius of " + number_text(v, 9) + " km";
  if (kProblem.objective == Objective::final_energy) return "a final energy of " + number_text(v, 9) + " km^2/s^2";
  return days_text(v);
}

// The looser integration a path to a start runs on (a random start's first solve, a family's turn
// at eps_start, the time route's continuations at eps_start): its steps stop at kLooseAccept, well
// above what that integration resolves, and where the path arrives the solution is solved again at
// the search's tolerance. 1e-6 against the search's 1e-10: every objective of S01-S14 the same
// (bit for bit where only the routes' paths went loose), 8-30 % less CPU.
constexpr double kLooseTolerance = 1e-6;
constexpr double kLooseAccept = 1e-5;
inline Settings loose_settings(const Settings& s) {
  Settings loose = s;
  loose.rtol = std::max(loose.rtol, kLooseTolerance);
  loose.atol = std::max(loose.atol, kLooseTolerance);
  loose.accept_residual = std::max(loose.accept_residual, kLooseAccept);
  return loose;
}

// A solution x at eps = 0 of the problem the settings s pose (its window edges held where s holds
// them) as the pool takes it: its residuals and shape evaluated there, how it was reached, the
// path's steps.
inline Extremal solved_extremal(const Settings& s, const std::vector<double>& x, std::string method,
                                std::vector<ContinuationStep> steps) {
  Extremal entry;
  entry.x = x;
  entry.F.assign(x.size(), 0.0);
  Propagator prop(s);
  shooting_function(x.data(), 0.0, prop, entry.F.data());
  for (const double f : entry.F) entry.max_residual = std::max(entry.max_residual, std::fabs(f));
  entry.shape = shape_of(s, x, 0.0);
  entry.method = std::move(method);
  entry.continuation = std::move(steps);
  return entry;
}

// The extremal a path arrived at (a.x solved at eps = 0) as the pool takes it: its residuals and
// shape, how it was reached, and the path's steps.
inline Extremal arrival_extremal(const Settings& s, const PathArrival& a, std::string method) {
  Extremal entry;
  entry.x = a.x;
  entry.F = a.F;
  entry.max_residual = a.max_residual;
  entry.info = a.info;
  entry.shape = shape_of(s, a.x, 0.0);
  entry.method = std::move(method);
  entry.continuation = a.steps;
  return entry;
}

// What every route of one search sees: the settings (the search's, `coarse`, and the integrator's
// own, `fine`), the problem's guess and admissibility, the pool, the program's knobs, the progress
// lines, the threads, and the evaluations counted so far.
struct SearchContext {
  SearchContext(const Settings& fine_settings, const Settings& coarse_settings, const Guess& g, const Admissible& a,
                Pool& p, ProgramKnobs& k, Progress& pr, bool inner)
      : fine(fine_settings),
        coarse(coarse_settings),
        guess(g),
        admissible(a),
        pool(p),
        knobs(k),
        progress(pr),
        threads(search_threads(coarse_settings)),
        started(wall_seconds()),
        nested(inner) {}

  const Settings& fine;
  const Settings& coarse;
  const Guess& guess;
  const Admissible& admissible;
  Pool& pool;
  ProgramKnobs& knobs;
  Progress& progress;
  const int threads;
  const double started;
  // A search inside a route (the thrust continuation's search at a raised thrust): the routes
  // that would call it again do not run.
  const bool nested;

  // The search at a raised thrust that measured the problem's time scale (scale.hpp), kept for the
  // thrust route to continue down from; status kNotSolved where none was made.
  Result scale_search;

  SearchRecord& rec() { return pool.record(); }
  // The minimum time the time scale estimates (normalized), NaN where it was not measured.
  double estimated_time() const { return rec().time_scale.estimate_days / kProblem.time_unit_days; }
  // Whether the time scale says the transfer winds many revolutions at the problem's own thrust,
  // where starts there rarely converge and cost the most: the thrust route reaches it instead.
  bool many_revolutions_expected() const { return rec().time_scale.revolutions > kFewRevolutions; }
  const SearchRecord& rec() const { return pool.record(); }
  bool out_of_time() const { return helios_rt::out_of_time(coarse, started); }
  void count(int e) {
    const std::lock_guard<std::mutex> lock(mutex_);
    evaluations_ += e;
  }
  int evaluations() const { return evaluations_; }

 private:
  std::mutex mutex_;
  int evaluations_ = 0;
};

class Route {
 public:
  virtual ~Route() = default;
  virtual const char* name() const = 0;
  // Why the route does not run now ("" when it does), read after the routes before it ran.
  virtual std::string skip(const SearchContext& c) const = 0;
  // Runs the route: what it did, in a line for the record.
  virtual std::string run(SearchContext& c) = 0;
};

// The routes that look for transfers within the window, in order (pipeline.hpp).
inline std::vector<std::unique_ptr<Route>> transfer_routes();

// The eps_start extremal `which` of the starts continued to eps = 0: true with `e` filled when it
// arrived. Each eps step starts hybrd's trust region next to the last solution and must keep the
// branch's revolutions: hybrd can land on another extremal's branch (seen on S13: from the
// 3-revolution branch to the 4-revolution one), and the path would then report that extremal as
// this one's continuation.
inline bool continue_start_extremal(SearchContext& c, int which, Extremal& e) {
  const StartExtremal& from = c.rec().start_extremals[which];
  Shooter shooter(c.coarse, kContinuationStart);
  Result path;
  std::vector<double> x = from.x;
  double res = 0, revolutions = from.shape.revolutions;
  const auto on_branch = [&](const std::vector<double>& to, double eps) {
    const double now = shape_of(c.coarse, to, eps).revolutions;
    if (std::fabs(now - revolutions) > 0.25) return false;
    revolutions = now;
    char line[96];
    std::snprintf(line, sizeof line, "continuing the extremal at eps_start %d: eps = %.3g", which, eps);
    c.progress.tick(line);
    return true;
  };
  const bool ok = homotopy_to_zero(c.coarse, shooter, x, path, c.admissible, res, on_branch);
  c.count(shooter.evaluations);
  if (!ok) return false;
  e.x = x;
  e.x_start = path.x_start;
  e.F = shooter.last_F;
  e.max_residual = res;
  e.info = path.info;
  e.homotopy = path.homotopy;
  e.shape = shape_of(c.coarse, x, 0.0);  // its cost is the objective
  e.method = "single shooting, eps continuation from the extremal at eps_start " + std::to_string(which) +
             (from.origin.empty() ? " (start " + std::to_string(from.first_start) + ")" : " (" + from.origin + ")");
  return true;
}

// Continues the given eps_start extremals to eps = 0 in parallel, entered into the pool by
// `route` in the order given.
inline void continue_start_extremals(SearchContext& c, const std::string& route, const std::vector<int>& which) {
  std::vector<Extremal> arrived(which.size());
  std::vector<char> ok(which.size(), 0);
  parallel_for(static_cast<int>(which.size()), c.threads, [&](int i) {
    if (!c.out_of_time()) ok[i] = continue_start_extremal(c, which[i], arrived[i]);
  });
  SearchRecord& rec = c.rec();
  for (std::size_t i = 0; i < which.size(); ++i) {
    StartExtremal& from = rec.start_extremals[which[i]];
    from.continued = true;
    ++rec.continued;
    if (!ok[i]) continue;
    const int k = c.pool.enter(route, std::move(arrived[i]), from.first_start);
    Extremal& e = rec.extremals[k];
    e.reached += from.reached - 1;  // every start that reached `from` led here
    e.from.push_back(which[i]);
    from.arrived = k;
  }
  const double best = best_objective(rec);
  c.progress.stage(std::to_string(rec.continued) + " continued to eps = 0: " + std::to_string(rec.extremals.size()) +
                   " distinct extremals" + (std::isfinite(best) ? ", best " + objective_text(best) : ""));
}

// The eps_start extremal k continued to eps = 0 where its cost, a lower bound of its objective
// (the starts' continue_promising), is below the best objective; else marked pruned and `how`
// says so. Returns the extremal at eps = 0 reached (-1: none).
inline int continue_if_promising(SearchContext& c, const std::string& route, int k, std::string& how) {
  StartExtremal& e = c.rec().start_extremals[k];
  if (!c.coarse.search_continue_all && e.shape.cost >= best_objective(c.rec())) {
    e.pruned = true;
    how += ", not continued: its cost at eps_start, a lower bound of its objective, is not below the best";
    return -1;
  }
  continue_start_extremals(c, route, {k});
  how += ", continued";
  return c.rec().start_extremals[k].arrived;
}

// The indices of the `n` lowest-cost entries of `list` (StartExtremal or Extremal).
template <class List>
std::vector<int> lowest_cost(const List& list, std::size_t n) {
  std::vector<int> order(list.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return list[a].shape.cost < list[b].shape.cost; });
  if (order.size() > n) order.resize(n);
  return order;
}

}  // namespace

}  // namespace helios_rt

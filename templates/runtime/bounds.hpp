// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, bounds (templates/runtime/bounds.hpp): bounds psi <= 0: passes over the
// active set, warm from the last pass.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The Newton homotopy F(z) - sigma F(x) = 0 at eps, followed from sigma = 1 (solved by x) to 0:
// it moves the rows that changed with the active set from their old form to their new one. True
// when sigma = 0 was reached (x is then the solution at eps).
inline bool shift_rows(const Settings& s, std::vector<double>& x, double eps, Result& r) {
  std::vector<double> start(kProblem.num_vars);
  {
    Propagator prop(s);
    try {
      shooting_function(x.data(), eps, prop, start.data());
    } catch (const numerical_error&) {
      return false;
    }
  }
  double sigma = 1;
  const Function shifted = [&](const double* z, double e, Propagator& p, double* F, double* J) {
    shooting_function_and_jacobian(z, e, p, F, J);
    for (int i = 0; i < kProblem.num_vars; ++i) F[i] -= sigma * start[i];
  };
  Shooter shooter(s, shifted, kContinuationStart);
  const auto anything = [](const double*) { return true; };
  const bool moved = continue_to_zero(s, 1.0, [&](double value) {
    sigma = value;
    std::vector<double> trial = x;
    int info = 0;
    double res = 0;
    const bool ok = homotopy_step(shooter, trial, eps, s.accept_residual, r, anything, info, res);
    if (ok) x = trial;
    return ok;
  });
  r.evaluations += shooter.evaluations;
  return moved;
}

// A pass over a new active set, warm from the last pass's result `warm`, by the first of these
// routes whose solution `pushes` (its active bounds' multipliers are not negative: a route that
// ends on the other side has followed the homotopy to another branch):
//   from its solution x (eps = 0), smoothed (eps raised by decades to eps_start as far as each
//     step, a Newton solve from the last, converges), the rows shifted there (shift_rows), and
//     eps continued back to 0;
//   when x could be smoothed, from x itself, the rows shifted at eps = 0;
//   from its solution at eps_start (x_start), where the problem is smooth and a bound can move
//     far (S10's periapsis radius by a factor of ten), shifted there and continued to 0.
// True when eps = 0 was reached (warm.x is then the solution).
template <class Admissible, class Pushes>
bool bound_homotopy(const Settings& s, Result& warm, Admissible&& admissible, Pushes&& pushes) {
  const auto to_zero = [&](std::vector<double>& x, double eps) {
    double res = 0;
    int info = 0;
    Shooter single(s);
    Settings down = s;
    down.eps_start = eps;
    const bool reached = eps == 0 ? homotopy_step(single, x, 0.0, s.final_residual, warm, admissible, info, res)
                                  : homotopy_to_zero(down, single, x, warm, admissible, res);
    warm.evaluations += single.evaluations;
    if (reached) {
      warm.max_residual = res;
      warm.F = single.last_F;
      warm.x = x;
    }
    return reached && pushes(x.data());
  };
  const std::vector<double> last_start = warm.x_start, last = warm.x;
  std::vector<double> x = last;
  double eps = 0;
  {
    Shooter plain(s, kContinuationStart);
    const auto anything = [](const double*) { return true; };
    for (double next = 1e-4; next <= s.eps_start * (1 + 1e-12); next *= 10) {
      std::vector<double> trial = x;
      int info = 0;
      double res = 0;
      if (!homotopy_step(plain, trial, next, s.accept_residual, warm, anything, info, res)) break;
      x = trial;
      eps = next;
    }
    warm.evaluations += plain.evaluations;
  }
  if (shift_rows(s, x, eps, warm) && to_zero(x, eps)) {
    if (eps != s.eps_start) warm.x_start = last_start;  // to_zero set it at eps
    return true;
  }
  if (eps > 0) {
    x = last;
    if (shift_rows(s, x, 0.0, warm) && to_zero(x, 0.0)) {
      warm.x_start = last_start;
      return true;
    }
  }
  if (last_start.empty()) return false;
  x = last_start;
  return shift_rows(s, x, s.eps_start, warm) && to_zero(x, s.eps_start);
}

// What the passes over the bounds' active set did, summed over every pass tried.
struct PassLog {
  int attempts = 0, iterations = 0, evaluations = 0;
  std::vector<std::string> methods;  // each pass's method
  std::vector<LegStep> legs;
  std::vector<HomotopyStep> homotopy;
  std::vector<ContinuationStep> continuation;
  std::string from;  // which of pass 1's extremals the passes start from ("" for its solution)
  void add(const Result& r, int pass) {
    attempts += r.attempts;
    iterations += r.iterations;
    evaluations += r.evaluations;
    methods.push_back(from + "pass " + std::to_string(pass) + ": " + r.method);
    legs.insert(legs.end(), r.legs.begin(), r.legs.end());
    homotopy.insert(homotopy.end(), r.homotopy.begin(), r.homotopy.end());
    continuation.insert(continuation.end(), r.continuation.begin(), r.continuation.end());
  }
};

// The values psi at x (eps = 0) of the `count` bounds.
inline std::vector<double> bound_values(const Settings& s, const std::vector<double>& x, std::size_t count) {
  Propagator prop(s);
  std::vector<double> F(kProblem.num_vars);
  shooting_function(x.data(), 0.0, prop, F.data());
  std::vector<double> values = prop.bound_values;
  values.resize(count, 0.0);
  return values;
}

// The passes after pass 1, from its converged solution r (every bound inactive): while r violates
// an inactive bound (psi > 0) or has a negative multiplier on an active one, the next pass makes
// the violated bounds active, or else drops the active bound with the most negative multiplier,
// and solves again: warm from the last solution (bound_homotopy), else (when `cold` allows) from
// cold. Never the same set twice. Every pass solves with its active set in s.active_bounds. True
// when a consistent set was reached (r then holds its solution, s.active_bounds the set); `steps`
// lists the changes ("+name", "-name").
template <class Solve, class Admissible>
bool active_set_passes(Settings& s, const std::vector<Bound>& bounds, Result& r, bool cold, Solve&& solve,
                       Admissible&& admissible, PassLog& log, std::vector<std::string>& steps) {
  std::vector<char>& active = s.active_bounds;
  active.assign(bounds.size(), 0);
  std::vector<std::vector<char>> tried{active};
  for (int pass = 2;; ++pass) {
    const std::vector<double> values = bound_values(s, r.x, bounds.size());
    std::vector<char> next = active;
    int drop = -1;
    for (std::size_t k = 0; k < bounds.size(); ++k) {
      if (!active[k] && values[k] > 0) next[k] = 1;
      if (active[k] && r.x[bounds[k].multiplier] < 0 &&
          (drop < 0 || r.x[bounds[k].multiplier] < r.x[bounds[drop].multiplier]))
        drop = static_cast<int>(k);
    }
    if (next == active && drop >= 0) next[drop] = 0;
    if (next == active) return true;  // consistent: the inactive bounds hold, the active ones push
    if (std::find(tried.begin(), tried.end(), next) != tried.end()) {
      r.status = Status::kNotConverged;
      r.detail = "the active set of the bounds cycles";
      return false;
    }
    tried.push_back(next);
    for (std::size_t k = 0; k < bounds.size(); ++k)
      if (next[k] != active[k]) steps.push_back((next[k] ? "+" : "-") + bounds[k].name);
    active = next;
    Result warm;
    warm.x = r.x;
    warm.x_start = r.x_start;
    warm.method = "warm from pass " + std::to_string(pass - 1) + " by a homotopy on the bounds' rows";
    const auto pushes = [&](const double* x) {
      for (std::size_t k = 0; k < bounds.size(); ++k)
        if (active[k] && x[bounds[k].multiplier] < 0) return false;
      return true;
    };
    if (bound_homotopy(s, warm, admissible, pushes)) {
      warm.status = Status::kConverged;
      warm.eps = 0;
      warm.attempts = 1;
      r = warm;
    } else if (cold) {
      log.evaluations += warm.evaluations;
      r = solve(s);
    } else {
      warm.method += " (did not converge)";
      log.add(warm, pass);
      r.status = Status::kNotConverged;
      r.detail = "the warm homotopy on the bounds' rows did not converge";
      return false;
    }
    log.add(r, pass);
    r.passes = pass;
    if (r.status != Status::kConverged) return false;
  }
}

// The starts of the passes over the bounds: pass 1's distinct extremals (r.search's), its
// solution first, then the others by objective. A solve without a search record (an llm-written
// SOLVE module) has its solution as the only one.
inline std::vector<std::size_t> pass_one_starts(const Settings& s, Result& r) {
  std::vector<Extremal>& extremals = r.search.extremals;
  if (extremals.empty()) {
    Extremal own;
    own.x = r.x;
    own.x_start = r.x_start;
    own.shape.cost = objective_of(s, r.x);
    own.reached = 1;
    own.method = r.method;
    extremals.push_back(own);
    r.search.returned = 0;
  }
  std::vector<std::size_t> order(extremals.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const bool a_solution = static_cast<int>(a) == r.search.returned,
               b_solution = static_cast<int>(b) == r.search.returned;
    return a_solution != b_solution ? a_solution : extremals[a].shape.cost < extremals[b].shape.cost;
  });
  return order;
}

// What every pass tried did, into the result r of the last: the counts and steps summed, the
// passes' methods with the active-set changes that led to r (`steps`), and each bound's report
// (`first`: its values after pass 1; the active set is s.active_bounds).
inline void record_passes(const Settings& s, const std::vector<Bound>& bounds, const std::vector<double>& first,
                          const PassLog& log, const std::vector<std::string>& steps, Result& r) {
  r.attempts = log.attempts;
  r.iterations = log.iterations;
  r.evaluations = log.evaluations;
  r.legs = log.legs;
  r.homotopy = log.homotopy;
  r.continuation = log.continuation;
  if (r.passes > 1) {
    std::string changes;
    for (const auto& c : steps) changes += (changes.empty() ? "" : " ") + c;
    std::string each;
    for (const auto& m : log.methods) each += (each.empty() ? "" : "; ") + m;
    r.method = std::to_string(r.passes) + " passes over the bounds' active set (" + changes + "): " + each;
  }
  const bool converged = r.status == Status::kConverged;
  const std::vector<double> last = converged ? bound_values(s, r.x, bounds.size()) : first;
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    const bool active = s.active_bounds[k] != 0;
    const double nu = converged ? r.x[bounds[k].multiplier] : 0.0;
    r.bounds.push_back({bounds[k].name, bounds[k].meaning, first[k], active, last[k], nu});
  }
}

}  // namespace

// Bounds psi <= 0 by passes over the active set: pass 1 solves with every bound inactive, then
// active_set_passes follows from its solution, warm. Pass 1's search keeps its distinct extremals,
// and the passes start from each of them (best first; one no better than a result already found
// cannot lead to a better one), since the best extremal without the bounds need not lead to the
// best one with them. The best consistent result is the solution. Only when no warm start
// gets there do the passes run again from pass 1's solution, now with a cold solve where the warm
// one fails.
Result two_pass_solve(const Settings& given, const std::vector<Bound>& bounds, const Solve& solve,
                      const Admissible& admissible) {
  Settings s = given;  // its active_bounds: the active set each pass solves with
  s.active_bounds.assign(bounds.size(), 0);
  PassLog log;
  std::vector<std::string> steps;  // the active-set changes that led to the solution
  Result r = solve(s);
  log.add(r, 1);
  std::vector<double> first(bounds.size(), 0.0);
  bool consistent = false;
  std::vector<char> final_set = s.active_bounds;
  if (r.status == Status::kConverged) {
    s.window_edges = r.window_edges;
    first = bound_values(s, r.x, bounds.size());
    std::vector<Extremal>& extremals = r.search.extremals;
    const std::vector<std::size_t> order = pass_one_starts(s, r);
    // Each start's result with the bounds (its active set and changes), by extremal; the chooser
    // decides which is returned.
    std::map<int, std::tuple<Result, std::vector<char>, std::vector<std::string>>> reached;
    double lowest = INFINITY;
    for (const std::size_t i : order) {
      Extremal& o = extremals[i];
      if (out_of_time(s) || o.shape.cost >= lowest) continue;
      o.bounded_tried = true;
      Result from = r;
      from.x = o.x;
      from.x_start = o.x_start;
      from.window_edges = s.window_edges = o.window_edges;  // an extremal at a window's edge stays there
      from.edge_transversality = o.edge_transversality;
      log.from = static_cast<int>(i) == r.search.returned ? "" : "from extremal " + std::to_string(i) + ", ";
      std::vector<std::string> changes;
      if (!active_set_passes(s, bounds, from, false, solve, admissible, log, changes)) continue;
      o.bounded_objective = objective_of(s, from.x);
      o.bounded_passes = from.passes;
      lowest = std::min(lowest, o.bounded_objective);
      reached.emplace(static_cast<int>(i), std::make_tuple(from, s.active_bounds, changes));
    }
    const Choice choice = choose_with_bounds(r.search);
    Result best = r;
    if (choice.returned >= 0) {
      std::tie(best, final_set, steps) = reached.at(choice.returned);
      consistent = true;
    }
    if (!consistent && !out_of_time(s)) {
      log.from = "cold: ";
      best = r;
      s.window_edges = r.window_edges;
      steps.clear();
      consistent = active_set_passes(s, bounds, best, true, solve, admissible, log, steps);
      final_set = s.active_bounds;
    }
    SearchRecord record = std::move(r.search);
    r = best;
    r.search = std::move(record);
    if (choice.returned >= 0) {
      r.search.returned = choice.returned;
      r.search.reason = choice.reason;
    }
    if (!consistent) {
      r.status = Status::kNotConverged;
      if (r.detail.empty()) r.detail = "no pass over the bounds' active set converged";
    }
  }
  s.active_bounds = final_set;
  s.window_edges = r.window_edges;
  record_passes(s, bounds, first, log, steps, r);
  return r;
}

}  // namespace helios_rt

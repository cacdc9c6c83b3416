// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, extremals (templates/runtime/extremals.hpp): what the searches of
// search.hpp share about the distinct extremals they reach at eps = 0: which may be returned
// (polished, in the final time's window, on the stated side of every target), the search's
// settings, their polish at the integrator's own tolerance, the choice of the best and why, and
// what a search that returns none says.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// Whether x's free final time (if any) lies in its window: tf_frac in [0, 1]. Nothing in the
// shooting system keeps it there, so an extremal can end outside (a minimum time below the
// window's start); it stays in the record and is never returned.
inline bool within_window(const std::vector<double>& x) {
  static const int at = free_final_time().variable;
  return at < 0 || (x[at] >= -1e-9 && x[at] <= 1 + 1e-9);
}

// Whether an extremal may be returned: polished, in the final time's window, and on the stated
// side of every target (not on a mirror the rows also admit: Shape::off_side).
inline bool returnable(const Extremal& e) {
  return e.polished && within_window(e.x) && e.shape.off_side.empty();
}

// The returnable extremal at eps = 0 with the lowest objective, the first reached among equals
// (-1: none).
inline int best_index(const SearchRecord& rec) {
  int best = -1;
  for (std::size_t i = 0; i < rec.extremals.size(); ++i)
    if (returnable(rec.extremals[i]) && (best < 0 || rec.extremals[i].shape.cost < rec.extremals[best].shape.cost))
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
  r.status = Status::kConverged;
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
  const char* format = objective_is_propellant()                     ? "%.6g kg of propellant"
                       : kProblem.objective == Objective::final_radius ? "a final radius of %.9g km"
                       : kProblem.objective == Objective::final_energy ? "a final energy of %.9g km^2/s^2"
                                                                       : "%.6g days";
  std::snprintf(buf, sizeof buf, format, objective_in_named_unit(objective));
  return buf;
}

inline bool search_time_left(const Settings& s, double started) {
  return wall_seconds() <= s.time_limit_s && (s.search_time_s <= 0 || wall_seconds() - started <= s.search_time_s);
}

// The best objective among the distinct extremals at eps = 0 (INFINITY: none yet).
inline double best_objective(const SearchRecord& rec) {
  const int best = best_index(rec);
  return best < 0 ? INFINITY : rec.extremals[best].shape.cost;
}

// Says on stderr when the search stopped before it was saturated (rec.stopped: why), with the
// estimate and what would let it go on.
inline void say_if_not_saturated(const SearchRecord& rec, const Settings& s, Progress& progress) {
  if (rec.saturated) return;
  const bool capped = rec.stopped.rfind("the cap", 0) == 0;
  const int converged = rec.eventless_draws > 0 || rec.converged_start == 0 ? rec.converged_final : rec.converged_start;
  char line[400];
  std::snprintf(line, sizeof line,
                "not saturated: %d of %d starts converged, and the chance that another finds a new extremal is %.3g "
                "(saturated: at most %.3g); stopped by %s. %s; %s lets the search go on.",
                converged, rec.starts, rec.unseen, s.search_saturation, rec.stopped.c_str(),
                best_index(rec) >= 0 ? "The best extremal found is returned"
                : rec.extremals.empty() ? "Nothing was found"
                                        : "None of the extremals found may be returned",
                capped ? "a larger search_starts (or max_attempts)" : "a larger search_time_s");
  progress.stage(line);
}

// After a search at `coarse` (search_settings(fine)): its extremals polished at `fine`, the best
// into r, else why there is none (`what_failed`, or the time).
inline void finish_search(const Settings& fine, const Settings& coarse, Result& r, double started,
                          const std::string& how, const std::string& what_failed, Progress& progress) {
  SearchRecord& rec = r.search;
  polish_extremals(fine, coarse, rec);
  rec.seconds = wall_seconds() - started;
  choose_best(rec, how);
  r.status = Status::kNotConverged;  // the search ran: converged below, or timed out, or not
  if (rec.returned >= 0) {
    take_extremal(r);
    progress.stage("returned extremal " + std::to_string(rec.returned) + ": " + rec.reason);
  } else if (wall_seconds() > fine.time_limit_s) {
    r.status = Status::kTimeout;
    r.detail = "time limit reached before convergence";
  } else if (const auto mirrored = std::find_if(rec.extremals.begin(), rec.extremals.end(),
                                                [](const Extremal& e) { return !e.shape.off_side.empty(); });
             mirrored != rec.extremals.end() &&
             std::all_of(rec.extremals.begin(), rec.extremals.end(),
                         [](const Extremal& e) { return !e.polished || !e.shape.off_side.empty(); })) {
    r.detail = "every extremal the search reached ends on the mirror of a target, which the rows also admit (" +
               mirrored->shape.off_side + " fails)";
  } else if (!rec.extremals.empty() && std::none_of(rec.extremals.begin(), rec.extremals.end(),
                                                    [](const Extremal& e) { return within_window(e.x); })) {
    const auto shortest = std::min_element(rec.extremals.begin(), rec.extremals.end(),
                                           [](const Extremal& a, const Extremal& b) { return a.shape.cost < b.shape.cost; });
    r.detail = "every extremal the search reached (" + std::to_string(rec.extremals.size()) +
               ") ends outside the final time's window; the shortest takes " + objective_text(shortest->shape.cost) +
               (shortest->x[free_final_time().variable] < 0
                    ? ", before the window opens: the minimum time is below the window (widen it, or minimize the "
                      "fuel at a fixed time of flight in it)"
                    : "");
  } else if (!rec.extremals.empty()) {
    r.detail = "none of the " + std::to_string(rec.extremals.size()) +
               " extremals the search reached at eps = 0 converged again at the integrator's tolerance";
  } else {
    r.detail = what_failed;
  }
}

}  // namespace

}  // namespace helios_rt

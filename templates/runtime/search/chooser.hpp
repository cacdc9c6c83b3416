// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the chooser (templates/runtime/search/chooser.hpp): the one place where
// the search's answer is decided, from its record alone. Which extremals may be returned (polished
// at the integrator's tolerance, in the final time's window, on the stated side of every target),
// the best of them (with bounds: the best the passes over the active set reached from them), why,
// whether the search settled the problem, and the verdict: converged, infeasible (no transfer
// within the stated bound: the minimum time found exceeds it, from a settled search), timed out
// (the safety net), or not converged with what was found instead. It reads only records
// (runtime_records.hpp), so tests/unit/chooser_test.cpp checks it on recorded pools.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// A transfer of at most this many revolutions is "few": the search's starts are reliable there.
constexpr double kFewRevolutions = 2.5;
// Starts that saturate settle a problem only where at least this many of them converged.
constexpr int kMinConverged = 16;

// Whether an extremal may be returned: polished, in the final time's window, and on the stated
// side of every target (not on a mirror the rows also admit: Shape::off_side).
inline bool returnable(const Extremal& e) {
  return e.polished && !e.outside_window && e.shape.off_side.empty();
}

// The returnable extremal with the lowest objective, the first reached among equals, if it costs no
// more than `bound` (-1: none).
inline int best_index(const std::vector<Extremal>& extremals, double bound = INFINITY) {
  int best = -1;
  for (std::size_t i = 0; i < extremals.size(); ++i)
    if (returnable(extremals[i]) && (best < 0 || extremals[i].shape.cost < extremals[best].shape.cost))
      best = static_cast<int>(i);
  return best >= 0 && extremals[best].shape.cost <= bound ? best : -1;
}
// The record's: never one that costs more than a feasible transfer known to the search, the
// minimum time completed by a coast (rec.coast_bound): it cannot be the optimum.
inline int best_index(const SearchRecord& rec) {
  return best_index(rec.extremals, std::isnan(rec.coast_bound) ? INFINITY : rec.coast_bound * (1 + 1e-9));
}

// The best objective among the returnable extremals (INFINITY: none yet).
inline double best_objective(const SearchRecord& rec) {
  const int best = best_index(rec);
  return best < 0 ? INFINITY : rec.extremals[best].shape.cost;
}

// Whether the search settles the problem by itself: its starts saturated on kMinConverged
// converged ones at least, or it reached a returnable extremal of few revolutions. Starts that
// saturate on fewer say only that random starts find little, and a best extremal of many
// revolutions that the starts are where they fail (a basin shrinks with the revolutions): an
// unsettled problem is left to the other routes (the thrust continuation, the time route).
inline bool settled(const SearchRecord& rec) {
  if (rec.saturated && rec.converged_start >= kMinConverged && !rec.extremals.empty()) return true;
  const int best = best_index(rec);
  return best >= 0 && rec.extremals[best].shape.revolutions <= kFewRevolutions;
}

// The returned extremal and why: the best returnable one.
struct Choice {
  int returned = -1;
  std::string reason;
};
inline Choice choose(const SearchRecord& rec, const std::string& how) {
  Choice c;
  c.returned = best_index(rec);
  if (c.returned < 0) return c;
  const std::size_t n = rec.extremals.size();
  c.reason = n == 1
                 ? "the only extremal reached at eps = 0 " + how
                 : "the lowest objective of the " + std::to_string(n) + " distinct extremals reached at eps = 0 " + how;
  return c;
}

// With bounds (bounds.hpp): the extremal whose passes over the active set reached the lowest
// objective (-1: none reached one).
inline Choice choose_with_bounds(const SearchRecord& rec) {
  Choice c;
  for (std::size_t i = 0; i < rec.extremals.size(); ++i) {
    const Extremal& e = rec.extremals[i];
    if (e.bounded_tried && std::isfinite(e.bounded_objective) &&
        (c.returned < 0 || e.bounded_objective < rec.extremals[c.returned].bounded_objective))
      c.returned = static_cast<int>(i);
  }
  if (c.returned >= 0)
    c.reason = "the lowest objective with the bounds reached from the " + std::to_string(rec.extremals.size()) +
               " distinct extremals of pass 1";
  return c;
}

// Whether the record proves the problem infeasible: no returnable extremal, and the minimum time
// the search found (a settled search for it) exceeds the stated bound.
inline bool proven_infeasible(const SearchRecord& rec) {
  return best_index(rec) < 0 && rec.minimum_time_settled && std::isfinite(rec.minimum_time_days) &&
         std::isfinite(rec.bound_days) && helios::solve::beyond_bound(rec.minimum_time_days, rec.bound_days);
}

// How a search ended: its status and, where it returns nothing, why.
struct Verdict {
  Status status = Status::kNotConverged;
  std::string detail;
};

// The verdict on a record (after the choice): `days_text` writes a time in the problem's units,
// `objective_text` an objective; `what_failed` says what the routes tried where nothing was found.
template <class DaysText, class ObjectiveText>
Verdict verdict(const SearchRecord& rec, DaysText&& days_text, ObjectiveText&& objective_text,
                const std::string& what_failed) {
  Verdict v;
  const std::vector<Extremal>& ex = rec.extremals;
  if (rec.returned >= 0) {
    v.status = Status::kConverged;
    return v;
  }
  if (proven_infeasible(rec)) {
    v.status = Status::kInfeasible;
    v.detail = "no transfer within the stated bound of " + days_text(rec.bound_days) + ": the minimum time is " +
               days_text(rec.minimum_time_days) + " (" + rec.minimum_time_how + ")";
    return v;
  }
  const int beaten = best_index(rec.extremals);
  if (beaten >= 0 && !std::isnan(rec.coast_bound)) {
    v.detail = "the best extremal the search reached costs " + objective_text(ex[beaten].shape.cost) +
               ", more than the minimum-time transfer completed by a coast on the target (" +
               objective_text(rec.coast_bound) +
               "): it is not the optimum, and no extremal at most as costly was reached";
    return v;
  }
  if (rec.time_limit_hit) {
    v.status = Status::kTimeout;
    v.detail = "the run's time limit (time_limit_s) was reached before an extremal could be returned";
    return v;
  }
  const auto mirrored = std::find_if(ex.begin(), ex.end(), [](const Extremal& e) { return !e.shape.off_side.empty(); });
  if (mirrored != ex.end() &&
      std::all_of(ex.begin(), ex.end(), [](const Extremal& e) { return !e.polished || !e.shape.off_side.empty(); })) {
    v.detail = "every extremal the search reached ends on the mirror of a target, which the rows also admit (" +
               mirrored->shape.off_side + " fails)";
  } else if (!ex.empty() && std::all_of(ex.begin(), ex.end(), [](const Extremal& e) { return e.outside_window; })) {
    const auto shortest = std::min_element(
        ex.begin(), ex.end(), [](const Extremal& a, const Extremal& b) { return a.shape.cost < b.shape.cost; });
    v.detail = "every extremal the search reached (" + std::to_string(ex.size()) +
               ") ends outside the final time's window; the shortest takes " + objective_text(shortest->shape.cost);
    if (std::isfinite(shortest->tf_days) && std::isfinite(rec.bound_days) && shortest->tf_days < rec.bound_days)
      v.detail +=
          ", before the window opens: the minimum time is below the window (widen it, or minimize the fuel at a fixed "
          "time of flight in it)";
  } else if (!ex.empty()) {
    v.detail = "none of the " + std::to_string(ex.size()) +
               " extremals the search reached at eps = 0 converged again at the integrator's tolerance";
  } else {
    v.detail = what_failed;
  }
  if (std::isfinite(rec.minimum_time_days) && std::isfinite(rec.bound_days) &&
      helios::solve::beyond_bound(rec.minimum_time_days, rec.bound_days))
    v.detail += "; the minimum time found, " + days_text(rec.minimum_time_days) +
                ", is beyond the bound, but the search for it did not settle (" + rec.minimum_time_how +
                "), so it does not show the problem infeasible";
  return v;
}

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the pool (templates/runtime/search/pool.hpp): the one place where the
// solutions the routes reach enter the search's record. Two lists: the distinct solutions at
// eps_start (a route's starts, or the minimum-fuel companion's), and the distinct extremals at
// eps = 0, the ones the chooser (chooser.hpp) picks from. A solution that is the same extremal as
// one already there (same_extremal) is counted with its twin, never listed twice; every extremal
// entering is marked with its route and with what makes it returnable or not (its final time's
// window). Before the choice, every extremal found at the search's tolerance is solved again at
// the integrator's own (polish).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// Two converged solutions are one extremal when their structure agrees (revolutions, switches)
// and their shooting variables or their cost do.
// Whether every shooting variable of xb lies within `relative` of xa's, relative to the larger of
// 1 and xa's largest |x_i|.
inline bool variables_within(const std::vector<double>& xa, const std::vector<double>& xb, double relative) {
  double dx = 0, size = 1;
  for (std::size_t i = 0; i < xa.size(); ++i) {
    dx = std::max(dx, std::fabs(xa[i] - xb[i]));
    size = std::max(size, std::fabs(xa[i]));
  }
  return dx <= relative * size;
}

inline bool same_extremal(const std::vector<double>& xa, const Shape& a, const std::vector<double>& xb,
                          const Shape& b) {
  if (a.switches != b.switches || std::fabs(a.revolutions - b.revolutions) > 1e-3) return false;
  return variables_within(xa, xb, 1e-6) || std::fabs(a.cost - b.cost) <= 1e-9 * std::max(1e-3, std::fabs(a.cost));
}

// The solution in `list` that x, a looser solve's, lies next to (every shooting variable within
// 1e-4 of the larger of 1 and the largest |x_i|), or null. Distinct extremals of one problem lie
// orders of magnitude further apart; a start that lands there is that extremal reached again.
template <class List>
const typename List::value_type* near_twin(const List& list, const std::vector<double>& x) {
  for (const auto& e : list)
    if (variables_within(x, e.x, 1e-4)) return &e;
  return nullptr;
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

// The final time of x in days where it is free (its window fraction's variable), NaN where fixed.
inline double free_final_time_days(const std::vector<double>& x) {
  static const int at = free_final_time().variable;
  if (at < 0) return NAN;
  return (kProblem.tf_min + (kProblem.tf - kProblem.tf_min) * x[at] - kProblem.t0) * kProblem.time_unit_days;
}

// Whether x's free departure and final time (where free) lie in their windows: t0_frac and
// tf_frac in [0, 1]. Nothing in the shooting system keeps them there, so an extremal can depart or
// end outside (a minimum time below the window's start, a cheapest departure past the window's
// end); it stays in the record and is never returned (the edge route, edge.hpp, solves the
// problem at the edge it crossed).
inline bool within_window(const std::vector<double>& x) {
  for (const TimeWindow& w : time_windows())
    if (!(x[w.variable] >= -1e-9 && x[w.variable] <= 1 + 1e-9)) return false;
  return true;
}

class Pool {
 public:
  explicit Pool(SearchRecord& rec) : rec_(rec) {}

  // A start's solution at eps_start into `list` (the starts' or the companion's distinct ones).
  int enter_start(std::vector<StartExtremal>& list, const StartRun& run, int start, const std::string& origin = "") {
    StartExtremal entry;
    entry.max_residual = run.res;
    entry.origin = origin;
    return merge_extremal(list, run.x, run.shape, start, std::move(entry));
  }

  // An extremal at eps = 0 reached by `route` (its x, shape and solve in `entry`); returns its index.
  int enter(const std::string& route, Extremal&& entry, int first_start = -1) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++rec_.converged_final;
    const std::vector<double> x = entry.x;
    const Shape shape = entry.shape;
    entry.route = route;
    mark(entry);
    const std::size_t before = rec_.extremals.size();
    const int k = merge_extremal(rec_.extremals, x, shape, first_start, std::move(entry));
    if (rec_.extremals.size() > before) ++added_[route];
    return k;
  }

  // How many distinct extremals `route` added.
  int added_by(const std::string& route) const {
    const auto it = added_.find(route);
    return it == added_.end() ? 0 : it->second;
  }

  // Each distinct extremal at eps = 0 found at the search's tolerance, solved again at the
  // integrator's own (`fine`) from there, where the search's was looser: a single shooting solve at
  // eps = 0 to final_residual, recorded in its homotopy, its shape (and objective) taken again.
  // Over many revolutions single shooting resolves F no better than ~1e-10 (its round-off grows
  // with each revolution), so where it stops short the extremal is solved by multiple shooting
  // (nodes.hpp, node_parts) instead, which is then what proves it. One that converges neither way
  // is kept in the record, marked, and not returned.
  void polish(const Settings& fine, const Settings& coarse) {
    if (coarse.rtol == fine.rtol && coarse.atol == fine.atol) return;
    for (Extremal& e : rec_.extremals) {
      if (out_of_time(fine)) {
        e.polished = false;
        continue;
      }
      Settings at_edges = fine;  // an extremal at a window's edge is one there
      at_edges.window_edges = e.window_edges;
      Shooter shooter(at_edges, kContinuationStart);
      std::vector<double> x = e.x;
      int info = 0;
      double res = 0;
      Result step;
      const auto anything = [](const double*) { return true; };
      e.polished = homotopy_step(shooter, x, 0.0, fine.final_residual, step, anything, info, res);
      e.homotopy.insert(e.homotopy.end(), step.homotopy.begin(), step.homotopy.end());
      if (e.polished) {
        e.x = x;
        e.F = shooter.last_F;
        e.max_residual = res;
        e.info = info;
      } else if (!by_nodes(at_edges, e)) {
        continue;
      }
      e.shape = shape_of(at_edges, e.x, 0.0);
      mark(e);
    }
  }

  SearchRecord& record() { return rec_; }
  const SearchRecord& record() const { return rec_; }

 private:
  // The polish by multiple shooting (see polish): true with e's x, F (the shooting function's rows)
  // and max|F| (every row's, the nodes' too) taken from it where it converges.
  static bool by_nodes(const Settings& fine, Extremal& e) {
    std::vector<double> times;
    int arcs = 0;
    node_values(fine, e.x, 0.0, 1, times, arcs);
    const int parts = node_parts(fine, arcs, e.shape.revolutions);
    if (parts < 1 || (arcs == 1 && parts == 1)) return false;
    const NodesSolution ms = solve_with_nodes(fine, e.x, 0.0, parts);
    e.homotopy.push_back({0.0, ms.converged, ms.max_residual, ms.evaluations});
    if (!ms.converged) return false;
    const int N = kProblem.num_vars;
    e.x.assign(ms.z.begin(), ms.z.begin() + N);
    e.F.assign(ms.F.begin(), ms.F.begin() + N);
    e.max_residual = ms.max_residual;
    e.info = ms.info;
    e.polished = true;
    e.method += ", polished by multiple shooting (" + std::to_string(parts) + " parts per arc)";
    return true;
  }

  static void mark(Extremal& e) {
    e.outside_window = !within_window(e.x);
    e.tf_days = free_final_time_days(e.x);
  }

  SearchRecord& rec_;
  std::map<std::string, int> added_;
  std::mutex mutex_;
};

}  // namespace

}  // namespace helios_rt

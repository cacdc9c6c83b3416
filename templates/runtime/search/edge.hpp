// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the edge route (templates/runtime/search/edge.hpp): a free departure
// (or final time) whose best extremal lies outside its window is solved at the window's edge.
//
// The transversality row of a free time asks that the cost not change to first order as the time
// slides; nothing in it keeps the time inside the stated window. When the cheapest extremal departs
// after the window's end (or before its start), the optimum over the window is at that edge, with
// the row released: the departure held there and the cost's gradient along the time (the released
// row's value, recorded) pointing out of the window. So each extremal outside its window that is
// cheaper than the best one inside is continued in the held window fraction, from where it lies to
// the edge it crossed (window_row: the row becomes frac - held), and the arrival is checked to be a
// minimum along the window: the same problem held a little inside costs no less. Such an arrival is
// an extremal of the problem as stated, with its time at the edge, and enters the pool.
//
// Not for a minimum-time problem's final time (there the bound route, bound.hpp, decides).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

class EdgeRoute : public Route {
 public:
  const char* name() const override { return "window edge"; }
  std::string skip(const SearchContext& c) const override {
    if (c.nested) return "inside another search";
    if (candidates(c.rec()).empty()) return "no extremal cheaper than the best within the windows lies outside them";
    return "";
  }

  std::string run(SearchContext& c) override {
    int reached = 0;
    std::string line;
    for (const int i : candidates(c.rec())) {
      if (c.out_of_time()) break;
      const std::string said = to_edge(c, i, reached);
      c.progress.stage("window edge from extremal " + std::to_string(i) + ": " + said);
      line += (line.empty() ? "" : "; ") + std::to_string(i) + ": " + said;
    }
    return std::to_string(reached) + " extremal(s) at a window's edge (" + line + ")";
  }

 private:
  static constexpr std::size_t kCandidates = 3;
  // The fraction of the window inside the edge where the held problem must cost no less.
  static constexpr double kInside = 1e-3;

  // The window of x that lies outside (the first; null: none, or a minimum time's final time).
  static const TimeWindow* crossed(const std::vector<double>& x) {
    for (const TimeWindow& w : time_windows()) {
      if (std::string(w.time) == "tf" && kProblem.objective == Objective::time) continue;
      if (x[w.variable] < -1e-9 || x[w.variable] > 1 + 1e-9) return &w;
    }
    return nullptr;
  }

  // The extremals outside a window, not held at an edge yet, cheaper than the best returnable
  // one: the cheapest kCandidates.
  static std::vector<int> candidates(const SearchRecord& rec) {
    const double best = best_objective(rec);
    std::vector<int> out;
    for (std::size_t i = 0; i < rec.extremals.size(); ++i) {
      const Extremal& e = rec.extremals[i];
      if (e.outside_window && e.window_edges.empty() && e.shape.off_side.empty() && e.shape.cost < best &&
          crossed(e.x) != nullptr)
        out.push_back(static_cast<int>(i));
    }
    std::sort(out.begin(), out.end(),
              [&](int a, int b) { return rec.extremals[a].shape.cost < rec.extremals[b].shape.cost; });
    if (out.size() > kCandidates) out.resize(kCandidates);
    return out;
  }

  // Extremal i continued to the edge its window crossed; says what came of it.
  static std::string to_edge(SearchContext& c, int i, int& reached) {
    const Extremal& from = c.rec().extremals[i];
    const TimeWindow& w = *crossed(from.x);
    const int v = w.variable;
    const double edge = from.x[v] < 0 ? 0.0 : 1.0;
    const std::string where = std::string(w.time == std::string("t0") ? "the departure" : "the final time") +
                              " held at its window's " + (edge == 0 ? "start" : "end");
    Settings held = c.coarse;
    held.window_edges.assign(static_cast<std::size_t>(kProblem.num_vars), NAN);
    held.window_edges[v] = from.x[v];
    Shooter shooter(held, kContinuationStart);
    std::vector<double> x = from.x;
    std::vector<ContinuationStep> steps;
    const double distance = std::fabs(from.x[v] - edge);
    const auto accept = [&](const std::vector<double>& z) { return c.admissible(z.data()); };
    const double at = follow_parameter(
        c.coarse, shooter, x, 0.0, [&](double p) { held.window_edges[v] = p; }, from.x[v], edge, 1e-7,
        {distance, 1e-3 * distance, distance}, "window fraction held", steps, accept,
        [](const std::vector<double>&) { return false; });
    c.count(shooter.evaluations);
    if (at != edge) return where + ": the continuation stopped at window fraction " + number_text(at, 9);
    const double cost = shape_of(held, x, 0.0).cost;
    // A minimum along the window: held a little inside, the problem costs no less.
    std::vector<double> inside = x;
    held.window_edges[v] = edge == 0 ? kInside : 1 - kInside;
    int info = 0;
    double res = 0;
    const bool inside_ok = shooter.solve(inside, 0.0, c.coarse.accept_residual, info, res) && accept(inside);
    c.count(shooter.last_step_evaluations);
    const double inside_cost = inside_ok ? shape_of(held, inside, 0.0).cost : NAN;
    held.window_edges[v] = edge;
    if (!inside_ok) return where + ": converged, but not a little inside, so not shown a minimum along the window";
    if (inside_cost < cost - 1e-12 * std::max(1.0, std::fabs(cost)))
      return where + ": not a minimum along the window (a little inside costs " + objective_text(inside_cost) +
             ", the edge " + objective_text(cost) + ")";
    Extremal entry =
        solved_extremal(held, x, "single shooting, " + where + " from extremal " + std::to_string(i), std::move(steps));
    std::vector<double> released(x.size());
    Propagator free(c.coarse);
    shooting_function(x.data(), 0.0, free, released.data());
    entry.edge_transversality = released[w.row];
    entry.window_edges = held.window_edges;
    const int k = c.pool.enter("window edge", std::move(entry));
    ++reached;
    return where + ": extremal " + std::to_string(k) + ", " + objective_text(cost) + " (a little inside " +
           objective_text(inside_cost) + ")";
  }
};

}  // namespace

}  // namespace helios_rt

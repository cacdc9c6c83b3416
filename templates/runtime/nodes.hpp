// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, nodes (templates/runtime/nodes.hpp): multiple shooting, the last polish
// of a converged solution. Round-off grows along a long propagation, and single shooting starts
// every arc after an event from what the event's map makes of the arc before, so the first arc's
// round-off reaches the later arcs amplified: on S10 (2201 days, a Mars swing-by) moving the shooting variables by a
// few doubles moves the Jupiter arrival rows by ~1e-10, while the same moves of the state at Mars's departure move them
// by ~2e-13, and round-off grows along each arc too (from 430 days before Mars it reaches Mars 30 times smaller than
// from the departure). So a converged solution is solved once more with nodes, the state and costates at the start of
// every arc after the first and between equal parts of every arc, as variables, and their continuity as rows: F(x;
// nodes) = 0 and (the values the propagation reaches) - node = 0, by hybrj with the exact Jacobian, from the
// single-shooting solution and the values it reaches. It is kept where it converges with max|F| over every row below
// single shooting's (S13, 1000 days of three revolutions without events: residual_noise 5e-11 by single shooting).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The values the propagation reaches at each node at x (ny each, in order), with the nodes' times,
// each arc in `segments` parts; `arcs` counts the arcs. Empty: no node, or x cannot be evaluated.
inline std::vector<double> node_values(const Settings& s, const std::vector<double>& x, double eps, int segments,
                                       std::vector<double>& times, int& arcs) {
  std::vector<double> reached;
  Propagator prop(s);
  Propagator::ArcNodes nodes;
  nodes.segments = segments;
  nodes.reached = &reached;
  const NodesInstalled installed(prop, &nodes);
  std::vector<double> F(static_cast<std::size_t>(kProblem.num_vars));
  try {
    shooting_function(x.data(), eps, prop, F.data());
  } catch (const numerical_error&) {
    return {};
  }
  times = nodes.times;
  arcs = nodes.arcs;
  return reached;
}

// Node k's component c: node<k>_<state> or node<k>_l_<state> (k from 1).
inline std::string node_name(int i) {
  const int n = ny(), ns = kProblem.num_states, c = i % n;
  return "node" + std::to_string(i / n + 1) + "_" + (c < ns ? "" : "l_") + kProblem.state_names[c % ns];
}

inline constexpr int kMaxNodeParts = 100;
// Over many revolutions about the central body round-off grows with each one: a part spans at
// most this many.
inline constexpr double kRevolutionsPerPart = 2;

// The parts each of `arcs` arcs is cut into: as many as make them no longer than
// s.node_spacing_days on average and no more than kRevolutionsPerPart revolutions each, at most
// kMaxNodeParts in all (the polish solves for every node's state and costate with a dense
// Jacobian, whose size grows as the square of their number); 0 with node_spacing_days 0 (no polish).
inline int node_parts(const Settings& s, int arcs, double revolutions) {
  if (s.node_spacing_days <= 0 || arcs < 1) return 0;
  const double span_days = (kProblem.tf - kProblem.t0) * kProblem.time_unit_days;
  const double wanted = std::max(std::ceil(span_days / s.node_spacing_days / arcs),
                                 std::ceil(std::fabs(revolutions) / kRevolutionsPerPart / arcs));
  return std::max(1, static_cast<int>(std::min<double>(wanted, kMaxNodeParts / arcs)));
}

// A solution by multiple shooting: the shooting variables and the nodes (z), its rows (F: the
// shooting function's, then the nodes' continuity defects), max|F|, the nodes' times and parts.
struct NodesSolution {
  bool converged = false;
  std::vector<double> z, F, times;
  double max_residual = INFINITY;
  int segments = 1, evaluations = 0, info = 0;
};

// x (a solution by single shooting at eps, or close to one) solved again with nodes at the start of
// every arc after the first and between `segments` equal parts of each arc, by hybrj with the exact
// Jacobian from x and the values its propagation reaches, to s.final_residual. Needs the shooting
// function on dual numbers of any width where the Jacobian is exact (dual_shooting_function).
inline NodesSolution solve_with_nodes(const Settings& s, const std::vector<double>& x, double eps, int segments) {
  NodesSolution out;
  out.segments = segments;
  if (exact_jacobian(s) && !dual_shooting_function()) return out;
  int arcs = 0;
  const std::vector<double> start = node_values(s, x, eps, segments, out.times, arcs);
  if (start.empty()) return out;
  const int size = kProblem.num_vars + static_cast<int>(start.size());
  out.z = x;
  out.z.insert(out.z.end(), start.begin(), start.end());
  Shooter shooter(s,
                  function_on_either_scalar(size, [segments](const auto* zz, double e, Propagator& p,
                                                             auto* G) { shooting_with_nodes(zz, e, segments, p, G); }),
                  kContinuationStart);
  out.converged = shooter.solve(out.z, eps, s.final_residual, out.info, out.max_residual);
  out.F = shooter.last_F;
  out.evaluations = shooter.evaluations;
  return out;
}

// The shooting function's rows at x by single shooting (into F) and their max|F| (INFINITY where
// the propagation fails).
inline double single_shooting(const Settings& s, const std::vector<double>& x, double eps, std::vector<double>& F) {
  F.assign(static_cast<std::size_t>(kProblem.num_vars), 0.0);
  try {
    Propagator prop(s);
    shooting_function(x.data(), eps, prop, F.data());
  } catch (const numerical_error&) {
    return INFINITY;
  }
  double m = 0;
  for (const double f : F) m = std::max(m, std::fabs(f));
  return m;
}

// Multiple shooting from r, converged by single shooting at eps = 0 (or nearly: an extremal the
// search kept for its round-off, pool.hpp): node_parts parts per arc (none: a problem of one arc
// that needs no more than one, such as a short LEO transfer). r takes its x, F, nodes, continuity
// defects and max|F| where it converges to final_residual below r's max|F|;
// r.single_shooting_residual is then max|F| of the new x alone by single shooting. A program with
// an exact Jacobian but without the shooting function on dual numbers is left as it is.
inline void polish_by_nodes(const Settings& s, Result& r) {
  if (r.status != Status::kConverged) return;
  std::vector<double> times;
  int arcs = 0;
  node_values(s, r.x, r.eps, 1, times, arcs);
  const int segments = node_parts(s, arcs, shape_of(s, r.x, r.eps).revolutions);
  if (segments < 1 || (arcs == 1 && segments == 1)) return;
  // What x gives by single shooting (the search's polish may have proved x by nodes already).
  const int N = kProblem.num_vars;
  std::vector<double> single;
  const double single_max = single_shooting(s, r.x, r.eps, single);
  if (!std::isfinite(single_max)) return;
  const NodesSolution ms = solve_with_nodes(s, r.x, r.eps, segments);
  r.evaluations += ms.evaluations;
  if (!ms.converged || !(ms.max_residual < single_max)) {
    r.F = single;
    r.max_residual = single_max;
    return;
  }
  r.x.assign(ms.z.begin(), ms.z.begin() + N);
  r.nodes.assign(ms.z.begin() + N, ms.z.end());
  r.node_times = ms.times;
  r.node_segments = segments;
  r.F.assign(ms.F.begin(), ms.F.begin() + N);
  r.continuity.assign(ms.F.begin() + N, ms.F.end());
  r.max_residual = ms.max_residual;
  r.method += ", then multiple shooting (" + std::to_string(r.nodes.size() / ny()) + " nodes)";
  r.single_shooting_residual = single_shooting(s, r.x, r.eps, single);
}

}  // namespace

}  // namespace helios_rt

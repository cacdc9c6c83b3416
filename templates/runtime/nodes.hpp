// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, nodes (templates/runtime/nodes.hpp): multiple shooting, the last polish
// of a converged solution. Round-off grows along a long propagation, and single shooting starts
// every arc after an event from what the event's map makes of the arc before, so the first arc's
// round-off reaches the later arcs amplified: on S10 (2201 days, a Mars swing-by) moving the shooting variables by a few
// doubles moves the Jupiter arrival rows by ~1e-10, while the same moves of the state at Mars's
// departure move them by ~2e-13, and round-off grows along each arc too (from 430 days before
// Mars it reaches Mars 30 times smaller than from the departure). So a converged solution is
// solved once more with nodes, the state and costates at the start of every arc after the first
// and between equal parts of every arc, as variables, and their continuity as rows:
// F(x; nodes) = 0 and (the values the propagation reaches) - node = 0, by hybrj with the exact
// Jacobian, from the single-shooting solution and the values it reaches. It is kept where it
// converges with max|F| over every row below single shooting's (S13, 1000 days of three
// revolutions without events: residual_noise 5e-11 by single shooting).
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

// Multiple shooting from r, converged by single shooting at eps = 0: nodes at the start of every
// arc after the first (at interior events), and each arc cut into the same number of parts, as
// many as make the parts no longer than s.node_spacing_days on average (none: a problem of one arc
// shorter than that, such as a LEO transfer of hours). r takes its x, F, nodes, continuity defects
// and max|F| where it converges to final_residual below r's max|F|; r.single_shooting_residual is
// then max|F| of the new x alone by single shooting. Its exact Jacobian needs the shooting function
// on dual numbers of any width; a program with an exact Jacobian but without that is left as it is.
inline void polish_by_nodes(const Settings& s, Result& r) {
  if (r.status != Status::kConverged || s.node_spacing_days <= 0 || (exact_jacobian(s) && !dual_shooting_function())) return;
  std::vector<double> times;
  int arcs = 0;
  node_values(s, r.x, r.eps, 1, times, arcs);
  if (arcs < 1) return;
  const double span_days = (kProblem.tf - kProblem.t0) * kProblem.time_unit_days;
  // At most kMaxNodeParts parts in all: the polish solves for every node's state and costate with
  // a dense Jacobian, whose size grows as the square of their number.
  const double wanted = std::ceil(span_days / s.node_spacing_days / arcs);
  const int segments = std::max(1, static_cast<int>(std::min<double>(wanted, kMaxNodeParts / arcs)));
  if (arcs == 1 && segments == 1) return;
  const std::vector<double> start = node_values(s, r.x, r.eps, segments, times, arcs);
  if (start.empty()) return;
  const int N = kProblem.num_vars, size = N + static_cast<int>(start.size());
  std::vector<double> z = r.x;
  z.insert(z.end(), start.begin(), start.end());
  Shooter shooter(s,
                  function_on_either_scalar(size,
                                            [segments](const auto* zz, double e, Propagator& p, auto* G) {
                                              shooting_with_nodes(zz, e, segments, p, G);
                                            }),
                  kContinuationStart);
  int info = 0;
  double res = 0;
  const bool converged = shooter.solve(z, r.eps, s.final_residual, info, res);
  r.evaluations += shooter.evaluations;
  if (!converged || !(res < r.max_residual)) return;
  r.x.assign(z.begin(), z.begin() + N);
  r.nodes.assign(z.begin() + N, z.end());
  r.node_times = times;
  r.node_segments = segments;
  r.F.assign(shooter.last_F.begin(), shooter.last_F.begin() + N);
  r.continuity.assign(shooter.last_F.begin() + N, shooter.last_F.end());
  r.max_residual = res;
  r.method += ", then multiple shooting (" + std::to_string(r.nodes.size() / ny()) + " nodes)";
  Propagator prop(s);
  std::vector<double> single(static_cast<std::size_t>(N));
  try {
    shooting_function(r.x.data(), r.eps, prop, single.data());
    r.single_shooting_residual = 0;
    for (const double f : single) r.single_shooting_residual = std::max(r.single_shooting_residual, std::fabs(f));
  } catch (const numerical_error&) {
    r.single_shooting_residual = INFINITY;
  }
}

}  // namespace

}  // namespace helios_rt

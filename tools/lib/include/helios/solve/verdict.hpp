#pragma once
// When a minimum time shows a stated bound infeasible: one rule for a single solve's verdict
// (templates/runtime/search/chooser.hpp) and a sweep's cells below their row's boundary
// (tools/lib/src/sweep/boundary.cpp), so a porkchop and a solve of one of its cells agree.

namespace helios::solve {

// Below this many days past the bound (or this share of it, over a day) a minimum time shows
// nothing: the two agree to the integration's round-off.
constexpr double kInfeasibleToleranceDays = 1e-6;

// Whether no transfer within `bound_days` exists when the shortest one takes `minimum_days`.
inline bool beyond_bound(double minimum_days, double bound_days) {
  const double scale = bound_days > 1 ? bound_days : 1.0;
  return minimum_days > bound_days + kInfeasibleToleranceDays * scale;
}

}  // namespace helios::solve

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, residual (templates/runtime/residual.hpp): the RESIDUAL module's
// interface: the shooting function, by legs for events, and the rows of the bounds.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

// The shooting function of the RESIDUAL module, with the bookkeeping hybrd1 needs.
void shooting_function(const double* x, double eps, Propagator& prop, double* F);

// Problems with interior events also have the shooting function by legs (RESIDUAL module):
// stop_at = k solves leg k alone (it ends at event k as if the trajectory ended there);
// stop_at = -1 is multiple shooting: after event k the costates restart from starts[k*n...] and
// their mismatch with the jump conditions is written to continuity[k*n...].
struct Legs {
  int stop_at = -1;
  const double* starts = nullptr;
  double* continuity = nullptr;
};
void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs);
using Residual = std::function<void(const double* x, double eps, Propagator& prop, double* F)>;

// Which shooting variables each leg solves for alone (indices into x; leg k > 0 also solves for
// its start costates), and the variables a leg alone holds fixed: the time fractions at their
// guesses, the event's other variables (costates after a state map, parameters) at 0.
struct LegPlan {
  std::vector<std::vector<int>> variables;
  std::vector<int> time_fractions, held_at_zero;
  // An epoch's window bound: while it is active (pass 2), legs alone hold the epoch's fraction
  // at the window's edge (0 or 1) instead of a guess inside.
  struct WindowEdge {
    int bound, fraction;
    double edge;
  };
  std::vector<WindowEdge> window_edges;
};

// A bound psi <= 0 of the derivation, solved in two passes: its row of the shooting function is
// its multiplier (= 0) while inactive and psi itself (= 0) when active.
struct Bound {
  std::string name, meaning;
  int multiplier;  // index of the bound's multiplier in x
};

struct BoundReport {
  std::string name, meaning;
  double first_pass_value;   // psi at the solution of pass 1 (bound inactive); > 0 is a violation
  bool active;               // made active in pass 2
  double value, multiplier;  // at the final solution
};

struct BoundState {
  std::vector<char> active;
  std::vector<double> value;
};
inline BoundState& bound_state() {
  thread_local BoundState state;  // each search thread its own (search.hpp's parallel_for)
  return state;
}

// Row k of the shooting function for bound k: records psi and returns it when the bound is
// active, else the inactive expression (its multiplier).
inline double bound_row(int k, double psi, double inactive) {
  BoundState& b = bound_state();
  if (static_cast<std::size_t>(k) >= b.value.size()) {
    b.value.resize(k + 1, 0.0);
    b.active.resize(k + 1, 0);
  }
  b.value[k] = psi;
  return b.active[k] ? psi : inactive;
}

}  // namespace helios_rt

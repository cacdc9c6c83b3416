// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, residual (templates/runtime/residual.hpp): the rows of the
// bounds (the RESIDUAL module's interface is in helios_runtime.hpp).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The active set of the bounds and their last values (bound_row).
struct BoundState {
  std::vector<char> active;
  std::vector<double> value;
};
inline BoundState& bound_state() {
  thread_local BoundState state;  // each search thread its own (search.hpp's parallel_for)
  return state;
}

}  // namespace

// Row k of the shooting function for bound k: records psi and returns it when the bound is
// active, else the inactive expression (its multiplier).
double bound_row(int k, double psi, double inactive) {
  BoundState& b = bound_state();
  if (static_cast<std::size_t>(k) >= b.value.size()) {
    b.value.resize(k + 1, 0.0);
    b.active.resize(k + 1, 0);
  }
  b.value[k] = psi;
  return b.active[k] ? psi : inactive;
}

Dual bound_row(int k, const Dual& psi, const Dual& inactive) {
  bound_row(k, psi.v, inactive.v);
  return bound_state().active[k] ? psi : inactive;
}

void dual_jacobian(int n, const double* x, double* F, double* J,
                   const std::function<void(const Dual* x, Dual* F)>& dual_function) {
  ad::begin_jacobian(n);
  std::vector<Dual> xd, Fd(static_cast<std::size_t>(n));
  std::vector<double> unit(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j) {
    unit[j] = 1;
    xd.push_back(ad::with_derivatives(x[j], unit.data()));
    unit[j] = 0;
  }
  dual_function(xd.data(), Fd.data());
  for (int i = 0; i < n; ++i) {
    F[i] = Fd[i].v;
    for (int j = 0; j < n; ++j) J[i + j * n] = ad::derivative(Fd[i], j);
  }
}

}  // namespace helios_rt

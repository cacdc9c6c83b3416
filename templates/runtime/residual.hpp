// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, residual (templates/runtime/residual.hpp): the rows of the
// bounds, and the shooting function with multiple shooting's nodes (the RESIDUAL module's
// interface is in helios_runtime.hpp).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The shooting function by legs (the RESIDUAL module's, of a problem with events) on double or on
// Dual, through the program's module table.
inline void legs_function(const double* x, double eps, Propagator& prop, double* F, const Legs* legs) {
  kModules.shooting_legs(x, eps, prop, F, legs);
}
inline void legs_function(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs) {
  kModules.shooting_legs_dual(x, eps, prop, F, legs);
}

// Installs `nodes` on a propagator for one scope.
class NodesInstalled {
 public:
  NodesInstalled(Propagator& prop, Propagator::ArcNodes* nodes) : prop_(prop) { prop_.nodes = nodes; }
  ~NodesInstalled() { prop_.nodes = nullptr; }
  NodesInstalled(const NodesInstalled&) = delete;
  NodesInstalled& operator=(const NodesInstalled&) = delete;

 private:
  Propagator& prop_;
};

// The shooting function of full width on dual numbers: the legs function without legs (a problem
// with interior events) or the plain one; null when the program has neither.
using DualShootingFunction = void (*)(const Dual*, double, Propagator&, Dual*);
inline DualShootingFunction dual_shooting_function() {
  if (kModules.shooting_function_dual) return kModules.shooting_function_dual;
  if (!kModules.shooting_legs_dual) return nullptr;
  return [](const Dual* x, double eps, Propagator& prop, Dual* F) {
    kModules.shooting_legs_dual(x, eps, prop, F, nullptr);
  };
}

// The shooting function with nodes on z = (x, nodes), on double or on Dual: F(x) with the
// propagation continued from each node (each arc in `segments` parts), then the nodes'
// continuity defects.
template <class T>
void shooting_with_nodes(const T* z, double eps, int segments, Propagator& prop, T* G) {
  const int N = kProblem.num_vars;
  Propagator::ArcNodes nodes;
  nodes.segments = segments;
  if constexpr (std::is_same_v<T, double>) {
    nodes.values = z + N;
    nodes.defects = G + N;
  } else {
    nodes.dual_values = z + N;
    nodes.dual_defects = G + N;
  }
  const NodesInstalled installed(prop, &nodes);
  if constexpr (std::is_same_v<T, double>)
    shooting_function(z, eps, prop, G);
  else
    dual_shooting_function()(z, eps, prop, G);
}

// The shooting function of a solution on z = (x, its `nodes` node values, each arc in `segments`
// parts): single shooting at x where it has none.
inline void solution_function(const double* z, std::size_t nodes, double eps, int segments, Propagator& prop,
                              double* F) {
  if (nodes == 0)
    shooting_function(z, eps, prop, F);
  else
    shooting_with_nodes(z, eps, segments, prop, F);
}

}  // namespace

// Row k of the shooting function for bound k: records psi on the propagator and returns it when
// the bound is in the propagator's active set, else the inactive expression (its multiplier).
double bound_row(Propagator& prop, int k, double psi, double inactive) {
  std::vector<double>& values = prop.bound_values;
  if (static_cast<std::size_t>(k) >= values.size()) values.resize(k + 1, 0.0);
  values[k] = psi;
  return prop.bound_active(k) ? psi : inactive;
}

Dual bound_row(Propagator& prop, int k, const Dual& psi, const Dual& inactive) {
  bound_row(prop, k, psi.v, inactive.v);
  return prop.bound_active(k) ? psi : inactive;
}

double window_row(Propagator& prop, int k, double frac, double transversality) {
  const double held = prop.held_fraction(k);
  return std::isnan(held) ? transversality : frac - held;
}

Dual window_row(Propagator& prop, int k, const Dual& frac, const Dual& transversality) {
  const double held = prop.held_fraction(k);
  return std::isnan(held) ? transversality : frac - held;
}

void side_condition(Propagator& prop, int k, double g, const char* meaning) {
  if (static_cast<std::size_t>(k) >= prop.side_values.size()) prop.side_values.resize(k + 1);
  prop.side_values[k] = {g, meaning};
}

void side_condition(Propagator& prop, int k, const Dual& g, const char* meaning) {
  side_condition(prop, k, g.v, meaning);
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

// The exact shooting Jacobian (the RESIDUAL module on dual numbers, its propagations by the
// variational equations with the switch and event-time corrections) against central finite
// differences of the shooting function: built by tests/bats/jacobian.bats with the program's
// shoot.cpp included (its main renamed), linked with libhelios-runtime.a.
// usage: shooting_jacobian_check EPS POINTS SEED [X0 X1 ...]
//   With HELIOS_NODE_SEGMENTS=K: the multiple-shooting system
//   instead (the runtime's nodes.hpp, built here on the same public calls): z = (x, the state and
//   costates at every node, each arc in K parts), the nodes moved off the trajectory by up to 1e-6
//   relative so that every continuity row is in play.
//   POINTS random starts of the SOLVE module's initial_guess (points where the shooting function
//   cannot be evaluated are skipped and counted), then X when given (a solution's variables).
// Prints "points N skipped K max_error E" (the largest |J - J_fd| over every entry, relative to
// 1 + its row's largest |entry|) and exits 1 when E > 1e-6 or no point was checked.
// NOTE: J_fd is, entry by entry, the closest to J of eight finite-difference estimates: the
// central differences D(h) with h = 1e-4, 1e-6, 1e-8 and 1e-10 times 1 + |x_j|, and their
// Richardson extrapolations (4 D(h) - D(2h)) / 3. No one estimate serves every entry: a
// difference's truncation grows as h^2 times the third derivative, which many switches or a
// swing-by make large (at S05's solution, 33 switches, D(1e-5) is off by 2e-3 relative and
// D(1e-7) by 2e-7; at S10's, D(1e-7) by 9e-2 and D(1e-10) by 1e-6, each converging to J), and its
// noise grows as the integrator's tolerance (1e-13) over h, which a free final time's row (the
// steps move with tf) multiplies by 1e2-1e3.
#include "helios_runtime.hpp"

#define main shoot_main
#include SHOOT_CPP
#undef main

#include <cstdlib>

namespace {

using namespace helios_rt;

int node_segments = 0;  // HELIOS_NODE_SEGMENTS: the multiple-shooting system (0: single shooting)

// The shooting function of z: x alone, or (x, nodes) with each arc in node_segments parts.
void evaluate(const std::vector<double>& z, double eps, Propagator& prop, double* F) {
  if (node_segments == 0) return shooting_function(z.data(), eps, prop, F);
  const int N = kProblem.num_vars;
  Propagator::ArcNodes nodes;
  nodes.segments = node_segments;
  nodes.values = z.data() + N;
  nodes.defects = F + N;
  prop.nodes = &nodes;
  shooting_function(z.data(), eps, prop, F);
  prop.nodes = nullptr;
}

// Its exact Jacobian (column-major, z.size() squared).
void exact_jacobian(const std::vector<double>& z, double eps, Propagator& prop, double* F, double* J) {
  if (node_segments == 0) return shooting_jacobian(z.data(), eps, prop, F, J);
  const int N = kProblem.num_vars;
  dual_jacobian(static_cast<int>(z.size()), z.data(), F, J, [&](const Dual* zd, Dual* Fd) {
    Propagator::ArcNodes nodes;
    nodes.segments = node_segments;
    nodes.dual_values = zd + N;
    nodes.dual_defects = Fd + N;
    prop.nodes = &nodes;
    // The program's module table: the plain function on dual numbers, or the legs (interior events).
    if (kModules.shooting_function_dual != nullptr)
      kModules.shooting_function_dual(zd, eps, prop, Fd);
    else
      kModules.shooting_legs_dual(zd, eps, prop, Fd, nullptr);
    prop.nodes = nullptr;
  });
}

// x with its nodes appended: the values the propagation reaches there, each moved by up to 1e-6
// relative (x alone without nodes).
std::vector<double> with_nodes(const std::vector<double>& x, double eps, Propagator& prop, std::mt19937_64& rng) {
  if (node_segments == 0) return x;
  std::vector<double> reached, F(static_cast<std::size_t>(kProblem.num_vars));
  Propagator::ArcNodes nodes;
  nodes.segments = node_segments;
  nodes.reached = &reached;
  prop.nodes = &nodes;
  shooting_function(x.data(), eps, prop, F.data());
  prop.nodes = nullptr;
  std::uniform_real_distribution<double> move(-1e-6, 1e-6);
  std::vector<double> z = x;
  for (const double v : reached) z.push_back(v * (1 + move(rng)));
  return z;
}

// The largest |a - b| over rows i of entries i + j n (column-major), relative to 1 + row max |a|.
double row_error(const std::vector<double>& a, const std::vector<double>& b, int n) {
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    double scale = 1;
    for (int j = 0; j < n; ++j) scale = std::max(scale, 1 + std::fabs(a[i + j * n]));
    for (int j = 0; j < n; ++j) worst = std::max(worst, std::fabs(a[i + j * n] - b[i + j * n]) / scale);
  }
  return worst;
}

// Central differences of the shooting function at x with steps h (1 + |x_j|); false where it
// cannot be evaluated.
bool central_differences(const std::vector<double>& x, double eps, double step, Propagator& prop,
                         std::vector<double>& J) {
  const int n = static_cast<int>(x.size());
  std::vector<double> up(n), down(n);
  try {
    for (int j = 0; j < n; ++j) {
      const double h = step * (1 + std::fabs(x[j]));
      std::vector<double> xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      evaluate(xp, eps, prop, up.data());
      evaluate(xm, eps, prop, down.data());
      for (int i = 0; i < n; ++i) J[i + j * n] = (up[i] - down[i]) / (2 * h);
    }
  } catch (const numerical_error&) {
    return false;
  }
  for (double v : J)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: shooting_jacobian_check EPS POINTS SEED [X...]\n");
    return 2;
  }
  const double eps = std::atof(argv[1]);
  const int points = std::atoi(argv[2]);
  std::mt19937_64 rng(std::strtoull(argv[3], nullptr, 10));
  const int n = kProblem.num_vars;
  std::vector<std::vector<double>> xs;
  for (int p = 0; p < points; ++p) {
    std::vector<double> x(n);
    initial_guess(rng, x.data());
    xs.push_back(x);
  }
  if (argc > 4) {
    if (argc - 4 != n) {
      std::fprintf(stderr, "shooting_jacobian_check: %d values given, the problem has %d variables\n", argc - 4, n);
      return 2;
    }
    std::vector<double> x(n);
    for (int j = 0; j < n; ++j) x[j] = std::atof(argv[4 + j]);
    xs.push_back(x);
  }
  if (const char* k = std::getenv("HELIOS_NODE_SEGMENTS")) node_segments = std::atoi(k);
  const Settings settings;
  Propagator prop(settings);
  double worst = 0;
  int checked = 0, skipped = 0;
  for (const auto& x0 : xs) {
    std::vector<double> x;
    bool ok = true;
    try {
      x = with_nodes(x0, eps, prop, rng);
    } catch (const numerical_error&) {
      ok = false;
      x = x0;
    }
    const int m = static_cast<int>(x.size());
    std::vector<double> F(m), J(m * m), J_fd(m * m), J_h(m * m);
    try {
      if (ok) exact_jacobian(x, eps, prop, F.data(), J.data());
    } catch (const numerical_error&) {
      ok = false;
    }
    std::vector<double> J_2h(m * m);
    std::fill(J_fd.begin(), J_fd.end(), INFINITY);
    for (const double step : {1e-4, 1e-6, 1e-8, 1e-10}) {
      ok = ok && central_differences(x, eps, step, prop, J_h) && central_differences(x, eps, 2 * step, prop, J_2h);
      for (int k = 0; ok && k < m * m; ++k)
        for (const double estimate : {J_h[k], (4 * J_h[k] - J_2h[k]) / 3})
          if (!(std::fabs(J_fd[k] - J[k]) <= std::fabs(estimate - J[k]))) J_fd[k] = estimate;
    }
    if (!ok) {
      ++skipped;
      continue;
    }
    ++checked;
    worst = std::max(worst, row_error(J, J_fd, m));
  }
  std::printf("points %d skipped %d max_error %.3e\n", checked, skipped, worst);
  return checked > 0 && worst <= 1e-6 ? 0 : 1;
}

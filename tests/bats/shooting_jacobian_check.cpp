// The exact shooting Jacobian (the RESIDUAL module on dual numbers, its propagations by the
// variational equations with the switch and event-time corrections) against central finite
// differences of the shooting function: built by tests/bats/jacobian.bats with the program's
// shoot.cpp included (its main renamed), linked with libhelios-runtime.a.
// usage: shooting_jacobian_check EPS POINTS SEED [X0 X1 ...]
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
#define main shoot_main
#include SHOOT_CPP
#undef main

#include <cstdlib>

namespace {

using namespace helios_rt;

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
      shooting_function(xp.data(), eps, prop, up.data());
      shooting_function(xm.data(), eps, prop, down.data());
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
  const Settings settings;
  Propagator prop(settings);
  double worst = 0;
  int checked = 0, skipped = 0;
  for (const auto& x : xs) {
    std::vector<double> F(n), J(n * n), J_fd(n * n), J_h(n * n);
    bool ok = true;
    try {
      shooting_jacobian(x.data(), eps, prop, F.data(), J.data());
    } catch (const numerical_error&) {
      ok = false;
    }
    std::vector<double> J_2h(n * n);
    std::fill(J_fd.begin(), J_fd.end(), INFINITY);
    for (const double step : {1e-4, 1e-6, 1e-8, 1e-10}) {
      ok = ok && central_differences(x, eps, step, prop, J_h) && central_differences(x, eps, 2 * step, prop, J_2h);
      for (int k = 0; ok && k < n * n; ++k)
        for (const double estimate : {J_h[k], (4 * J_h[k] - J_2h[k]) / 3})
          if (!(std::fabs(J_fd[k] - J[k]) <= std::fabs(estimate - J[k]))) J_fd[k] = estimate;
    }
    if (!ok) {
      ++skipped;
      continue;
    }
    ++checked;
    worst = std::max(worst, row_error(J, J_fd, n));
  }
  std::printf("points %d skipped %d max_error %.3e\n", checked, skipped, worst);
  return checked > 0 && worst <= 1e-6 ? 0 : 1;
}

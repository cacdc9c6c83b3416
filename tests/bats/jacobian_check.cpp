// The generated JACOBIAN module (df/dz with z = (y, lambda0), df/du, the direction law's and the throttle slopes'
// gradients) against central finite differences of the generated (or template) DYNAMICS and
// SWITCH modules, at random points: built by tests/bats/jacobian.bats with the
// program's shoot.cpp included (its main renamed), linked with libhelios-runtime.a.
// usage: jacobian_check POINTS SEED  -> one line "max_error E" (the largest error over every
// entry, relative to 1 + the row's largest |entry|); exit 1 when E > 1e-6.
#define main shoot_main
#include SHOOT_CPP
#undef main

#include <cstdlib>

namespace {

using namespace helios_rt;

// The largest |a - b| of entries i * cols + j over rows, each relative to 1 + that row's max |a|.
double row_error(const std::vector<double>& a, const std::vector<double>& b, int rows, int cols) {
  double worst = 0;
  for (int i = 0; i < rows; ++i) {
    double scale = 1;
    for (int j = 0; j < cols; ++j) scale = std::max(scale, 1 + std::fabs(a[i * cols + j]));
    for (int j = 0; j < cols; ++j) worst = std::max(worst, std::fabs(a[i * cols + j] - b[i * cols + j]) / scale);
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const int points = argc > 1 ? std::atoi(argv[1]) : 20;
  std::mt19937_64 rng(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1);
  std::uniform_real_distribution<double> size(0.5, 1.5), sign(-1, 1), unit(0, 1);
  const int ns = kProblem.num_states, ny = 2 * ns, nz = ny + 1, nc = kProblem.num_controls;
  double worst = 0;
  for (int p = 0; p < points; ++p) {
    std::vector<double> y(ny), control(kMaxControls, 0.0);
    for (int i = 0; i < ns; ++i) y[i] = size(rng) * (i == kProblem.mass_index || sign(rng) > 0 ? 1 : -1);
    for (int i = ns; i < ny; ++i) y[i] = sign(rng);
    for (int k = 0; k < nc; ++k) control[k] = unit(rng);
    const Multipliers mult{size(rng), unit(rng)};
    const double t = kProblem.t0 + unit(rng) * (kProblem.tf - kProblem.t0);
    // z = (y, lambda0) moved by s h along z_j (h = 1e-6 (1 + |z_j|)).
    const auto step = [&](int j) { return 1e-6 * (1 + std::fabs(j < ny ? y[j] : mult.lambda0)); };
    const auto moved = [&](int j, double by, std::vector<double>& yj, Multipliers& mj) {
      yj = y;
      mj = mult;
      (j < ny ? yj[j] : mj.lambda0) += by;
    };
    std::vector<double> dfdz(ny * nz), dfdu(std::max(1, ny * nc)), fd_z(ny * nz), fd_u(std::max(1, ny * nc));
    dynamics_jacobian(t, y.data(), control.data(), mult, dfdz.data(), dfdu.data());
    std::vector<double> up(ny), down(ny), cu(kMaxControls), cd(kMaxControls), yp, ym;
    Multipliers mp, mm;
    for (int j = 0; j < nz; ++j) {  // central differences in z_j
      const double h = step(j);
      moved(j, h, yp, mp);
      moved(j, -h, ym, mm);
      dynamics(t, yp.data(), control.data(), mp, up.data());
      dynamics(t, ym.data(), control.data(), mm, down.data());
      for (int i = 0; i < ny; ++i) fd_z[i * nz + j] = (up[i] - down[i]) / (2 * h);
    }
    for (int k = 0; k < nc; ++k) {  // and in control_k
      const double h = 1e-6 * (1 + std::fabs(control[k]));
      std::vector<double> up_c = control, down_c = control;
      up_c[k] += h;
      down_c[k] -= h;
      dynamics(t, y.data(), up_c.data(), mult, up.data());
      dynamics(t, y.data(), down_c.data(), mult, down.data());
      for (int i = 0; i < ny; ++i) fd_u[i * nc + k] = (up[i] - down[i]) / (2 * h);
    }
    std::vector<double> dcdy(std::max(1, nc * ny)), fd_c(std::max(1, nc * ny), 0.0);
    direction_jacobian(y.data(), dcdy.data());
    for (int j = 0; j < ny; ++j) {  // the direction law's central differences (the throttle's row stays 0)
      const double h = step(j);
      moved(j, h, yp, mp);
      moved(j, -h, ym, mm);
      std::fill(cu.begin(), cu.end(), 0.0);
      std::fill(cd.begin(), cd.end(), 0.0);
      direction_control(yp.data(), cu.data());
      direction_control(ym.data(), cd.data());
      for (int k = 0; k < nc; ++k)
        if (k != kProblem.throttle_index) fd_c[k * ny + j] = (cu[k] - cd[k]) / (2 * h);
    }
    if (kProblem.throttle_index >= 0) {  // the throttle slopes' gradients in z
      std::vector<double> dl(nz), du(nz), fd_l(nz), fd_h(nz);
      kModules.throttle_slopes_jacobian(y.data(), mult, dl.data(), du.data());
      for (int j = 0; j < nz; ++j) {
        const double h = step(j);
        moved(j, h, yp, mp);
        moved(j, -h, ym, mm);
        double lp = 0, hp = 0, lm = 0, hm = 0;
        kModules.throttle_slopes(yp.data(), mp, lp, hp);
        kModules.throttle_slopes(ym.data(), mm, lm, hm);
        fd_l[j] = (lp - lm) / (2 * h);
        fd_h[j] = (hp - hm) / (2 * h);
      }
      worst = std::max({worst, row_error(dl, fd_l, 1, nz), row_error(du, fd_h, 1, nz)});
    }
    worst = std::max({worst, row_error(dfdz, fd_z, ny, nz), nc > 0 ? row_error(dfdu, fd_u, ny, nc) : 0.0,
                      nc > 0 ? row_error(dcdy, fd_c, nc, ny) : 0.0});
  }
  std::printf("max_error %.3e\n", worst);
  return worst <= 1e-6 ? 0 : 1;
}

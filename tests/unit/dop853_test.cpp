#include "dop853.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "helios/astro/kepler.hpp"
#include "test_helpers.hpp"

namespace {

using State = std::array<double, 6>;

// Two-body problem in units with mu = 1.
struct TwoBody {
  int calls = 0;
  void operator()(double /*t*/, const double* y, double* dy) {
    ++calls;
    const double r2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2];
    const double k = -1.0 / (r2 * std::sqrt(r2));
    dy[0] = y[3];
    dy[1] = y[4];
    dy[2] = y[5];
    dy[3] = k * y[0];
    dy[4] = k * y[1];
    dy[5] = k * y[2];
  }
};

// Periapsis of an orbit with a = 1, e = 0.5, slightly inclined so all components are exercised.
State initial_state() {
  return helios::astro::elements_to_state({1.0, 0.5, 0.3, 0.4, 0.5, 0.0}, 1.0);
}

double max_abs_diff(const State& a, const State& b) {
  double m = 0.0;
  for (int k = 0; k < 6; ++k) m = std::max(m, std::fabs(a[k] - b[k]));
  return m;
}

// Fixed-step integration over [0, t_end] with n_steps steps.
State integrate_fixed(double t_end, int n_steps) {
  TwoBody f;
  helios_rt::Dop853 rk(6);
  State y = initial_state(), f0{}, y1{}, f1{};
  f(0.0, y.data(), f0.data());
  const double h = t_end / n_steps;
  for (int i = 0; i < n_steps; ++i) {
    rk.step(f, i * h, y.data(), f0.data(), h, y1.data(), f1.data(), 1e-12, 1e-12);
    y = y1;
    f0 = f1;
  }
  return y;
}

}  // namespace

TEST(Dop853, CoefficientsSatisfyOrderConditions) {
  using namespace helios_rt::dop853_coeffs;
  for (int s = 1; s < 12; ++s) {
    double row = 0.0;
    for (int j = 0; j < s; ++j) row += A[s][j];
    EXPECT_TRUE(IsClose(row, C[s], 1e-13, 0.0)) << "row " << s;  // entries reach ~40
  }
  // Quadrature conditions sum_j b_j c_j^k = 1/(k+1) up to order 8.
  for (int k = 0; k < 8; ++k) {
    double q = 0.0;
    for (int j = 0; j < 12; ++j) q += B[j] * std::pow(C[j], k);
    EXPECT_TRUE(IsClose(q, 1.0 / (k + 1), 1e-14, 0.0)) << "k=" << k;
  }
  // Both error estimators annihilate constants.
  double e5 = 0.0, e3 = -(BHH[0] + BHH[1] + BHH[2]);
  for (int j = 0; j < 12; ++j) {
    e5 += E5[j];
    e3 += B[j];
  }
  EXPECT_TRUE(IsClose(e5, 0.0, 1e-14, 0.0));
  EXPECT_TRUE(IsClose(e3, 0.0, 1e-14, 0.0));
}

TEST(Dop853, FixedStepIsEighthOrder) {
  const double period = 2.0 * helios::astro::PI;
  const State exact = initial_state();  // one full period returns to the start
  const double e1 = max_abs_diff(integrate_fixed(period, 120), exact);
  const double e2 = max_abs_diff(integrate_fixed(period, 240), exact);
  const double ratio = e1 / e2;
  EXPECT_GT(ratio, 150.0) << "e1=" << e1 << " e2=" << e2;
  EXPECT_LT(ratio, 400.0) << "e1=" << e1 << " e2=" << e2;
  EXPECT_GT(e2, 1e-13);  // still well above round-off, so the ratio measures truncation error
}

TEST(Dop853, AdaptiveMatchesKeplerPropagation) {
  const double t_end = 5.0 * 2.0 * helios::astro::PI + 1.234;
  const double tol = 1e-12;
  TwoBody f;
  helios_rt::Dop853 rk(6);
  State y = initial_state(), f0{}, y1{}, f1{};
  f(0.0, y.data(), f0.data());
  double t = 0.0, h = 1e-3;
  int accepted = 0, rejected = 0;
  bool last_rejected = false;
  while (t < t_end && accepted + rejected < 100000) {
    const bool last = t + h >= t_end;
    const double hs = last ? t_end - t : h;
    const double err = rk.step(f, t, y.data(), f0.data(), hs, y1.data(), f1.data(), tol, tol);
    double fac = helios_rt::Dop853::step_factor(err);
    if (err <= 1.0) {
      t = last ? t_end : t + hs;
      y = y1;
      f0 = f1;
      ++accepted;
      if (last_rejected) fac = std::min(fac, 1.0);  // as in dop853.f: no growth right after a rejection
      last_rejected = false;
    } else {
      ++rejected;
      last_rejected = true;
    }
    h = hs * fac;
  }
  ASSERT_EQ(t, t_end);
  const State exact = helios::astro::propagate(initial_state(), t_end, 1.0);
  double scale = 0.0;
  for (int k = 0; k < 6; ++k) scale = std::max(scale, std::fabs(exact[k]));
  for (int k = 0; k < 6; ++k) EXPECT_TRUE(IsClose(y[k], exact[k], 1e-9 * scale, 1e-9)) << "k=" << k;
  EXPECT_GT(accepted, 50);
  EXPECT_LT(accepted, 5000);
}

TEST(Dop853, ErrorEstimateGrowsWithStep) {
  TwoBody f;
  helios_rt::Dop853 rk(6);
  const State y = initial_state();
  State f0{}, y1{}, f1{};
  f(0.0, y.data(), f0.data());
  double prev = 0.0;
  for (double h : {0.005, 0.01, 0.02, 0.04, 0.08}) {
    const double err = rk.step(f, 0.0, y.data(), f0.data(), h, y1.data(), f1.data(), 1e-12, 1e-12);
    EXPECT_GT(err, prev) << "h=" << h;
    if (prev > 0.0) {
      EXPECT_GT(err / prev, 8.0) << "h=" << h;  // high order: much more than linear growth
    }
    prev = err;
  }
}

TEST(Dop853, StepWritesEndpointDerivativeAndAllowsAliasing) {
  TwoBody f;
  helios_rt::Dop853 rk(6);
  State y = initial_state(), f0{}, y1{}, f1{}, fcheck{};
  f(0.0, y.data(), f0.data());
  const int before = f.calls;
  rk.step(f, 0.0, y.data(), f0.data(), 0.05, y1.data(), f1.data(), 1e-10, 1e-10);
  EXPECT_EQ(f.calls - before, 12);  // 11 new stages + the end point
  f(0.05, y1.data(), fcheck.data());
  for (int k = 0; k < 6; ++k) EXPECT_TRUE(IsClose(f1[k], fcheck[k], 0.0, 1e-15));
  // In place: y_new == y and f_new == f0.
  State yi = initial_state(), fi{};
  f(0.0, yi.data(), fi.data());
  const double err_sep = rk.step(f, 0.0, yi.data(), fi.data(), 0.05, y1.data(), f1.data(), 1e-10, 1e-10);
  const double err_in = rk.step(f, 0.0, yi.data(), fi.data(), 0.05, yi.data(), fi.data(), 1e-10, 1e-10);
  EXPECT_TRUE(IsClose(err_in, err_sep, 0.0, 1e-15));
  for (int k = 0; k < 6; ++k) {
    EXPECT_TRUE(IsClose(yi[k], y1[k], 0.0, 1e-15));
    EXPECT_TRUE(IsClose(fi[k], f1[k], 0.0, 1e-15));
  }
}

TEST(Dop853, StepFactor) {
  using helios_rt::Dop853;
  EXPECT_TRUE(IsClose(Dop853::step_factor(0.0), 6.0, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(Dop853::step_factor(1e-30), 6.0, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(Dop853::step_factor(1.0), 0.9, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(Dop853::step_factor(std::pow(0.9 / 2.0, 8.0)), 2.0, 0.0, 1e-14));
  EXPECT_TRUE(IsClose(Dop853::step_factor(1e30), 0.333, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(Dop853::step_factor(std::nan("")), 0.333, 0.0, 1e-15));
}

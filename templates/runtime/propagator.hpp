// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, propagator (templates/runtime/propagator.hpp): the propagator: DOP853
// under the optimal control, one mode at a time, switches located to round-off.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

Propagator::Propagator(const Settings& s) : settings_(s), stepper_(std::make_unique<Dop853>(ny())) {}
Propagator::~Propagator() = default;

void Propagator::propagate(double t0, double t1, double* y, const Multipliers& mult) {
  const IntegrationTimer timer;
  ++arc_;
  Mode mode = mode_at(y, mult);
  double t = t0;
  double h = std::min(t1 - t0, 1e-3 * (1 + std::fabs(t1 - t0)));
  std::array<double, kMaxNY> f0{}, ynew{}, fnew{};
  std::array<double, 2> g_old{}, g_new{};
  auto rhs = [&](double tt, const double* yy, double* dy) {
    std::array<double, kMaxControls> control{};
    control_in_mode(yy, mode, mult, control.data());
    dynamics(tt, yy, control.data(), mult, dy);
  };
  record(t, y, mode, mult);
  int steps = 0;
  while (t < t1) {
    if (++steps > settings_.max_steps) throw numerical_error("integrator exceeded max_steps");
    h = std::min(h, max_step);
    const bool last = h >= t1 - t;
    if (last) h = t1 - t;
    rhs(t, y, f0.data());
    const double err =
        stepper_->step(rhs, t, y, f0.data(), h, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    if (!(err <= 1.0)) {
      h *= Dop853::step_factor(err);
      if (h < 1e-15 * (1 + std::fabs(t))) throw numerical_error("integrator step size underflow");
      continue;
    }
    const int ng = stay_functions(y, mode, mult, g_old.data());
    stay_functions(ynew.data(), mode, mult, g_new.data());
    int crossed = -1;
    double b = h;  // the switch lies in (0, b] of the step
    for (int k = 0; k < ng; ++k)
      if (g_old[k] >= 0 && g_new[k] < 0) crossed = k;
    if (crossed < 0 && ng > 0) crossed = dip(t, y, f0.data(), h, ynew.data(), fnew.data(), mode, mult, b, g_new);
    if (crossed < 0) {
      t = last ? t1 : t + h;
      std::copy(ynew.begin(), ynew.begin() + ny(), y);
      record(t, y, mode, mult);
      h *= Dop853::step_factor(err);
      continue;
    }
    // Step to the far side of the switch's bracket so the new mode starts past the switch.
    const double hs = locate_switch(rhs, t, y, mode, mult, crossed, g_old[crossed], g_new[crossed], b);
    rhs(t, y, f0.data());
    stepper_->step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    t += hs;
    std::copy(ynew.begin(), ynew.begin() + ny(), y);
    mode = next_mode(mode, crossed, mult);
    record(t, y, mode, mult);
    if (switches) {
      std::array<double, kMaxControls> control{};
      control_in_mode(y, mode, mult, control.data());
      switches->push_back({t, control[kProblem.throttle_index]});
    }
    // The new mode's stay function starts at round-off from 0: a long first step that ends past
    // the next switch would bracket that round-off instead. A short one moves clear of it, and
    // the step control grows the steps again.
    h = 1e-6 * (1 + std::fabs(t1 - t0));
  }
}

// The switch of stay function `crossed` on the frozen-mode step from (t, y), which changes
// sign from ga (at 0) to gb (at b) over the step's length: Illinois regula falsi in the length,
// to round-off. Returns the bracket's far end (past the switch).
template <class Rhs>
double Propagator::locate_switch(Rhs& rhs, double t, const double* y, Mode mode, const Multipliers& mult, int crossed,
                                 double ga, double gb, double b) {
  std::array<double, kMaxNY> f0{}, ynew{}, fnew{};
  std::array<double, 2> g{};
  double a = 0;
  int side = 0;
  for (int it = 0; it < 100 && b - a > 4e-16 * (1 + std::fabs(t)); ++it) {
    double hs = (a * gb - b * ga) / (gb - ga);
    if (!(hs > a && hs < b)) hs = 0.5 * (a + b);
    rhs(t, y, f0.data());
    stepper_->step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    stay_functions(ynew.data(), mode, mult, g.data());
    const double gs = g[crossed];
    if (gs == 0) return hs;
    if ((gs > 0) == (ga > 0)) {
      a = hs;
      ga = gs;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = hs;
      gb = gs;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return b;
}

// A mode that ends and resumes inside one step (a short arc whose switches the step's ends do
// not show; missing it makes the shooting function jump where the arc appears): the stay
// functions on the step's cubic Hermite interpolant at kDipPoints - 1 interior points, and where
// one is negative, the real sub-step there to confirm it. Returns the stay function that
// changes sign (-1: none), with b and g_at_b the sub-step's length and the stay functions at
// its end.
constexpr int kDipPoints = 12;
int Propagator::dip(double t, const double* y, const double* f0, double h, const double* y1, const double* f1,
                    Mode mode, const Multipliers& mult, double& b, std::array<double, 2>& g_at_b) {
  std::array<double, kMaxNY> yi{}, fi{};
  std::array<double, 2> g{};
  for (int j = 1; j < kDipPoints; ++j) {
    const double th = static_cast<double>(j) / kDipPoints, th2 = th * th, th3 = th2 * th;
    const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th, h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
    for (int i = 0, n = ny(); i < n; ++i) yi[i] = h00 * y[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
    const int ng = stay_functions(yi.data(), mode, mult, g.data());
    for (int k = 0; k < ng; ++k) {
      if (g[k] >= 0) continue;
      auto rhs = [&](double tt, const double* yy, double* dy) {
        std::array<double, kMaxControls> control{};
        control_in_mode(yy, mode, mult, control.data());
        dynamics(tt, yy, control.data(), mult, dy);
      };
      stepper_->step(rhs, t, y, f0, th * h, yi.data(), fi.data(), settings_.atol, settings_.rtol);
      stay_functions(yi.data(), mode, mult, g.data());
      if (g[k] < 0) {
        b = th * h;
        g_at_b = g;
        return k;
      }
    }
  }
  return -1;
}

Mode Propagator::next_mode(Mode mode, int crossed, const Multipliers& mult) {
  const bool bang = mult.eps == 0;
  if (mode == kOff) return bang ? kFull : kInterior;
  if (mode == kFull) return bang ? kOff : kInterior;
  return crossed == 0 ? kOff : kFull;
}

void Propagator::record(double t, const double* y, Mode mode, const Multipliers& mult) {
  if (!samples) return;
  Sample s;
  s.arc = arc_;
  s.t = t;
  std::copy(y, y + ny(), s.y.begin());
  control_in_mode(y, mode, mult, s.control.data());
  s.H = hamiltonian(t, y, s.control.data(), mult);
  s.S = switching_value(y, mult);
  samples->push_back(s);
}

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, controls (templates/runtime/controls.hpp): the throttle modes: the
// optimal control in each mode and the functions that stay positive while it holds.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The length of y: states then costates.
inline int ny() {
  return 2 * kProblem.num_states;
}

}  // namespace

Mode mode_at(const double* y, const Multipliers& mult) {
  if (kProblem.throttle_index < 0) {
    return kFull;
  } else {
    double s0 = 0, s1 = 0;
    throttle_slopes(y, mult, s0, s1);
    if (s0 >= 0) return kOff;
    if (s1 <= 0) return kFull;
    return kInterior;
  }
}

void control_in_mode(const double* y, Mode mode, const Multipliers& mult, double* control) {
  direction_control(y, control);
  if (kProblem.throttle_index >= 0) {
    double u = mode == kFull ? 1.0 : 0.0;
    if (mode == kInterior) {
      double s0 = 0, s1 = 0;
      throttle_slopes(y, mult, s0, s1);
      u = std::min(1.0, std::max(0.0, s0 / (s0 - s1)));
    }
    control[kProblem.throttle_index] = u;
  }
}

namespace {

// The switching function at eps = 0 (0 without a throttle), recorded in the trajectory.
inline double switching_value(const double* y, const Multipliers& mult) {
  if (kProblem.throttle_index < 0) {
    return 0.0;
  } else {
    double s0 = 0, s1 = 0;
    throttle_slopes(y, Multipliers{mult.lambda0, 0.0}, s0, s1);
    return s0;
  }
}

// Functions that stay positive while `mode` holds; a sign change is a switch.
inline int stay_functions(const double* y, Mode mode, const Multipliers& mult, double* g) {
  if (kProblem.throttle_index < 0) {
    return 0;
  } else {
    double s0 = 0, s1 = 0;
    throttle_slopes(y, mult, s0, s1);
    switch (mode) {
      case kOff:
        g[0] = s0;
        return 1;
      case kFull:
        g[0] = -s1;
        return 1;
      case kInterior:
        g[0] = -s0;
        g[1] = s1;
        return 2;
    }
    return 0;
  }
}

}  // namespace

}  // namespace helios_rt

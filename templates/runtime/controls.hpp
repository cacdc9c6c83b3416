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

// Whether the spacecraft's mass is constant (no mass state): the program then gives the rate of its
// L1 cost (ProblemShape::throttle_cost_rate).
inline bool constant_mass() {
  return kProblem.throttle_cost_rate != nullptr;
}

// The rate of the L1 (minimum-fuel) cost at full throttle, normalized: with a mass state the mass
// flow Tmax/c (the mass equation's -dm/dt at u = 1), where the problem has a throttle and a mass
// whose flow depends on nothing but the throttle, else 0 (the routes that need it say they do not
// apply); with a constant mass the program's rate, Tmax/c (the propellant it would burn) or Tmax/m
// (the delta-v), read from the parameters so it follows the thrust a route moves (0 at full
// throttle throughout: no throttle to price). The companion
// problem of a minimum-time one prices its throttle by it (fuel_weight). A mass flow is measured
// once at the program's own thrust and followed in proportion to the maximum thrust where the
// search moves it (search/knobs.hpp): the flow is Tmax/c.
// The program's thrust-scale parameters (ProblemShape::thrust_scale; Tmax where it lists none).
inline const std::vector<double*>& thrust_scale_parameters() {
  static const std::vector<double*> out = [] {
    std::vector<double*> found;
    if (kProblem.thrust_scale) {
      for (const char* const* n = kProblem.thrust_scale; *n; ++n)
        if (double* q = scalar_parameter(*n)) found.push_back(q);
    } else if (double* q = scalar_parameter("Tmax")) {
      found.push_back(q);
    }
    return found;
  }();
  return out;
}

// Why the routes that take the full-throttle mass flow for a constant do not apply ("" where they do).
inline const char* varying_flow_reason() {
  return kProblem.mass_flow_varies ? "the mass flow follows the Sun's distance (a solar-electric engine), and the "
                                     "route takes it for a constant"
                                   : "";
}

inline double full_throttle_cost_rate() {
  if (constant_mass()) return kProblem.throttle_index >= 0 ? kProblem.throttle_cost_rate() : 0.0;
  // A flow that follows the position has no rate of its own: 0, and the routes say why (varying_flow_reason).
  if (kProblem.mass_flow_varies) return 0.0;
  // Followed through one thrust-scale parameter with a value (they move together).
  static const double* const thrust = [] {
    for (double* q : thrust_scale_parameters())
      if (*q != 0) return static_cast<const double*>(q);
    return static_cast<const double*>(nullptr);
  }();
  static const double own_thrust = thrust ? *thrust : 1.0;
  static const double flow = [] {
    const int m = kProblem.mass_index, u = kProblem.throttle_index;
    if (m < 0 || u < 0) return 0.0;
    const auto flow_at = [&](double mass, double position) {
      std::array<double, kMaxNY> y{}, dy{};
      std::array<double, kMaxControls> control{};
      y[0] = position;
      y[1] = 0.25 * position;
      y[4] = 1 / std::sqrt(position);
      y[m] = mass;
      control[u] = 1;
      dynamics(0.0, y.data(), control.data(), Multipliers{0.0, 0.0}, dy.data());
      return -dy[m];
    };
    const double a = flow_at(1.0, 1.0), b = flow_at(0.5, 2.0);
    return std::isfinite(a) && a > 0 && a == b ? a : 0.0;
  }();
  return thrust && own_thrust > 0 ? flow * (*thrust / own_thrust) : flow;
}

// The time full throttle takes to burn the whole initial mass (normalized; the initial mass is the
// mass unit): infinite for an engine of constant mass, and where the throttle has no mass flow of
// its own (a solar-electric engine's flow follows the distance: no burnout is known).
inline double burnout_time() {
  const double flow = constant_mass() ? 0.0 : full_throttle_cost_rate();
  return flow > 0 ? 1 / flow : INFINITY;
}

// Whether the throttle has a fuel cost: with a mass state, whose flow is the throttle's at a rate of
// its own or following the Sun's distance (a solar-electric engine); at a constant mass, the L1
// cost's rate. The routes that continue a minimum-fuel extremal in its final time need only this,
// not the rate.
inline bool throttle_has_fuel_cost() {
  if (constant_mass() || !kProblem.mass_flow_varies) return full_throttle_cost_rate() > 0;
  return kProblem.mass_index >= 0 && kProblem.throttle_index >= 0;
}

// The minimum-fuel cost of an engine of constant mass is the delta-v (no exhaust velocity prices it
// in propellant).
inline bool cost_is_delta_v() {
  return constant_mass() && !(kProblem.exhaust_velocity_m_s > 0);
}

// dH/du at u = 0 and u = 1 (the SWITCH module's throttle_slopes), with the companion's price of
// the throttle: w lambda0 (Tmax/c)(1 - eps + 2 eps u) more (w = mult.fuel_weight, 0 in the
// problem itself).
inline void slopes(const double* y, const Multipliers& mult, double& s0, double& s1) {
  kModules.throttle_slopes(y, mult, s0, s1);
  if (mult.fuel_weight != 0) {
    const double price = mult.fuel_weight * mult.lambda0 * full_throttle_cost_rate();
    s0 += price * (1 - mult.eps);
    s1 += price * (1 + mult.eps);
  }
}

// Their derivatives in z = (y, lambda0) (the JACOBIAN module's throttle_slopes_jacobian), the
// companion's price in the lambda0 column.
inline void slopes_jacobian(const double* y, const Multipliers& mult, double* d0, double* d1) {
  kModules.throttle_slopes_jacobian(y, mult, d0, d1);
  if (mult.fuel_weight != 0) {
    const double price = mult.fuel_weight * full_throttle_cost_rate();
    d0[ny()] += price * (1 - mult.eps);
    d1[ny()] += price * (1 + mult.eps);
  }
}

}  // namespace

Mode mode_at(const double* y, const Multipliers& mult) {
  if (kProblem.throttle_index < 0) {
    return kFull;
  } else {
    double s0 = 0, s1 = 0;
    slopes(y, mult, s0, s1);
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
      slopes(y, mult, s0, s1);
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
    slopes(y, Multipliers{mult.lambda0, 0.0, mult.fuel_weight}, s0, s1);
    return s0;
  }
}

// Functions that stay positive while `mode` holds; a sign change is a switch.
inline int stay_functions(const double* y, Mode mode, const Multipliers& mult, double* g) {
  if (kProblem.throttle_index < 0) {
    return 0;
  } else {
    double s0 = 0, s1 = 0;
    slopes(y, mult, s0, s1);
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

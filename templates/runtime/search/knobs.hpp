// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the program's knobs (templates/runtime/search/knobs.hpp): the one
// object that owns what the routes of the search move in the program: its maximum thrust and its
// final time (or the final time's window), which are the program's parameters (parameters.hpp),
// shared by its threads. Routes that move them run alone, one path after the other, and the knobs
// put the problem's own values back when they go. Also the handles the routes find by the
// derivation's names: the free final time's variable and row, and lambda0's variable.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The free times whose shooting variable is a fraction of a window (t0_frac: the departure's,
// tf_frac: the final time's, tf = tf_min + (tf_max - tf_min) tf_frac) with their transversality
// rows (transversality_t0, transversality_tf: H(tf) + dPhi/dtf = 0), by the derivation's names.
struct TimeWindow {
  int variable = -1, row = -1;
  const char* time = "";  // "t0" or "tf"
};
inline const std::vector<TimeWindow>& time_windows() {
  static const std::vector<TimeWindow> windows = [] {
    std::vector<TimeWindow> out;
    for (const char* time : {"t0", "tf"}) {
      TimeWindow w;
      w.time = time;
      for (int i = 0; i < kProblem.num_vars; ++i) {
        if (std::string(kProblem.variable_names[i]) == std::string(time) + "_frac") w.variable = i;
        if (std::string(kProblem.equation_names[i]) == std::string("transversality_") + time) w.row = i;
      }
      if (w.variable >= 0 && w.row >= 0) out.push_back(w);
    }
    return out;
  }();
  return windows;
}

// The free final time's window (variable and row -1 where the final time is not free).
inline TimeWindow free_final_time() {
  for (const TimeWindow& w : time_windows())
    if (w.time == std::string("tf")) return w;
  return {};
}

// The index of the shooting variable lambda0 (-1: none).
inline int lambda0_variable() {
  for (int i = 0; i < kProblem.num_vars; ++i)
    if (std::string(kProblem.variable_names[i]) == "lambda0") return i;
  return -1;
}

// Whether the problem's targets stay put on the calendar: no epoch, no body on an orbit, no
// coasting target. Only then does a changed thrust or final time leave the transfer the same
// problem (a moving target would be met elsewhere).
inline bool targets_fixed_in_time() {
  return kProblem.epoch_mjd2000 == 0 && kProblem.num_orbit_bodies == 0 && kModules.coast_dynamics == nullptr;
}

class ProgramKnobs {
 public:
  ProgramKnobs()
      : thrust_(thrust_scale_parameters()), tf_(scalar_parameter("kTf")), tf_min_(scalar_parameter("kTfMin")) {
    for (double* q : thrust_) thrust0_.push_back(*q);
    own_thrust_ = reference_thrust();
    if (tf_) tf0_ = own_tf_ = *tf_;
    if (tf_min_) tf_min0_ = *tf_min_;
    full_throttle_cost_rate();  // measured at the problem's own thrust, before any route moves it
  }
  ~ProgramKnobs() { reset_base(); }
  ProgramKnobs(const ProgramKnobs&) = delete;
  ProgramKnobs& operator=(const ProgramKnobs&) = delete;

  // Whether the program has a maximum thrust to scale with its final time (or window).
  bool thrust_scalable() const { return !thrust_.empty() && tf_ && (tf_min_ || free_final_time().variable < 0); }
  // Whether the program's final time is a parameter.
  bool final_time_movable() const { return tf_ != nullptr; }

  // The problem at Tmax e^sigma, its final time (or window) scaled by e^-sigma: a transfer at full
  // thrust takes a time nearly inversely proportional to the thrust.
  void scale_thrust(double sigma) {
    sigma_ = sigma;
    for (std::size_t k = 0; k < thrust_.size(); ++k) *thrust_[k] = thrust0_[k] * std::exp(sigma);
    *tf_ = tf0_ * std::exp(-sigma);
    if (tf_min_) *tf_min_ = tf_min0_ * std::exp(-sigma);
  }
  double sigma() const { return sigma_; }
  // The maximum thrust at sigma in newtons (a solar-electric engine's at one length unit, 1 AU).
  double thrust_N(double sigma) const {
    const double time_unit_s = kProblem.time_unit_days * 86400.0;
    return own_thrust_ * std::exp(sigma) * kProblem.mass_unit_kg * kProblem.length_unit_km * 1e3 /
           (time_unit_s * time_unit_s);
  }
  double own_thrust_N() const { return thrust_N(0); }

  // The final time (or the window's end) moved from the problem's own to `tf` as the base the
  // thrust scaling and restore() start from (the bound route, bound.hpp, opens the window so);
  // back to the problem's own with reset_base().
  void open_final_time(double tf) {
    tf0_ = tf;
    restore();
  }
  void reset_base() {
    tf0_ = own_tf_;
    restore();
  }
  bool opened() const { return tf0_ != own_tf_; }

  // The problem's final time (or window's end) at the current thrust scaling from its base (the
  // unit of set_final_fraction), and the program's final time put at `tf` or at a fraction s of
  // the unit.
  double final_time_unit() const { return tf0_ * std::exp(-sigma_); }
  void set_final_time(double tf) { *tf_ = tf; }
  void set_final_fraction(double s) { *tf_ = s * final_time_unit(); }
  double final_time() const { return *tf_; }
  // Back to the current scaling's final time.
  void reset_final_time() { *tf_ = final_time_unit(); }

  // The problem's own thrust, and its final time (or window) at the base.
  void restore() {
    sigma_ = 0;
    for (std::size_t k = 0; k < thrust_.size(); ++k) *thrust_[k] = thrust0_[k];
    if (tf_) *tf_ = tf0_;
    if (tf_min_) *tf_min_ = tf_min0_;
  }

 private:
  // The program's own thrust (normalized): Tmax, or where the thrust follows the position its value
  // at (1, 0, 0), one length unit from the centre: the full throttle's mass flow there times the
  // exhaust velocity, or without one (an engine given by fits) the mass times the acceleration the
  // full throttle adds to the coast's, its direction the control law's for lambda_v = (-1, 0, 0).
  static double reference_thrust() {
    if (const double* tmax = scalar_parameter("Tmax")) return *tmax;
    const int m = kProblem.mass_index, u = kProblem.throttle_index;
    if (m < 0 || u < 0) return 0;
    std::array<double, kMaxNY> y{}, full{}, coast{};
    std::array<double, kMaxControls> control{};
    y[0] = 1;
    y[4] = 1;
    y[m] = 1;
    y[kProblem.num_states + 3] = -1;
    const Multipliers mult{0.0, 0.0};
    control_in_mode(y.data(), kFull, mult, control.data());
    dynamics(0.0, y.data(), control.data(), mult, full.data());
    const double c = kProblem.exhaust_velocity_m_s / (kProblem.speed_unit_km_s * 1e3);
    if (c > 0) return -full[m] * c;
    control_in_mode(y.data(), kOff, mult, control.data());
    dynamics(0.0, y.data(), control.data(), mult, coast.data());
    const double thrust = std::hypot(full[3] - coast[3], full[4] - coast[4], full[5] - coast[5]);
    return std::isfinite(thrust) ? thrust : 0;
  }

  std::vector<double*> thrust_;
  std::vector<double> thrust0_;
  double *tf_ = nullptr, *tf_min_ = nullptr;
  double own_thrust_ = 0, tf0_ = 0, own_tf_ = 0, tf_min0_ = 0, sigma_ = 0;
};

}  // namespace

}  // namespace helios_rt

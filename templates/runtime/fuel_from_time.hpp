// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, minimum fuel from minimum time (templates/runtime/fuel_from_time.hpp):
// a minimum-fuel problem at a fixed final time solved from its minimum-time extremal.
// ---------------------------------------------------------------------------------------------
// Below the shortest final time t_min at which the transfer is possible there is none; at t_min
// the only admissible control is full thrust, and the minimum-fuel extremal there is abnormal
// (lambda0 = 0): its costates are those of the minimum-time extremal (whose own cost multiplier
// enters only its H(tf) row, not the control). As the final time grows from t_min, coasting arcs
// open and lambda0 grows. So the minimum-fuel extremals at a fixed time form families that start at
// the minimum-time extremals; the one continued from the minimum-time optimum is the natural
// candidate (Caillau, Gergaud and Noailles on the GTO to GEO transfer), and it does not depend on a
// random start landing in a small basin.
//
// The shooting function of the fuel problem serves both ends. With lambda0 held at a and the final
// time free in lambda0's slot (tf = s tf_unit: the held-multiplier system), its solutions at a = 0
// are the minimum-time extremals and at a > 0 minimum-fuel extremals at the final time they reach.
// The route, for a fuel problem whose targets do not move on the calendar:
//   1. from a minimum-fuel solution at eps_start, the final time is continued down (lambda0 free)
//      until no shorter one converges, and the minimum-time extremal is solved there (a = 0);
//   2. from it, a is continued up from 0 at eps_start while coasting arcs open, then the final time
//      itself (lambda0 free) up to the problem's;
//   3. there eps is continued to 0: an extremal of the problem.
// The final time is the program's parameter kTf: one path at a time (the search runs it alone).
#pragma once

namespace helios_rt {

namespace {

// The stages of the route's steps (solution.json's continuation; schemas/solution.schema.json).
constexpr const char* kFinalTimeDown = "minimum fuel, the final time down [days]";
constexpr const char* kMinimumTime = "minimum time (lambda0 = 0), the final time free [days]";
constexpr const char* kLambda0Held = "lambda0 held, the final time free (lambda0)";
constexpr const char* kFinalTimeUp = "minimum fuel, the final time up [days]";

// The index of the shooting variable lambda0 (-1: none).
inline int lambda0_variable() {
  for (int i = 0; i < kProblem.num_vars; ++i)
    if (std::string(kProblem.variable_names[i]) == "lambda0") return i;
  return -1;
}

// Whether the problem has the route: minimum propellant at a fixed final time (a parameter), with
// a throttle that burns mass and lambda0 a variable, and targets that do not move on the calendar
// (no epoch, no body on an orbit, no coasting target: a final time moved elsewhere would meet them
// elsewhere).
inline bool has_time_route() {
  return kProblem.objective == Objective::propellant && free_final_time().variable < 0 && full_mass_flow() > 0 &&
         lambda0_variable() >= 0 && scalar_parameter("kTf") != nullptr && kProblem.epoch_mjd2000 == 0 &&
         kProblem.num_orbit_bodies == 0 && kModules.coast_dynamics == nullptr;
}

// The program's final time: its unit (the problem's final time at the current thrust scaling, the
// parameter's own value unless the thrust is raised), where the paths set it, and its own value
// restored when the route ends.
class FinalTime {
 public:
  FinalTime() : tf_(scalar_parameter("kTf")), own_(*tf_), unit_(own_) {}
  ~FinalTime() { *tf_ = own_; }
  FinalTime(const FinalTime&) = delete;
  FinalTime& operator=(const FinalTime&) = delete;
  void set(double tf) const { *tf_ = tf; }
  double own() const { return own_; }
  double unit() const { return unit_; }
  // The problem's final time scaled with the thrust (thrust_continuation.hpp: by e^-sigma).
  void rescale(double sigma) {
    unit_ = own_ * std::exp(-sigma);
    *tf_ = unit_;
  }

 private:
  double* tf_;
  double own_, unit_;
};

// The held-multiplier system: the shooting function with lambda0 held at `held` and, in lambda0's
// slot, the final time as a fraction s of the problem's (tf = s tf.unit()); dF/ds by a difference.
inline Function held_multiplier_function(const FinalTime& tf, int l0, const double& held) {
  return [&tf, l0, &held](const double* z, double eps, Propagator& prop, double* F, double* J) {
    const int N = kProblem.num_vars;
    std::vector<double> x(z, z + N);
    const double s = x[l0];
    x[l0] = held;
    tf.set(s * tf.unit());
    shooting_function_and_jacobian(x.data(), eps, prop, F, J);
    if (J) {
      std::vector<double> shifted(static_cast<std::size_t>(N));
      const double h = 1e-7 * std::max(1.0, std::fabs(s));
      tf.set((s + h) * tf.unit());
      shooting_function_and_jacobian(x.data(), eps, prop, shifted.data(), nullptr);
      for (int i = 0; i < N; ++i) J[i + l0 * N] = (shifted[i] - F[i]) / h;
      tf.set(s * tf.unit());
    }
  };
}

// What the route reached from one fuel solution: the minimum-time extremal (its final time in the
// problem's normalized units, NaN where step 1 failed) and the extremal at eps = 0 of step 3.
struct TimeRouteArrival : PathArrival {
  double tf_min = NAN;
  std::vector<HomotopyStep> homotopy;  // eps from eps_start to 0 at the problem's final time
};

// Step 1 from the fuel solution x (at eps_start, the problem's final time): the minimum-time
// extremal as held-multiplier variables z (s in lambda0's slot); false where it was not reached.
inline bool minimum_time_from_fuel_solution(const Settings& s, const FinalTime& tf, std::vector<double> x, double eps,
                                            std::vector<double>& z, TimeRouteArrival& out, int& evaluations) {
  const int l0 = lambda0_variable();
  Shooter fuel(s, kContinuationStart);
  const double day = 1 / kProblem.time_unit_days, own_days = tf.unit() / day;
  const double reached = day * follow_parameter(
                                   s, fuel, x, eps, [&](double days) { tf.set(days * day); }, own_days, 0.0,
                                   -1e-7 * own_days, {0.05 * own_days, 1e-4 * own_days, 0.2 * own_days}, kFinalTimeDown,
                                   out.steps, [&](const std::vector<double>& y) { return y[l0] >= 0; },
                                   [](const std::vector<double>&) { return false; });
  evaluations += fuel.evaluations;
  const double held = 0;
  Shooter time(s, held_multiplier_function(tf, l0, held), kContinuationStart);
  z = x;
  z[l0] = reached / tf.unit();
  int info = 0;
  double res = 0;
  const bool ok = time.solve(z, 0.0, s.accept_residual, info, res) && z[l0] > 0;
  out.steps.push_back({kMinimumTime, z[l0] * tf.unit() * kProblem.time_unit_days, ok, res, time.last_step_evaluations});
  evaluations += time.evaluations;
  if (ok) out.tf_min = z[l0] * tf.unit();
  tf.set(tf.unit());
  return ok;
}

// The revolutions of the minimum-time extremal z (held-multiplier variables).
inline double minimum_time_revolutions(const Settings& s, const FinalTime& tf, const std::vector<double>& z) {
  const int l0 = lambda0_variable();
  std::vector<double> x = z;
  x[l0] = 0;
  tf.set(z[l0] * tf.unit());
  const double revolutions = shape_of(s, x, 0.0).revolutions;
  tf.set(tf.unit());
  return revolutions;
}

// Steps 2 and 3 from the minimum-time extremal z, at eps_start (the smooth problem every start is
// solved at: at eps = 0 the path stalls where a coasting arc is born): lambda0 held at a, continued
// up from 0 until coasting has lengthened the flight by kOpening of what separates it from the
// problem's final time (s(a) is flat while the thrust stays full, then rises, and may fold back: a
// is a parameter only near the start); then the final time itself, lambda0 free, up to the
// problem's; there eps is continued down to 0 (homotopy_to_zero).
template <class Admissible>
void fuel_path_from_minimum_time(const Settings& s, const FinalTime& tf, std::vector<double> z, Admissible& admissible,
                                 TimeRouteArrival& out, int& evaluations) {
  constexpr double kOpening = 0.02;
  const int l0 = lambda0_variable();
  const double eps = s.eps_start, opened = z[l0] + kOpening * (1 - z[l0]);
  double held = 0;
  Shooter opening(s, held_multiplier_function(tf, l0, held), kContinuationStart);
  const double a = follow_parameter(
      s, opening, z, eps, [&](double v) { held = v; }, 0.0, 0.999, 1e-7, {1e-3, 1e-7, 0.05}, kLambda0Held, out.steps,
      [&](const std::vector<double>& y) { return y[l0] > 0; },
      [&](const std::vector<double>& y) { return y[l0] >= opened; });
  evaluations += opening.evaluations;
  if (!(z[l0] >= opened) || z[l0] > 1) {
    tf.set(tf.unit());
    return;
  }
  Shooter itself(s, kContinuationStart);
  std::vector<double> x = z;
  x[l0] = a;
  const double day = 1 / kProblem.time_unit_days, own_days = tf.unit() / day, from_days = z[l0] * own_days;
  tf.set(from_days * day);
  const double reached_days = follow_parameter(
      s, itself, x, eps, [&](double days) { tf.set(days * day); }, from_days, own_days, 1e-7 * own_days,
      {0.02 * own_days, 1e-5 * own_days, 0.2 * own_days}, kFinalTimeUp, out.steps,
      [&](const std::vector<double>& y) { return y[l0] > 0; }, [](const std::vector<double>&) { return false; });
  tf.set(tf.unit());
  if (reached_days == own_days) {
    Result path;
    double res = 0;
    out.arrived = homotopy_to_zero(
        s, itself, x, path, [&](const double* y) { return admissible(y); }, res);
    out.homotopy = path.homotopy;
    if (out.arrived) {
      out.x = x;
      out.F = itself.last_F;
      out.max_residual = res;
      out.info = path.info;
    }
  }
  evaluations += itself.evaluations;
}

}  // namespace

}  // namespace helios_rt

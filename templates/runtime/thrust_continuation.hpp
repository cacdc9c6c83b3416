// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, thrust continuation (templates/runtime/thrust_continuation.hpp): a
// many-revolution transfer reached from a few-revolution one along the maximum thrust.
// ---------------------------------------------------------------------------------------------
// At low thrust a transfer winds many times about the central body, the shooting function's basin
// shrinks with the revolutions, and random starts find poor extremals or none. At a higher thrust
// the same transfer takes few revolutions, where the search is reliable. The problem family
//   Tmax(sigma) = Tmax e^sigma,   the final time's window [tf_min, tf] e^-sigma,
// (a transfer at full thrust takes a time close to inversely proportional to the thrust, so its
// final time keeps its place in the scaled window) is the problem itself at sigma = 0. The search
// (search.hpp) raises the thrust until its own search there returns an extremal of few
// revolutions, then continues its best extremals down to sigma = 0 (continue_thrust_down), the
// revolutions recorded at every step. The parameters are the program's globals, shared by its
// threads: the continuation runs alone, one path after the other.
#pragma once

namespace helios_rt {

namespace {

// A transfer of at most this many revolutions is "few": where the search is started from.
constexpr double kFewRevolutions = 2.5;
// The most doublings of the thrust tried.
constexpr int kMaxThrustDoublings = 8;
// The most extremals of the search at the raised thrust continued down.
constexpr int kThrustBranches = 3;

// The program's parameters the continuation scales: the maximum thrust and the final time's
// window, with their own values (sigma = 0).
class ThrustScaling {
 public:
  ThrustScaling()
      : thrust_(scalar_parameter("Tmax")), tf_(scalar_parameter("kTf")), tf_min_(scalar_parameter("kTfMin")) {
    if (*this) thrust0_ = *thrust_, tf0_ = *tf_, tf_min0_ = *tf_min_;
  }
  // Whether the program has a maximum thrust to scale.
  explicit operator bool() const { return thrust_ && tf_ && tf_min_; }
  // The problem at Tmax e^sigma, its final time's window scaled by e^-sigma.
  void set(double sigma) const {
    *thrust_ = thrust0_ * std::exp(sigma);
    *tf_ = tf0_ * std::exp(-sigma);
    *tf_min_ = tf_min0_ * std::exp(-sigma);
  }
  // The maximum thrust at sigma in newtons.
  double thrust_N(double sigma) const {
    const double time_unit_s = kProblem.time_unit_days * 86400.0;
    return thrust0_ * std::exp(sigma) * kProblem.mass_unit_kg * kProblem.length_unit_km * 1e3 /
           (time_unit_s * time_unit_s);
  }

 private:
  double *thrust_ = nullptr, *tf_ = nullptr, *tf_min_ = nullptr;
  double thrust0_ = 0, tf0_ = 0, tf_min0_ = 0;
};

// From the solution x (eps = 0) at `sigma0` down to sigma = 0: at each step a tangent predictor
// (dx/dsigma = -J^-1 dF/dsigma) and hybrd from it; a step that fails is retried from predictions
// perturbed at random (relative scales 1e-3 to 1e-1, kThrustRetries of them) before it is halved,
// so that where the branch being followed turns back (a fold: below some thrust the extremal of
// that shape no longer exists) the continuation goes on on a neighbouring one; it stops when the
// step falls below 1e-3 in sigma. The revolutions of every solution reached are recorded (a jump
// shows a change of branch). The scaling is set to sigma0 first and left at the last sigma reached
// (the caller restores it). `along` is the system followed: the shooting function itself by
// default, or another with the same variables (fuel_from_time.hpp's minimum-time system), whose
// own parameters `along.set` moves with sigma and whose revolutions `along.revolutions` tells.
struct ThrustPath {
  Function function = shooting_function_and_jacobian;
  std::function<void(double sigma)> set;
  std::function<double(const std::vector<double>& x)> revolutions;
};
template <class Admissible>
PathArrival continue_thrust_down(const Settings& s, const ThrustScaling& scaling, std::vector<double> x,
                                   double sigma0, Admissible& admissible, int& evaluations, double deadline,
                                   const ThrustPath& along = {}) {
  constexpr int kThrustRetries = 8;
  PathArrival out;
  Shooter shooter(s, along.function, kContinuationStart);
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double sigma = sigma0, step = std::min(0.25, sigma0);
  std::vector<double> tangent;
  const auto set = [&](double v) {
    scaling.set(v);
    if (along.set) along.set(v);
  };
  set(sigma);
  // dx/dsigma at the current point, dF/dsigma by a difference over 1e-7.
  const auto predict = [&] { return parameter_tangent(shooter, x, 0.0, set, sigma, 1e-7, tangent); };
  bool predicted = predict();
  while (sigma > 0 && wall_seconds() < deadline) {
    const double next = std::max(0.0, sigma - step);
    set(next);
    std::vector<double> trial;
    bool ok = false;
    for (int attempt = 0; attempt <= kThrustRetries && !ok && wall_seconds() < deadline; ++attempt) {
      trial = x;
      if (predicted)
        for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent[i] * (next - sigma);
      if (attempt > 0) {
        const double scale = std::pow(10.0, -3.0 + 2.0 * (attempt - 1) / std::max(1, kThrustRetries - 1));
        for (double& v : trial) v *= 1 + scale * unit(rng);
      }
      int info = 0;
      double res = 0;
      // Every step at the search's acceptance; the search polishes the arrival at final_residual.
      ok = shooter.solve(trial, 0.0, s.accept_residual, info, res) && admissible(trial.data());
      ContinuationStep record{"maximum thrust [N], the final time's window scaled inversely", scaling.thrust_N(next),
                              ok, res, shooter.last_step_evaluations};
      if (ok) {
        record.revolutions = along.revolutions ? along.revolutions(trial) : shape_of(s, trial, 0.0).revolutions;
        out.info = info;
        out.max_residual = res;
      }
      out.steps.push_back(record);
    }
    if (!ok) {
      set(sigma);
      step *= 0.5;
      if (step < 1e-3) break;
      continue;
    }
    x = trial;
    sigma = next;
    step = std::min(step * 1.5, 0.5);
    if (sigma > 0) predicted = predict();
  }
  evaluations += shooter.evaluations;
  if (sigma == 0) {
    out.arrived = true;
    out.x = x;
    out.F = shooter.last_F;
  }
  return out;
}

}  // namespace

}  // namespace helios_rt

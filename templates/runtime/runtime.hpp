// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime (templates/runtime/runtime.hpp): the fixed part of every generated
// shooting program. It needs the PROBLEM block (namespace problem) before it and the modules
// DYNAMICS, SWITCH, RESIDUAL and SOLVE after it (their prototypes are below).
//
// Numerics (design.md section 6): normalized units; an adaptive DOP853 integrator whose control
// mode (throttle off / interior / full) is frozen inside each step, with the switching times
// located to round-off so the shooting function stays smooth at eps = 0; eps-homotopy from
// eps = 1 with adaptive steps and retreat; seeded random restarts; cminpack hybrd1.
// ---------------------------------------------------------------------------------------------
namespace helios_rt {

constexpr int kNY = 2 * problem::kNumStates;  // states then costates

struct Multipliers {
  double lambda0 = 1;
  double eps = 1;
};

// DYNAMICS module: state and costate right-hand sides and H at time t for a given control vector.
void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy);
double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult);
// SWITCH module: the continuous controls (all but the throttle) and dH/du at u = 0 and u = 1.
// A problem without a throttle (kThrottleIndex < 0) has one mode and no throttle_slopes.
void direction_control(const double* y, double* control);
void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper);

// Throttle modes. With eps > 0, H is strictly convex in u: u = 0 where dH/du(0) >= 0, u = 1 where
// dH/du(1) <= 0, otherwise u solves dH/du = 0. At eps = 0 both slopes equal the switching function.
enum Mode { kOff = 0, kInterior = 1, kFull = 2 };

inline Mode mode_at(const double* y, const Multipliers& mult) {
  if constexpr (problem::kThrottleIndex < 0) {
    return kFull;
  } else {
    double s0 = 0, s1 = 0;
    throttle_slopes(y, mult, s0, s1);
    if (s0 >= 0) return kOff;
    if (s1 <= 0) return kFull;
    return kInterior;
  }
}

inline void control_in_mode(const double* y, Mode mode, const Multipliers& mult, double* control) {
  direction_control(y, control);
  if constexpr (problem::kThrottleIndex >= 0) {
    double u = mode == kFull ? 1.0 : 0.0;
    if (mode == kInterior) {
      double s0 = 0, s1 = 0;
      throttle_slopes(y, mult, s0, s1);
      u = std::min(1.0, std::max(0.0, s0 / (s0 - s1)));
    }
    control[problem::kThrottleIndex] = u;
  }
}

// The switching function at eps = 0 (0 without a throttle), recorded in the trajectory.
inline double switching_value(const double* y, const Multipliers& mult) {
  if constexpr (problem::kThrottleIndex < 0) {
    return 0.0;
  } else {
    double s0 = 0, s1 = 0;
    throttle_slopes(y, Multipliers{mult.lambda0, 0.0}, s0, s1);
    return s0;
  }
}

// Functions that stay positive while `mode` holds; a sign change is a switch.
inline int stay_functions(const double* y, Mode mode, const Multipliers& mult, double* g) {
  if constexpr (problem::kThrottleIndex < 0) {
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

// Ephemeris mode "jpl_lp": a planet's heliocentric state at normalized time t after the epoch of
// t0, in normalized units.
// A body of problem::kOrbitBodies is propagated on its Keplerian orbit instead.
inline std::array<double, 6> ephemeris_state(const std::string& body, double t) {
  for (const auto& b : problem::kOrbitBodies)
    if (body == b.name)
      return helios::astro::propagate(helios::astro::elements_to_state(b.elements, problem::mu), t - b.epoch,
                                      problem::mu);
  const auto s = helios::astro::jpl_lp_state(helios::astro::planet_from_name(body),
                                             problem::kEpochMjd2000 + t * problem::kTimeUnitDays);
  return {s[0] / problem::kLengthUnitKm, s[1] / problem::kLengthUnitKm, s[2] / problem::kLengthUnitKm,
          s[3] / problem::kSpeedUnitKmS, s[4] / problem::kSpeedUnitKmS, s[5] / problem::kSpeedUnitKmS};
}

// Time derivative of the ephemeris model itself, as a free event time's transversality condition
// needs. A body of problem::kOrbitBodies moves exactly on its Kepler orbit: (v, -mu r/|r|^3). A
// JPL low-precision planet's elements drift, so its rate is not the Kepler velocity the model
// reports: a fourth-order central difference.
inline std::array<double, 6> ephemeris_rate(const std::string& body, double t) {
  for (const auto& b : problem::kOrbitBodies)
    if (body == b.name) {
      const auto s = ephemeris_state(body, t);
      const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), k = -problem::mu / (r * r * r);
      return {s[3], s[4], s[5], k * s[0], k * s[1], k * s[2]};
    }
  const double h = 1e-3 / problem::kTimeUnitDays;  // 1e-3 day: truncation ~1e-13, round-off ~1e-12
  const auto p1 = ephemeris_state(body, t + h), m1 = ephemeris_state(body, t - h);
  const auto p2 = ephemeris_state(body, t + 2 * h), m2 = ephemeris_state(body, t - 2 * h);
  std::array<double, 6> d{};
  for (int i = 0; i < 6; ++i) d[i] = (8 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12 * h);
  return d;
}

struct numerical_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Unpowered dynamics of a coasting target (generated when the problem has one).
void coast_dynamics(const double* y, double* dy);

// A coasting target's state at t1 from its state y0 at t0, integrated to 1e-14.
inline std::array<double, 6> coast_state(const std::array<double, 6>& y0, double t0, double t1) {
  Dop853 stepper(6);
  std::array<double, 6> y = y0, f0{}, ynew{}, fnew{};
  auto rhs = [](double, const double* yy, double* dy) { coast_dynamics(yy, dy); };
  double t = t0, h = 1e-3 * (1 + std::fabs(t1 - t0));
  const double direction = t1 >= t0 ? 1.0 : -1.0;
  for (int steps = 0; direction * (t1 - t) > 0; ++steps) {
    if (steps > 1000000) throw numerical_error("coasting target: integrator exceeded its step budget");
    const bool last = h >= direction * (t1 - t);
    const double step = last ? t1 - t : direction * h;
    rhs(t, y.data(), f0.data());
    const double err = stepper.step(rhs, t, y.data(), f0.data(), step, ynew.data(), fnew.data(), 1e-14, 1e-14);
    if (!(err <= 1.0)) {
      h *= Dop853::step_factor(err);
      if (h < 1e-15 * (1 + std::fabs(t))) throw numerical_error("coasting target: step size underflow");
      continue;
    }
    t = last ? t1 : t + step;
    y = ynew;
    h *= Dop853::step_factor(err);
  }
  return y;
}

struct Settings {
  unsigned seed = 1;
  int max_attempts = 200;
  double time_limit_s = 600;
  double rtol = 1e-13, atol = 1e-13;
  double hybrd_tol = 1e-12;
  double accept_residual = 1e-8;  // intermediate homotopy steps
  double final_residual = 1e-10;  // the gate at eps = 0
  double eps_start = problem::kHomotopyStart;
  double eps_min = 1e-6;  // below this the next step is eps = 0
  double eps_first_ratio = 0.5;
  int leg_attempts = 20;  // random guesses per leg before the attempt is abandoned
  int max_steps = 200000;  // integrator steps per arc
};

struct Sample {
  int arc;  // samples of one propagate() call share an arc; H may jump only between arcs
  double t;
  std::array<double, kNY> y;
  std::array<double, problem::kNumControls> control;
  double H, S;
};

struct Switch {
  double t;
  double throttle_after;
};

inline double wall_seconds() {
  using clock = std::chrono::steady_clock;
  static const auto start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}

// Integrates y from t0 to t1 under the optimal control, one mode at a time.
class Propagator {
 public:
  explicit Propagator(const Settings& s) : settings_(s), stepper_(kNY) {}

  std::vector<Sample>* samples = nullptr;  // when set, every accepted step is recorded
  std::vector<Switch>* switches = nullptr;
  double max_step = INFINITY;  // limits steps when recording, for smooth plots

  void propagate(double t0, double t1, double* y, const Multipliers& mult) {
    ++arc_;
    Mode mode = mode_at(y, mult);
    double t = t0;
    double h = std::min(t1 - t0, 1e-3 * (1 + std::fabs(t1 - t0)));
    std::array<double, kNY> f0{}, ynew{}, fnew{};
    std::array<double, 2> g_old{}, g_new{};
    auto rhs = [&](double tt, const double* yy, double* dy) {
      std::array<double, problem::kNumControls> control{};
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
          stepper_.step(rhs, t, y, f0.data(), h, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
      if (!(err <= 1.0)) {
        h *= Dop853::step_factor(err);
        if (h < 1e-15 * (1 + std::fabs(t))) throw numerical_error("integrator step size underflow");
        continue;
      }
      const int ng = stay_functions(y, mode, mult, g_old.data());
      stay_functions(ynew.data(), mode, mult, g_new.data());
      int crossed = -1;
      for (int k = 0; k < ng; ++k)
        if (g_old[k] >= 0 && g_new[k] < 0) crossed = k;
      if (crossed < 0) {
        t = last ? t1 : t + h;
        std::copy(ynew.begin(), ynew.end(), y);
        record(t, y, mode, mult);
        h *= Dop853::step_factor(err);
        continue;
      }
      // Locate the switch on the frozen-mode step (Illinois regula falsi in the step length).
      double a = 0, b = h, ga = g_old[crossed], gb = g_new[crossed];
      double hs = b;
      int side = 0;
      for (int it = 0; it < 100 && b - a > 4e-16 * (1 + std::fabs(t)); ++it) {
        hs = (a * gb - b * ga) / (gb - ga);
        if (!(hs > a && hs < b)) hs = 0.5 * (a + b);
        rhs(t, y, f0.data());
        stepper_.step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
        stay_functions(ynew.data(), mode, mult, g_new.data());
        const double gs = g_new[crossed];
        if (gs == 0) {
          a = b = hs;
          break;
        }
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
      // Step to the far side of the bracket so the new mode starts past the switch.
      hs = b;
      rhs(t, y, f0.data());
      stepper_.step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
      t += hs;
      std::copy(ynew.begin(), ynew.end(), y);
      mode = next_mode(mode, crossed, mult);
      record(t, y, mode, mult);
      if (switches) {
        std::array<double, problem::kNumControls> control{};
        control_in_mode(y, mode, mult, control.data());
        switches->push_back({t, control[problem::kThrottleIndex]});
      }
      h = std::max(h - hs, 1e-6 * (1 + std::fabs(t1 - t0)));
    }
  }

 private:
  static Mode next_mode(Mode mode, int crossed, const Multipliers& mult) {
    const bool bang = mult.eps == 0;
    if (mode == kOff) return bang ? kFull : kInterior;
    if (mode == kFull) return bang ? kOff : kInterior;
    return crossed == 0 ? kOff : kFull;
  }

  void record(double t, const double* y, Mode mode, const Multipliers& mult) {
    if (!samples) return;
    Sample s;
    s.arc = arc_;
    s.t = t;
    std::copy(y, y + kNY, s.y.begin());
    control_in_mode(y, mode, mult, s.control.data());
    s.H = hamiltonian(t, y, s.control.data(), mult);
    s.S = switching_value(y, mult);
    samples->push_back(s);
  }

  const Settings& settings_;
  Dop853 stepper_;
  int arc_ = 0;
};

// The shooting function of the RESIDUAL module, with the bookkeeping hybrd1 needs.
void shooting_function(const double* x, double eps, Propagator& prop, double* F);

// Problems with interior events also have the shooting function by legs (RESIDUAL module):
// stop_at = k solves leg k alone (it ends at event k as if the trajectory ended there);
// stop_at = -1 is multiple shooting: after event k the costates restart from starts[k*n...] and
// their mismatch with the jump conditions is written to continuity[k*n...].
struct Legs {
  int stop_at = -1;
  const double* starts = nullptr;
  double* continuity = nullptr;
};
void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs);
using Residual = std::function<void(const double* x, double eps, Propagator& prop, double* F)>;

// Which shooting variables each leg solves for alone (indices into x; leg k > 0 also solves for
// its start costates), and the variables a leg alone holds fixed: the time fractions at their
// guesses, the event's other variables (costates after a state map, parameters) at 0.
struct LegPlan {
  std::vector<std::vector<int>> variables;
  std::vector<int> time_fractions, held_at_zero;
  // An epoch's window bound: while it is active (pass 2), legs alone hold the epoch's fraction
  // at the window's edge (0 or 1) instead of a guess inside.
  struct WindowEdge {
    int bound, fraction;
    double edge;
  };
  std::vector<WindowEdge> window_edges;
};

struct HomotopyStep {
  double eps;
  bool converged;
  double max_residual;
  int evaluations;
};

struct LegStep {
  int leg;
  bool converged;
  double max_residual;
  int evaluations;
};

// A bound psi <= 0 of the derivation, solved in two passes: its row of the shooting function is
// its multiplier (= 0) while inactive and psi itself (= 0) when active.
struct Bound {
  std::string name, meaning;
  int multiplier;  // index of the bound's multiplier in x
};

struct BoundReport {
  std::string name, meaning;
  double first_pass_value;  // psi at the solution of pass 1 (bound inactive); > 0 is a violation
  bool active;              // made active in pass 2
  double value, multiplier;  // at the final solution
};

struct BoundState {
  std::vector<char> active;
  std::vector<double> value;
};
inline BoundState& bound_state() {
  static BoundState state;
  return state;
}


// Row k of the shooting function for bound k: records psi and returns it when the bound is
// active, else the inactive expression (its multiplier).
inline double bound_row(int k, double psi, double inactive) {
  BoundState& b = bound_state();
  if (static_cast<std::size_t>(k) >= b.value.size()) {
    b.value.resize(k + 1, 0.0);
    b.active.resize(k + 1, 0);
  }
  b.value[k] = psi;
  return b.active[k] ? psi : inactive;
}

struct Result {
  std::string status = "not_converged";
  std::string method = "single shooting";
  int passes = 1;
  std::vector<BoundReport> bounds;
  std::vector<LegStep> legs;
  std::string detail;
  int info = 0;
  std::vector<double> x;
  std::vector<double> F;
  double eps = 1;
  double max_residual = 0;
  int evaluations = 0;
  int attempts = 0;
  int iterations = 0;
  std::vector<HomotopyStep> homotopy;
};

inline std::string hybrd_meaning(int info) {
  switch (info) {
    case 0:
      return "improper input parameters";
    case 1:
      return "relative error between two consecutive iterates is at most tol";
    case 2:
      return "number of calls to fcn has reached 200*(n+1)";
    case 3:
      return "tol is too small; no further improvement in x is possible";
    case 4:
      return "iteration is not making good progress";
    default:
      return "stopped by the shooting function (integration failure or time limit)";
  }
}

class Shooter {
 public:
  explicit Shooter(const Settings& s, Residual residual = shooting_function)
      : settings_(s), prop_(s), residual_(std::move(residual)) {}

  // hybrd1 from x at eps; true if max|F| <= accept. Returns the info code through `info`.
  bool solve(std::vector<double>& x, double eps, double accept, int& info, double& max_res) {
    eps_ = eps;
    failed_ = false;
    const int n = static_cast<int>(x.size());
    size_ = n;
    std::vector<double> F(n), wa(static_cast<std::size_t>(n * (3 * n + 13)) / 2 + 1);
    const int before = evaluations;
    info = hybrd1(&Shooter::callback, this, n, x.data(), F.data(), settings_.hybrd_tol, wa.data(),
                  static_cast<int>(wa.size()));
    if (failed_) info = -1;
    // hybrd1 returns the x of the smallest residual it saw; evaluate there for the record.
    if (!evaluate(x.data(), F.data())) {
      max_res = INFINITY;
      return false;
    }
    max_res = 0;
    for (double f : F) max_res = std::max(max_res, std::fabs(f));
    last_F = F;
    last_step_evaluations = evaluations - before;
    return std::isfinite(max_res) && max_res <= accept;
  }

  bool evaluate(const double* x, double* F) {
    try {
      residual_(x, eps_, prop_, F);
      ++evaluations;
      for (int i = 0; i < size_; ++i)
        if (!std::isfinite(F[i])) return false;
      return true;
    } catch (const numerical_error&) {
      return false;
    }
  }

  int evaluations = 0;
  int last_step_evaluations = 0;
  std::vector<double> last_F;
  Propagator& propagator() { return prop_; }

 private:
  static int callback(void* self, int n, const double* x, double* F, int) {
    auto* me = static_cast<Shooter*>(self);
    if (wall_seconds() > me->settings_.time_limit_s) {
      me->failed_ = true;
      return -1;
    }
    if (!me->evaluate(x, F)) {
      // A failed integration is a large residual, so hybrd backs off instead of stopping.
      for (int i = 0; i < n; ++i) F[i] = 1e6;
    }
    return 0;
  }

  const Settings& settings_;
  Propagator prop_;
  Residual residual_;
  int size_ = problem::kNumVars;
  double eps_ = 1;
  bool failed_ = false;
};

// One hybrd solve from x at eps, recorded in r: true if max|F| <= accept and x is admissible.
template <class Admissible>
bool homotopy_step(Shooter& shooter, std::vector<double>& x, double eps, double accept, Result& r,
                   Admissible&& admissible, int& info, double& res) {
  ++r.iterations;
  const bool ok = shooter.solve(x, eps, accept, info, res) && admissible(x.data());
  r.homotopy.push_back({eps, ok, res, shooter.last_step_evaluations});
  return ok;
}

// Solves at settings.eps_start from the guess x, then continues in eps down to 0 with an adaptive
// step in log(eps) and retreat on failure. True when eps = 0 is reached (x and res are then its
// solution).
template <class Admissible>
bool homotopy_to_zero(const Settings& s, Shooter& shooter, std::vector<double>& x, Result& r, Admissible&& admissible,
                      double& res) {
  int info = 0;
  double eps = s.eps_start;
  if (!homotopy_step(shooter, x, eps, s.accept_residual, r, admissible, info, res)) return false;
  double log_step = std::log(1.0 / s.eps_first_ratio);
  double zero_below = s.eps_min;  // eps at or below which the next step goes to eps = 0
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = eps <= zero_below;
    const double next = to_zero ? 0.0 : std::max(eps * std::exp(-log_step), 0.5 * zero_below);
    std::vector<double> trial = x;
    const double accept = to_zero ? s.final_residual : s.accept_residual;
    if (homotopy_step(shooter, trial, next, accept, r, admissible, info, res)) {
      x = trial;
      eps = next;
      r.info = info;
      if (to_zero) return true;
      log_step = std::min(log_step * 1.5, std::log(20.0));
    } else if (to_zero) {
      zero_below = 0.01 * eps;  // the bang-bang problem is still too far: smooth less first
      if (zero_below < 1e-12) return false;
    } else {
      log_step *= 0.5;
      if (log_step < std::log(1.02)) return false;
    }
  }
  return false;
}

// Seeded random restarts, each continued in eps from settings.eps_start to 0.
template <class Guess, class Admissible>
Result homotopy_solve(const Settings& s, Guess&& initial_guess, Admissible&& admissible) {
  Result r;
  Shooter shooter(s);
  std::mt19937_64 rng(s.seed);
  while (r.attempts < s.max_attempts) {
    if (wall_seconds() > s.time_limit_s) {
      r.status = "timeout";
      r.detail = "time limit reached before convergence";
      break;
    }
    ++r.attempts;  // attempts started, each from a new seeded guess
    std::vector<double> x(problem::kNumVars);
    initial_guess(rng, x.data());
    double res = 0;
    if (homotopy_to_zero(s, shooter, x, r, admissible, res)) {
      r.status = "converged";
      r.x = x;
      r.F = shooter.last_F;
      r.eps = 0;
      r.max_residual = res;
      break;
    }
  }
  if (r.status == "not_converged")
    r.detail = "no seeded attempt reached eps = 0 (" + std::to_string(r.attempts) + " attempts)";
  r.evaluations = shooter.evaluations;
  return r;
}

// Problems with interior events (the RESIDUAL module's LegPlan): each attempt first
// solves the legs one after the other at eps_start, each as if the trajectory ended at its event
// (leg k starts from the state leg k-1 reached); from those, multiple shooting over all legs is
// continued in eps to 0 and the solution is polished by single shooting. The legs are small
// problems that converge from random guesses where the whole one rarely does.
template <class Guess, class Admissible>
Result legs_homotopy_solve(const Settings& s, const LegPlan& plan, Guess&& initial_guess, Admissible&& admissible) {
  constexpr int n = problem::kNumStates, N = problem::kNumVars;
  const int events = static_cast<int>(plan.variables.size()) - 1;
  Result r;
  r.method = "legs, then multiple shooting, then single shooting";
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> symmetric(-1.0, 1.0);
  Shooter single(s);
  int evaluations = 0;
  while (r.attempts < s.max_attempts && r.status == "not_converged") {
    if (wall_seconds() > s.time_limit_s) {
      r.status = "timeout";
      r.detail = "time limit reached before convergence";
      break;
    }
    ++r.attempts;
    std::vector<double> x(N), starts(static_cast<std::size_t>(events * n));
    const auto guess = [&] {
      initial_guess(rng, x.data());
      for (const int i : plan.held_at_zero) x[i] = 0;
      if (r.attempts == 1)
        for (const int i : plan.time_fractions) x[i] = 0.5;  // first attempt: the middle of every window
      const BoundState& bounds = bound_state();
      for (const auto& w : plan.window_edges)
        if (static_cast<std::size_t>(w.bound) < bounds.active.size() && bounds.active[w.bound]) x[w.fraction] = w.edge;
    };
    guess();
    bool legs_solved = true;
    for (int k = 0; k <= events && legs_solved; ++k) {
      const auto& own = plan.variables[k];
      const int m = static_cast<int>(own.size()) + (k > 0 ? n : 0);
      const Residual leg = [&, k](const double* z, double eps, Propagator& prop, double* F) {
        std::vector<double> xx = x, st = starts;
        for (std::size_t j = 0; j < own.size(); ++j) xx[own[j]] = z[j];
        if (k > 0)
          for (int i = 0; i < n; ++i) st[(k - 1) * n + i] = z[own.size() + i];
        const Legs legs{k, st.data(), nullptr};
        shooting_legs(xx.data(), eps, prop, F, &legs);
      };
      Shooter shooter(s, leg);
      bool solved = false;
      for (int tries = 0; tries < s.leg_attempts && !solved; ++tries) {
        std::vector<double> z(m);
        if (k == 0) {
          if (tries > 0) guess();
          for (std::size_t j = 0; j < own.size(); ++j) z[j] = x[own[j]];
        } else {
          // Like leg 0's guess: (lambda0, start costates) uniform on the sphere with lambda0 > 0,
          // then scaled to leg 0's lambda0 (which this leg shares and cannot change).
          double norm2 = 0;
          for (auto& v : z) {
            v = symmetric(rng);
            norm2 += v * v;
          }
          const double lambda0 = 0.5 * (1 + symmetric(rng));
          const double scale = x[plan.variables[0][0]] / lambda0;
          for (auto& v : z) v *= scale * std::sqrt((1 - lambda0 * lambda0) / norm2);
        }
        int info = 0;
        double res = 0;
        ++r.iterations;
        solved = shooter.solve(z, s.eps_start, s.accept_residual, info, res);
        if (solved) {
          for (std::size_t j = 0; j < own.size(); ++j) x[own[j]] = z[j];
          if (k > 0)
            for (int i = 0; i < n; ++i) starts[(k - 1) * n + i] = z[own.size() + i];
          solved = k > 0 || x[plan.variables[0][0]] > 0;  // lambda0 > 0; the rest is checked joined
        }
        r.legs.push_back({k, solved, res, shooter.last_step_evaluations});
      }
      evaluations += shooter.evaluations;
      legs_solved = solved;
    }
    if (!legs_solved) continue;
    // Multiple shooting over [x, starts]: F = [the problem's equations, costate continuity].
    const Residual multiple = [&](const double* z, double eps, Propagator& prop, double* F) {
      const Legs legs{-1, z + N, F + N};
      shooting_legs(z, eps, prop, F, &legs);
    };
    Shooter shooter(s, multiple);
    std::vector<double> z(x);
    z.insert(z.end(), starts.begin(), starts.end());
    double res = 0;
    if (homotopy_to_zero(s, shooter, z, r, admissible, res)) {
      x.assign(z.begin(), z.begin() + N);
      int info = 0;
      if (homotopy_step(single, x, 0.0, s.final_residual, r, admissible, info, res)) {
        r.status = "converged";
        r.x = x;
        r.F = single.last_F;
        r.eps = 0;
        r.max_residual = res;
      }
    }
    evaluations += shooter.evaluations;
  }
  if (r.status == "not_converged")
    r.detail = "no seeded attempt reached eps = 0 (" + std::to_string(r.attempts) + " attempts)";
  r.evaluations = evaluations + single.evaluations;
  return r;
}

// Bounds psi <= 0 by passes over the active set: pass 1 solves with every bound inactive; while
// the solution violates an inactive bound (psi > 0) or has a negative multiplier on an active one,
// the next pass makes the violated bounds active, or else drops the active bound with the most
// negative multiplier, and solves again from cold. Usually two passes; never the same set twice.
template <class Solve>
Result two_pass_solve(const Settings& s, const std::vector<Bound>& bounds, Solve&& solve) {
  BoundState& state = bound_state();
  state.active.assign(bounds.size(), 0);
  state.value.assign(bounds.size(), 0.0);
  const auto values_at = [&](const std::vector<double>& x) {
    Propagator prop(s);
    std::vector<double> F(problem::kNumVars);
    shooting_function(x.data(), 0.0, prop, F.data());
    return state.value;
  };
  std::vector<std::vector<char>> tried;
  std::vector<double> first;
  std::vector<std::string> steps;
  Result r;
  int attempts = 0, iterations = 0, evaluations = 0;
  for (int pass = 1;; ++pass) {
    tried.push_back(state.active);
    r = solve(s);
    attempts += r.attempts;
    iterations += r.iterations;
    evaluations += r.evaluations;
    r.passes = pass;
    if (r.status != "converged") break;
    const std::vector<double> values = values_at(r.x);
    if (pass == 1) first = values;
    std::vector<char> next = state.active;
    int drop = -1;
    for (std::size_t k = 0; k < bounds.size(); ++k) {
      if (!state.active[k] && values[k] > 0) next[k] = 1;
      if (state.active[k] && r.x[bounds[k].multiplier] < 0 &&
          (drop < 0 || r.x[bounds[k].multiplier] < r.x[bounds[drop].multiplier]))
        drop = static_cast<int>(k);
    }
    if (next == state.active && drop >= 0) next[drop] = 0;
    if (next == state.active) break;  // consistent: the inactive bounds hold, the active ones push
    if (std::find(tried.begin(), tried.end(), next) != tried.end()) {
      r.status = "not_converged";
      r.detail = "the active set of the bounds cycles";
      break;
    }
    for (std::size_t k = 0; k < bounds.size(); ++k)
      if (next[k] != state.active[k]) steps.push_back((next[k] ? "+" : "-") + bounds[k].name);
    state.active = next;
  }
  r.attempts = attempts;
  r.iterations = iterations;
  r.evaluations = evaluations;
  if (r.passes > 1) {
    std::string changes;
    for (const auto& c : steps) changes += (changes.empty() ? "" : " ") + c;
    r.method = std::to_string(r.passes) + " passes over the bounds' active set (" + changes + "): " + r.method;
  }
  if (first.empty()) first.assign(bounds.size(), 0.0);
  const std::vector<double> last = r.status == "converged" ? values_at(r.x) : first;
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    const bool active = state.active[k] != 0;
    const double nu = r.status == "converged" ? r.x[bounds[k].multiplier] : 0.0;
    r.bounds.push_back({bounds[k].name, bounds[k].meaning, first[k], active, last[k], nu});
  }
  return r;
}

}  // namespace helios_rt

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
  // The global search (search.hpp): at most search_starts starts at eps_start, fewer once the
  // chance that another converged start finds a new extremal is below search_saturation (0:
  // always all); how many of the lowest-cost distinct extremals are continued to eps = 0
  // (problems without interior events); complete attempts (problems with them); its own time
  // budget (0: only time_limit_s) and threads (0: the cores).
  int search_starts = 64;
  double search_saturation = 0.05;
  int search_continued = 4;
  int search_attempts = 4;
  double search_time_s = 0;
  int threads = 0;
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
      double b = h;  // the switch lies in (0, b] of the step
      for (int k = 0; k < ng; ++k)
        if (g_old[k] >= 0 && g_new[k] < 0) crossed = k;
      if (crossed < 0 && ng > 0) crossed = dip(t, y, f0.data(), h, ynew.data(), fnew.data(), mode, mult, b, g_new);
      if (crossed < 0) {
        t = last ? t1 : t + h;
        std::copy(ynew.begin(), ynew.end(), y);
        record(t, y, mode, mult);
        h *= Dop853::step_factor(err);
        continue;
      }
      // Locate the switch on the frozen-mode step (Illinois regula falsi in the step length).
      double a = 0, ga = g_old[crossed], gb = g_new[crossed];
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
      // The new mode's stay function starts at round-off from 0: a long first step that ends past
      // the next switch would bracket that round-off instead. A short one moves clear of it, and
      // the step control grows the steps again.
      h = 1e-6 * (1 + std::fabs(t1 - t0));
    }
  }

 private:
  // A mode that ends and resumes inside one step (a short arc whose switches the step's ends do
  // not show; missing it makes the shooting function jump where the arc appears): the stay
  // functions on the step's cubic Hermite interpolant at kDipPoints - 1 interior points, and where
  // one is negative, the real sub-step there to confirm it. Returns the stay function that
  // changes sign (-1: none), with b and g_at_b the sub-step's length and the stay functions at
  // its end.
  static constexpr int kDipPoints = 12;
  int dip(double t, const double* y, const double* f0, double h, const double* y1, const double* f1, Mode mode,
          const Multipliers& mult, double& b, std::array<double, 2>& g_at_b) {
    std::array<double, kNY> yi{}, fi{};
    std::array<double, 2> g{};
    for (int j = 1; j < kDipPoints; ++j) {
      const double th = static_cast<double>(j) / kDipPoints, th2 = th * th, th3 = th2 * th;
      const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th, h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
      for (int i = 0; i < kNY; ++i) yi[i] = h00 * y[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
      const int ng = stay_functions(yi.data(), mode, mult, g.data());
      for (int k = 0; k < ng; ++k) {
        if (g[k] >= 0) continue;
        auto rhs = [&](double tt, const double* yy, double* dy) {
          std::array<double, problem::kNumControls> control{};
          control_in_mode(yy, mode, mult, control.data());
          dynamics(tt, yy, control.data(), mult, dy);
        };
        stepper_.step(rhs, t, y, f0, th * h, yi.data(), fi.data(), settings_.atol, settings_.rtol);
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
  double first_pass_value;   // psi at the solution of pass 1 (bound inactive); > 0 is a violation
  bool active;               // made active in pass 2
  double value, multiplier;  // at the final solution
};

struct BoundState {
  std::vector<char> active;
  std::vector<double> value;
};
inline BoundState& bound_state() {
  thread_local BoundState state;  // each search thread its own (search.hpp's parallel_for)
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

// One solve of the continuation onto the events (continuation_attempt): its stage ("events off",
// "epochs", "targets", "parameters"), the stage's homotopy value (the guess number, 0, tau or
// kappa) and the outcome.
struct ContinuationStep {
  std::string stage;
  double value;
  bool converged;
  double max_residual;
  int evaluations;
};

// What tells one extremal from another (search.hpp's shape_of): the revolutions about the
// central body (the angle the position sweeps about the initial angular momentum, over 2 pi), the
// throttle's mode changes (at eps = 0 its bang-bang switches), and the cost at its eps: the
// propellant of the smoothed problem (the integral of u - eps u (1 - u), in propellant units) for
// a throttle, else the flight time. At eps = 0 the cost is the objective.
struct Shape {
  double revolutions = 0;
  int switches = 0;
  double cost = INFINITY;
};

// A distinct solution at eps_start, and how many starts reached it.
struct StartExtremal {
  std::vector<double> x;
  Shape shape;
  double max_residual = 0;
  int first_start = 0, reached = 0;
  bool continued = false;
  int arrived = -1;  // the extremal at eps = 0 it was continued to (-1: none)
};

// A distinct extremal at eps = 0 (it satisfies the problem's own necessary conditions), with the
// solve that reached it first. With bounds: whether the passes over the active set started from
// it, the objective they reached (NaN when they did not converge) and their number.
struct Extremal {
  std::vector<double> x, x_start, F;
  Shape shape;
  double max_residual = 0;
  int info = 0;
  int first_start = 0, reached = 0;  // the first start (or attempt) that reached it, and how many did
  std::vector<int> from;             // the eps_start extremals (or attempts) that led to it
  std::string method;
  std::vector<HomotopyStep> homotopy;
  std::vector<LegStep> legs;
  std::vector<ContinuationStep> continuation;
  bool bounded_tried = false;
  double bounded_objective = NAN;
  int bounded_passes = 0;
};

// What the global search did (search.hpp), for solution.json.
struct SearchRecord {
  std::string method;
  int threads = 1;
  int starts = 0;           // starts (or complete attempts) drawn
  int converged_start = 0;  // starts converged at eps_start (problems without events)
  int continued = 0;        // eps_start extremals continued to eps = 0
  int converged_final = 0;  // solves that reached eps = 0
  double seconds = 0;
  bool cut_by_time = false;
  std::vector<StartExtremal> start_extremals;
  std::vector<Extremal> extremals;
  int returned = -1;  // index into extremals
  std::string reason;
};

struct Result {
  std::string status = "not_converged";
  std::string method = "single shooting";
  int passes = 1;
  std::vector<BoundReport> bounds;
  std::vector<LegStep> legs;
  std::string detail;
  int info = 0;
  std::vector<double> x;
  std::vector<double> x_start;  // the solution at settings.eps_start that eps was continued from to x
  std::vector<double> F;
  double eps = 1;
  double max_residual = 0;
  int evaluations = 0;
  int attempts = 0;
  int iterations = 0;
  std::vector<HomotopyStep> homotopy;
  std::vector<ContinuationStep> continuation;
  SearchRecord search;
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

// How hybrd starts: hybrd1's choice (trust region 100 times the unscaled |x|) suits random guesses
// and the eps steps; a continuation step starts next to its solution and takes the trust region
// at |D x| with D the Jacobian's column norms (hybrd mode 1, factor 1), so it does not jump to
// another branch.
struct HybrdStart {
  double factor = 100;
  bool scaled = false;  // hybrd mode 1: D from the Jacobian's column norms; else D = 1 (mode 2)
};
constexpr HybrdStart kContinuationStart{1.0, true};

class Shooter {
 public:
  explicit Shooter(const Settings& s, Residual residual = shooting_function, HybrdStart start = {})
      : settings_(s), prop_(s), residual_(std::move(residual)), start_(start) {}

  // hybrd1 from x at eps; true if max|F| <= accept. Returns the info code through `info`.
  bool solve(std::vector<double>& x, double eps, double accept, int& info, double& max_res) {
    eps_ = eps;
    failed_ = false;
    const int n = static_cast<int>(x.size());
    size_ = n;
    std::vector<double> F(n), wa(static_cast<std::size_t>(n * (3 * n + 13)) / 2 + 1);
    const int before = evaluations;
    if (start_.factor == 100 && !start_.scaled) {
      info = hybrd1(&Shooter::callback, this, n, x.data(), F.data(), settings_.hybrd_tol, wa.data(),
                    static_cast<int>(wa.size()));
    } else {  // hybrd1's call with the trust region's start changed
      const int lr = n * (n + 1) / 2;
      double* w = wa.data();
      for (int j = 0; j < n; ++j) w[j] = 1;
      int nfev = 0;
      info = hybrd(&Shooter::callback, this, n, x.data(), F.data(), settings_.hybrd_tol, 200 * (n + 1), n - 1, n - 1,
                   0.0, w, start_.scaled ? 1 : 2, start_.factor, 0, &nfev, w + 6 * n + lr, n, w + 6 * n, lr, w + n,
                   w + 2 * n, w + 3 * n, w + 4 * n, w + 5 * n);
      if (info == 5) info = 4;
    }
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
  HybrdStart start_;
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

// Any step of a continuation stays on its branch (see homotopy_to_zero's on_branch).
struct AnyBranch {
  bool operator()(const std::vector<double>&, const std::vector<double>&, double) const { return true; }
};

// Solves at settings.eps_start from the guess x, then continues in eps down to 0 with an adaptive
// step in log(eps) and retreat on failure. A step whose solution `on_branch(from, to, eps)` rejects
// (hybrd jumped to another extremal's branch) counts as failed. True when eps = 0 is reached (x
// and res are then its solution; r.x_start the first N variables of the solution at eps_start).
template <class Admissible, class OnBranch = AnyBranch>
bool homotopy_to_zero(const Settings& s, Shooter& shooter, std::vector<double>& x, Result& r, Admissible&& admissible,
                      double& res, OnBranch&& on_branch = OnBranch{}) {
  int info = 0;
  double eps = s.eps_start;
  if (!homotopy_step(shooter, x, eps, s.accept_residual, r, admissible, info, res)) return false;
  r.x_start.assign(x.begin(), x.begin() + problem::kNumVars);
  double log_step = std::log(1.0 / s.eps_first_ratio);
  double zero_below = s.eps_min;  // eps at or below which the next step goes to eps = 0
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = eps <= zero_below;
    const double next = to_zero ? 0.0 : std::max(eps * std::exp(-log_step), 0.5 * zero_below);
    std::vector<double> trial = x;
    const double accept = to_zero ? s.final_residual : s.accept_residual;
    bool ok = homotopy_step(shooter, trial, next, accept, r, admissible, info, res);
    if (ok && !on_branch(x, trial, next)) ok = r.homotopy.back().converged = false;
    if (ok) {
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

// A solution re-propagated with every step recorded (steps of at most max_step) and every switch;
// throws numerical_error where the integration fails.
struct RecordedPath {
  std::vector<Sample> samples;
  std::vector<Switch> switches;
};
inline RecordedPath recorded_path(const Settings& s, const std::vector<double>& x, double eps, double max_step) {
  RecordedPath path;
  Propagator prop(s);
  prop.samples = &path.samples;
  prop.switches = &path.switches;
  prop.max_step = max_step;
  std::vector<double> F(problem::kNumVars);
  shooting_function(x.data(), eps, prop, F.data());
  return path;
}

// The objective of a converged x (smaller is better): the propellant of a minimum-fuel or
// minimum-initial-mass problem (summed over the arcs: a dropped lander is not propellant), the
// flight time tf - t0 of a minimum-time one.
inline double objective_of(const Settings& s, const std::vector<double>& x) {
  std::vector<Sample> samples;
  try {
    samples = recorded_path(s, x, 0.0, INFINITY).samples;
  } catch (const numerical_error&) {
    return INFINITY;
  }
  if (samples.empty()) return INFINITY;
  if (problem::kMinimumFuel && problem::kMassIndex >= 0) {
    double propellant = 0;
    for (std::size_t i = 1; i < samples.size(); ++i)
      if (samples[i].arc == samples[i - 1].arc)
        propellant += samples[i - 1].y[problem::kMassIndex] - samples[i].y[problem::kMassIndex];
    return propellant;
  }
  return samples.back().t - samples.front().t;
}

// Problems with interior events (the RESIDUAL module's LegPlan): an attempt first solves the
// legs one after the other at eps_start, each as if the trajectory ended at its event (leg k
// starts from the state leg k-1 reached); from those, multiple shooting over all legs is
// continued in eps to 0 and the solution is polished by single shooting. The legs are small
// problems that converge from random guesses where the whole one rarely does. True when the
// attempt converged (r then holds the solution).
template <class Guess, class Admissible>
bool legs_attempt(const Settings& s, const LegPlan& plan, Guess&& initial_guess, Admissible&& admissible,
                  std::mt19937_64& rng, Shooter& single, Result& r, int& evaluations) {
  constexpr int n = problem::kNumStates, N = problem::kNumVars;
  const int events = static_cast<int>(plan.variables.size()) - 1;
  std::uniform_real_distribution<double> symmetric(-1.0, 1.0);
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
  if (!legs_solved) return false;
  // Multiple shooting over [x, starts]: F = [the problem's equations, costate continuity].
  const Residual multiple = [&](const double* z, double eps, Propagator& prop, double* F) {
    const Legs legs{-1, z + N, F + N};
    shooting_legs(z, eps, prop, F, &legs);
  };
  Shooter shooter(s, multiple);
  std::vector<double> z(x);
  z.insert(z.end(), starts.begin(), starts.end());
  double res = 0;
  bool converged = false;
  if (homotopy_to_zero(s, shooter, z, r, admissible, res)) {
    x.assign(z.begin(), z.begin() + N);
    int info = 0;
    if (homotopy_step(single, x, 0.0, s.final_residual, r, admissible, info, res)) {
      r.status = "converged";
      r.method = "legs, then multiple shooting, then single shooting";
      r.x = x;
      r.F = single.last_F;
      r.eps = 0;
      r.max_residual = res;
      converged = true;
    }
  }
  evaluations += shooter.evaluations;
  return converged;
}

// The events' own shooting variables and rows (RESIDUAL module), for the continuation onto the
// events. An event is passable when it is instantaneous and its state map is the identity with
// its parameters at 0: the trajectory of the problem without it (its multipliers and parameters
// 0, its epoch held) then solves every row of the event but its constraint c = 0.
struct EventRows {
  std::vector<std::array<int, 2>> constraints;  // {multiplier nu_j, row of c_j = 0}
  std::array<int, 2> epoch{-1, -1};             // {epoch as a window fraction, row of its free-epoch condition}
  std::vector<std::array<int, 2>> parameters;   // {Category-C parameter, row of its stationarity}
  std::vector<std::array<int, 2>> costates;     // {costate just after the event, row of its jump}
};

struct EventPlan {
  bool passable = false;    // every event passable
  int multiplier = 0;       // lambda0
  std::vector<int> sphere;  // the normalization's variables, lambda0 among them
  std::vector<EventRows> events;
};

// Continuation in a homotopy parameter from `start` down to 0 (as homotopy_to_zero does in eps):
// steps in log(value) that grow after a success and halve after a failure, the last step to 0
// from below start * 1e-10. `step(value)` solves there from the last solution and keeps it on
// success.
template <class Step>
bool continue_to_zero(const Settings& s, double start, Step&& step) {
  if (!step(start)) return false;
  double value = start, log_step = std::log(1.0 / s.eps_first_ratio), zero_below = start * 1e-10;
  while (wall_seconds() <= s.time_limit_s) {
    const bool to_zero = value <= zero_below;
    const double next = to_zero ? 0.0 : std::max(value * std::exp(-log_step), 0.5 * zero_below);
    if (step(next)) {
      if (to_zero) return true;
      value = next;
      log_step = std::min(log_step * 1.5, std::log(20.0));
    } else if (to_zero) {
      zero_below *= 0.01;
      if (zero_below < start * 1e-16) return false;
    } else {
      log_step *= 0.5;
      if (log_step < std::log(1.02)) return false;
    }
  }
  return false;
}

// One attempt of the continuation onto the events, all at eps_start:
//   events off: the problem without its events (each event's rows held: nu = 0, parameters = 0,
//     epoch = its reference) from a scale-free random guess: lambda0 = 1 and every other variable
//     of the sphere of magnitude log-uniform in [1e-3, 1], random sign, then projected on the sphere;
//   epochs: each event's reference epoch where that trajectory passes closest to the event's
//     target (the first attempt from it) or uniform in its window (later attempts);
//   targets: Newton homotopy F(x) - (1 - tau) F(x_off) = 0, tau 0 -> 1, with the parameters held at
//     0; at tau = 0 the targets sit where the eventless trajectory passes, at tau = 1 they are the
//     events' own;
//   parameters: stationarity + kappa lambda0 p = 0 (the cost plus kappa/2 |p|^2), kappa from large
//     to 0: the parameters leave 0 in the direction that lowers the cost (with p held at 0 a swing-by
//     angle delta = 0 solves every row for any other angle, a coordinate pole, not a minimum);
//   eps: single shooting continued from eps_start to 0.
// True when it converged (r then holds the solution).
template <class Guess, class Admissible>
bool continuation_attempt(const Settings& s, const EventPlan& plan, Guess&& initial_guess, Admissible&& admissible,
                          std::mt19937_64& rng, std::vector<double>& eventless, int& uses, Result& r,
                          int& evaluations) {
  constexpr int N = problem::kNumVars;
  const double eps = s.eps_start;
  const int nev = static_cast<int>(plan.events.size());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> reference(static_cast<std::size_t>(nev), 0.5);
  const auto hold_events = [&](const double* x, double* F) {
    for (int k = 0; k < nev; ++k) {
      const EventRows& e = plan.events[k];
      for (const auto& [v, row] : e.constraints) F[row] = x[v];
      if (e.epoch[0] >= 0) F[e.epoch[1]] = x[e.epoch[0]] - reference[k];
      for (const auto& [v, row] : e.parameters) F[row] = x[v];
    }
  };
  const auto snap = [&](std::vector<double>& x) {
    for (int k = 0; k < nev; ++k) {
      const EventRows& e = plan.events[k];
      for (const auto& [v, row] : e.constraints) x[v] = 0;
      if (e.epoch[0] >= 0) x[e.epoch[0]] = reference[k];
      for (const auto& [v, row] : e.parameters) x[v] = 0;
    }
  };
  // With the event off its jump rows read lambda(t-) - lambda(t+) = 0: the costates after it that are
  // shooting variables are set to those before it (event by event, as each one moves the next).
  Propagator prop(s);
  std::vector<double> F(N);
  const auto carry_costates = [&](std::vector<double>& x) {
    for (int pass = 0; pass < nev; ++pass) {
      try {
        shooting_function(x.data(), eps, prop, F.data());
      } catch (const numerical_error&) {
        return;
      }
      for (const auto& e : plan.events)
        for (const auto& [v, row] : e.costates)
          if (std::isfinite(F[row])) x[v] += F[row];
    }
  };
  const Residual off = [&](const double* x, double e, Propagator& prop, double* F) {
    shooting_function(x, e, prop, F);
    hold_events(x, F);
  };
  Shooter shooter_off(s, off, kContinuationStart);
  const auto solve = [&](Shooter& shooter, std::vector<double>& x, const char* stage, double value) {
    int info = 0;
    double res = 0;
    ++r.iterations;
    const bool ok = shooter.solve(x, eps, s.accept_residual, info, res) && admissible(x.data());
    r.continuation.push_back({stage, value, ok, res, shooter.last_step_evaluations});
    return ok;
  };
  const auto done = [&](bool ok) {
    evaluations += shooter_off.evaluations;
    return ok;
  };

  // Events off, from scale-free random guesses, in the variables and rows of no event (the
  // event's own are set from them: nu = 0, parameters 0, epochs at the reference, the costates
  // after it carried over), once: later attempts start from the same eventless solution.
  std::vector<int> own_variables, own_rows;
  {
    std::vector<bool> event_variable(N), event_row(N);
    for (const auto& e : plan.events) {
      for (const auto* pairs : {&e.constraints, &e.parameters, &e.costates})
        for (const auto& [v, row] : *pairs) event_variable[v] = event_row[row] = true;
      if (e.epoch[0] >= 0) event_variable[e.epoch[0]] = event_row[e.epoch[1]] = true;
    }
    for (int i = 0; i < N; ++i) {
      if (!event_variable[i]) own_variables.push_back(i);
      if (!event_row[i]) own_rows.push_back(i);
    }
  }
  std::vector<double> x(N);
  if (eventless.empty()) {
    const bool reduced = own_variables.size() == own_rows.size();
    std::vector<double> base(N);
    const auto expand = [&](const double* z, std::vector<double>& xx) {
      xx = base;
      for (std::size_t j = 0; j < own_variables.size(); ++j) xx[own_variables[j]] = z[j];
    };
    const Residual eventless_residual = [&](const double* z, double e, Propagator& p, double* G) {
      std::vector<double> xx, FF(N);
      expand(z, xx);
      for (int pass = 0; pass <= nev; ++pass) {
        shooting_function(xx.data(), e, p, FF.data());
        bool carried = false;
        for (const auto& ev : plan.events)
          for (const auto& [v, row] : ev.costates) {
            xx[v] += FF[row];
            carried = true;
          }
        if (!carried) break;
      }
      for (std::size_t j = 0; j < own_rows.size(); ++j) G[j] = FF[own_rows[j]];
    };
    Shooter shooter_eventless(s, eventless_residual, kContinuationStart);
    bool off_solved = false;
    for (int tries = 0; tries < s.leg_attempts && !off_solved; ++tries) {
      initial_guess(rng, x.data());
      double norm2 = 0;
      for (const int i : plan.sphere) {
        x[i] = i == plan.multiplier ? 1.0 : (unit(rng) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, -3.0 + 3.0 * unit(rng));
        norm2 += x[i] * x[i];
      }
      for (const int i : plan.sphere) x[i] /= std::sqrt(norm2);
      snap(x);
      carry_costates(x);
      if (reduced) {
        base = x;
        std::vector<double> z(own_variables.size());
        for (std::size_t j = 0; j < z.size(); ++j) z[j] = x[own_variables[j]];
        int info = 0;
        double res = 0;
        ++r.iterations;
        off_solved = shooter_eventless.solve(z, eps, s.accept_residual, info, res);
        expand(z.data(), x);
        carry_costates(x);
        off_solved = off_solved && admissible(x.data());
        r.continuation.push_back(
            {"events off", static_cast<double>(tries), off_solved, res, shooter_eventless.last_step_evaluations});
      } else {
        off_solved = solve(shooter_off, x, "events off", tries);
      }
    }
    evaluations += shooter_eventless.evaluations;
    if (!off_solved) return done(false);
    eventless = x;
  }
  x = eventless;
  const bool closest = uses++ == 0;

  // Reference epochs: where the eventless trajectory passes closest to each target (its c rows
  // are the offsets: the first attempt from the eventless solution), or at random (later ones).
  const auto distance = [&](const std::vector<double>& z, int k) -> double {
    try {
      shooting_function(z.data(), eps, prop, F.data());
    } catch (const numerical_error&) {
      return INFINITY;
    }
    double d2 = 0;
    for (const auto& [v, row] : plan.events[k].constraints) d2 += F[row] * F[row];
    return std::isfinite(d2) ? d2 : INFINITY;
  };
  for (int k = 0; k < nev; ++k) {
    const int v = plan.events[k].epoch[0];
    if (v < 0) continue;
    if (closest) {
      std::vector<double> z = x;
      double best = INFINITY;
      for (int j = 0; j <= 40; ++j) {
        z[v] = j / 40.0;
        const double d = distance(z, k);
        if (d < best) {
          best = d;
          reference[k] = z[v];
        }
      }
    } else {
      reference[k] = unit(rng);
    }
    x[v] = reference[k];
  }
  snap(x);
  carry_costates(x);
  if (!solve(shooter_off, x, "epochs", 0)) return done(false);
  snap(x);  // exactly 0: a finite-difference step on a variable of 1e-80 would be lost

  // Targets: the Newton homotopy from the eventless trajectory's offsets.
  std::vector<double> F0(N);
  try {
    shooting_function(x.data(), eps, prop, F0.data());
  } catch (const numerical_error&) {
    return done(false);
  }
  double tau = 0;
  const Residual targets = [&](const double* z, double e, Propagator& p, double* G) {
    shooting_function(z, e, p, G);
    for (int i = 0; i < N; ++i) G[i] -= (1 - tau) * F0[i];
    for (const auto& ev : plan.events)
      for (const auto& [v, row] : ev.parameters) G[row] = z[v];
  };
  Shooter shooter_targets(s, targets, kContinuationStart);
  {
    std::vector<double> previous = x;
    double tau_previous = 0, step = 0.1;
    bool reached = false;
    while (!reached && wall_seconds() <= s.time_limit_s) {
      const double from = tau, next = std::min(1.0, tau + step);
      std::vector<double> trial = x;
      tau = next;
      bool solved = false;
      if (from > 0) {  // secant predictor along the path; where the path bends, from x itself
        for (int i = 0; i < N; ++i) trial[i] += (x[i] - previous[i]) / (from - tau_previous) * (next - from);
        solved = solve(shooter_targets, trial, "targets", next);
        if (!solved) trial = x;
      }
      if (solved || solve(shooter_targets, trial, "targets", next)) {
        previous = x;
        tau_previous = from;
        x = trial;
        reached = next >= 1.0;
        step *= 1.5;
      } else {
        tau = from;
        step *= 0.5;
        if (step < 1e-3) break;
      }
    }
    evaluations += shooter_targets.evaluations;
    if (!reached) return done(false);
  }

  // Parameters: from 0 to stationarity, kappa from large to 0.
  bool has_parameters = false;
  double stationarity = 0;
  try {
    shooting_function(x.data(), eps, prop, F.data());
  } catch (const numerical_error&) {
    return done(false);
  }
  for (const auto& ev : plan.events)
    for (const auto& [v, row] : ev.parameters) {
      has_parameters = true;
      stationarity = std::max(stationarity, std::fabs(F[row]));
    }
  if (has_parameters) {
    double kappa = 0;
    // The penalty's weight of each parameter: 1 on the first attempt from the eventless solution,
    // log-uniform in [0.1, 10] on later ones, so that they follow other paths.
    std::vector<double> weight(N, 1.0);
    if (!closest)
      for (auto& w : weight) w = std::pow(10.0, -1.0 + 2.0 * unit(rng));
    const Residual penalized = [&](const double* z, double e, Propagator& p, double* G) {
      shooting_function(z, e, p, G);
      for (const auto& ev : plan.events)
        for (const auto& [v, row] : ev.parameters) G[row] += kappa * weight[v] * z[plan.multiplier] * z[v];
    };
    Shooter shooter_parameters(s, penalized, kContinuationStart);
    // The first kappa moves the parameters by about 1e-3.
    const double start = stationarity > 0 ? stationarity / (1e-3 * x[plan.multiplier]) : 1.0;
    // Secant predictor in log(kappa) from the last two solutions (the parameters move fast
    // where kappa meets the cost's own curvature).
    std::vector<double> previous;  // the solution before x on the path (none before the first kappa)
    double log_previous = 0, log_current = 0;
    bool on_path = false;  // x solves at log_current (before the first kappa it holds p = 0)
    const bool ok = continue_to_zero(s, start, [&](double value) {
      kappa = value;
      std::vector<double> trial = x;
      bool solved = false;
      if (value > 0 && !previous.empty()) {
        for (int i = 0; i < N; ++i)
          trial[i] += (x[i] - previous[i]) * (std::log(value) - log_current) / (log_current - log_previous);
        solved = solve(shooter_parameters, trial, "parameters", value);
        if (!solved) trial = x;  // the path bends: from the last solution itself
      }
      if (!solved && !solve(shooter_parameters, trial, "parameters", value)) return false;
      if (value > 0) {
        if (on_path) {
          previous = x;
          log_previous = log_current;
        }
        log_current = std::log(value);
        on_path = true;
      }
      x = trial;
      return true;
    });
    evaluations += shooter_parameters.evaluations;
    if (!ok) return done(false);
  }

  // eps to 0 on the whole problem (to the intermediate gate), then the polish to the final gate:
  // hybrd1 from there, else once more from the continuation's start.
  Settings to_zero = s;
  to_zero.final_residual = std::max(s.final_residual, s.accept_residual);
  Shooter full(s, shooting_function, kContinuationStart), polish(s);
  double res = 0;
  int info = 0;
  bool converged = homotopy_to_zero(to_zero, full, x, r, admissible, res);
  if (converged) {
    std::vector<double> y = x;
    Shooter* last = &polish;
    converged = homotopy_step(polish, y, 0.0, s.final_residual, r, admissible, info, res);
    if (!converged) {
      y = x;
      last = &full;
      converged = homotopy_step(full, y, 0.0, s.final_residual, r, admissible, info, res);
    }
    // A parameter that moves nothing at the solution (a swing-by's plane angle at delta = 0 or pi)
    // leaves its stationarity row satisfied for any value: a coordinate pole, not an optimum.
    const auto at_pole = [&](const std::vector<double>& z) {
      std::vector<double> G0(N), G(N);
      try {
        shooting_function(z.data(), 0.0, prop, G0.data());
        for (const auto& ev : plan.events)
          for (const auto& [v, row] : ev.parameters) {
            std::vector<double> moved = z;
            moved[v] += 1e-4;
            shooting_function(moved.data(), 0.0, prop, G.data());
            double change = 0, size = 0;
            for (int i = 0; i < N; ++i) {
              bool own = false;
              for (const auto& e2 : plan.events)
                for (const auto& [v2, row2] : e2.parameters) own = own || i == row2;
              if (own) continue;
              change = std::max(change, std::fabs(G[i] - G0[i]));
              size = std::max(size, std::fabs(G0[i]));
            }
            if (!(change > 1e-12 * (1 + size))) return true;
          }
      } catch (const numerical_error&) {
        return true;
      }
      return false;
    };
    if (converged && has_parameters && at_pole(y)) converged = false;
    if (converged) {
      r.status = "converged";
      r.method = std::string("events off, then continuation onto the events' targets") +
                 (has_parameters ? ", then their parameters" : "") + ", then eps continuation, then single shooting";
      r.info = info;
      r.x = y;
      r.F = last->last_F;
      r.eps = 0;
      r.max_residual = res;
    }
  }
  evaluations += full.evaluations + polish.evaluations;
  return done(converged);
}

// The Newton homotopy F(z) - sigma F(x) = 0 at eps, followed from sigma = 1 (solved by x) to 0:
// it moves the rows that changed with the active set from their old form to their new one. True
// when sigma = 0 was reached (x is then the solution at eps).
inline bool shift_rows(const Settings& s, std::vector<double>& x, double eps, Result& r) {
  std::vector<double> start(problem::kNumVars);
  {
    Propagator prop(s);
    try {
      shooting_function(x.data(), eps, prop, start.data());
    } catch (const numerical_error&) {
      return false;
    }
  }
  double sigma = 1;
  const Residual shifted = [&](const double* z, double e, Propagator& p, double* F) {
    shooting_function(z, e, p, F);
    for (int i = 0; i < problem::kNumVars; ++i) F[i] -= sigma * start[i];
  };
  Shooter shooter(s, shifted, kContinuationStart);
  const auto anything = [](const double*) { return true; };
  const bool moved = continue_to_zero(s, 1.0, [&](double value) {
    sigma = value;
    std::vector<double> trial = x;
    int info = 0;
    double res = 0;
    const bool ok = homotopy_step(shooter, trial, eps, s.accept_residual, r, anything, info, res);
    if (ok) x = trial;
    return ok;
  });
  r.evaluations += shooter.evaluations;
  return moved;
}

// A pass over a new active set, warm from the last pass's result `warm`:
//   first from its solution x (eps = 0), smoothed (eps raised by decades to eps_start as far as
//     each step, a Newton solve from the last, converges), the rows shifted there (shift_rows),
//     and eps continued back to 0;
//   else from its solution at eps_start (x_start), where the problem is smooth and a bound can
//     move far (S10's periapsis radius by a factor of ten), shifted there and continued to 0.
// True when eps = 0 was reached (warm.x is then the solution).
template <class Admissible>
bool bound_homotopy(const Settings& s, Result& warm, Admissible&& admissible) {
  const auto to_zero = [&](std::vector<double>& x, double eps) {
    double res = 0;
    int info = 0;
    Shooter single(s);
    Settings down = s;
    down.eps_start = eps;
    const bool reached = eps == 0 ? homotopy_step(single, x, 0.0, s.final_residual, warm, admissible, info, res)
                                  : homotopy_to_zero(down, single, x, warm, admissible, res);
    warm.evaluations += single.evaluations;
    if (reached) {
      warm.max_residual = res;
      warm.F = single.last_F;
      warm.x = x;
    }
    return reached;
  };
  const std::vector<double> last_start = warm.x_start;
  std::vector<double> x = warm.x;
  double eps = 0;
  {
    Shooter plain(s, shooting_function, kContinuationStart);
    const auto anything = [](const double*) { return true; };
    for (double next = 1e-4; next <= s.eps_start * (1 + 1e-12); next *= 10) {
      std::vector<double> trial = x;
      int info = 0;
      double res = 0;
      if (!homotopy_step(plain, trial, next, s.accept_residual, warm, anything, info, res)) break;
      x = trial;
      eps = next;
    }
    warm.evaluations += plain.evaluations;
  }
  if (shift_rows(s, x, eps, warm) && to_zero(x, eps)) {
    if (eps != s.eps_start) warm.x_start = last_start;  // to_zero set it at eps
    return true;
  }
  if (last_start.empty()) return false;
  x = last_start;
  return shift_rows(s, x, s.eps_start, warm) && to_zero(x, s.eps_start);
}

// What the passes over the bounds' active set did, summed over every pass tried.
struct PassLog {
  int attempts = 0, iterations = 0, evaluations = 0;
  std::vector<std::string> methods;  // each pass's method
  std::vector<LegStep> legs;
  std::vector<HomotopyStep> homotopy;
  std::vector<ContinuationStep> continuation;
  std::string from;  // which of pass 1's extremals the passes start from ("" for its solution)
  void add(const Result& r, int pass) {
    attempts += r.attempts;
    iterations += r.iterations;
    evaluations += r.evaluations;
    methods.push_back(from + "pass " + std::to_string(pass) + ": " + r.method);
    legs.insert(legs.end(), r.legs.begin(), r.legs.end());
    homotopy.insert(homotopy.end(), r.homotopy.begin(), r.homotopy.end());
    continuation.insert(continuation.end(), r.continuation.begin(), r.continuation.end());
  }
};

// The bounds' values psi at x (eps = 0).
inline std::vector<double> bound_values(const Settings& s, const std::vector<double>& x) {
  Propagator prop(s);
  std::vector<double> F(problem::kNumVars);
  shooting_function(x.data(), 0.0, prop, F.data());
  return bound_state().value;
}

// The passes after pass 1, from its converged solution r (every bound inactive): while r violates
// an inactive bound (psi > 0) or has a negative multiplier on an active one, the next pass makes
// the violated bounds active, or else drops the active bound with the most negative multiplier,
// and solves again: warm from the last solution (bound_homotopy), else (when `cold` allows) from
// cold. Never the same set twice. True when a consistent set was reached (r then holds its
// solution, bound_state().active the set); `steps` lists the changes ("+name", "-name").
template <class Solve, class Admissible>
bool active_set_passes(const Settings& s, const std::vector<Bound>& bounds, Result& r, bool cold, Solve&& solve,
                       Admissible&& admissible, PassLog& log, std::vector<std::string>& steps) {
  BoundState& state = bound_state();
  state.active.assign(bounds.size(), 0);
  std::vector<std::vector<char>> tried{state.active};
  for (int pass = 2;; ++pass) {
    const std::vector<double> values = bound_values(s, r.x);
    std::vector<char> next = state.active;
    int drop = -1;
    for (std::size_t k = 0; k < bounds.size(); ++k) {
      if (!state.active[k] && values[k] > 0) next[k] = 1;
      if (state.active[k] && r.x[bounds[k].multiplier] < 0 &&
          (drop < 0 || r.x[bounds[k].multiplier] < r.x[bounds[drop].multiplier]))
        drop = static_cast<int>(k);
    }
    if (next == state.active && drop >= 0) next[drop] = 0;
    if (next == state.active) return true;  // consistent: the inactive bounds hold, the active ones push
    if (std::find(tried.begin(), tried.end(), next) != tried.end()) {
      r.status = "not_converged";
      r.detail = "the active set of the bounds cycles";
      return false;
    }
    tried.push_back(next);
    for (std::size_t k = 0; k < bounds.size(); ++k)
      if (next[k] != state.active[k]) steps.push_back((next[k] ? "+" : "-") + bounds[k].name);
    state.active = next;
    Result warm;
    warm.x = r.x;
    warm.x_start = r.x_start;
    warm.method = "warm from pass " + std::to_string(pass - 1) + " by a homotopy on the bounds' rows";
    if (bound_homotopy(s, warm, admissible)) {
      warm.status = "converged";
      warm.eps = 0;
      warm.attempts = 1;
      r = warm;
    } else if (cold) {
      log.evaluations += warm.evaluations;
      r = solve(s);
    } else {
      warm.method += " (did not converge)";
      log.add(warm, pass);
      r.status = "not_converged";
      r.detail = "the warm homotopy on the bounds' rows did not converge";
      return false;
    }
    log.add(r, pass);
    r.passes = pass;
    if (r.status != "converged") return false;
  }
}

// Bounds psi <= 0 by passes over the active set: pass 1 solves with every bound inactive, then
// active_set_passes follows from its solution, warm. Pass 1's search keeps its distinct extremals,
// and the passes start from each of them (best first; one no better than a result already found
// cannot lead to a better one), since the best extremal without the bounds need not lead to the
// best one with them. The best consistent result is the solution. Only when no warm start
// gets there do the passes run again from pass 1's solution, now with a cold solve where the warm
// one fails.
template <class Solve, class Admissible>
Result two_pass_solve(const Settings& s, const std::vector<Bound>& bounds, Solve&& solve, Admissible&& admissible) {
  BoundState& state = bound_state();
  state.active.assign(bounds.size(), 0);
  state.value.assign(bounds.size(), 0.0);
  PassLog log;
  std::vector<std::string> steps;  // the active-set changes that led to the solution
  Result r = solve(s);
  log.add(r, 1);
  std::vector<double> first(bounds.size(), 0.0);
  bool consistent = false;
  std::vector<char> final_set = state.active;
  if (r.status == "converged") {
    first = bound_values(s, r.x);
    // The starts: pass 1's distinct extremals, its solution first, then the others by objective.
    std::vector<Extremal>& extremals = r.search.extremals;
    if (extremals.empty()) {  // a solve without a search record (an llm-written SOLVE module)
      Extremal own;
      own.x = r.x;
      own.x_start = r.x_start;
      own.shape.cost = objective_of(s, r.x);
      own.reached = 1;
      own.method = r.method;
      extremals.push_back(own);
      r.search.returned = 0;
    }
    std::vector<std::size_t> order(extremals.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      const bool a_solution = static_cast<int>(a) == r.search.returned,
                 b_solution = static_cast<int>(b) == r.search.returned;
      return a_solution != b_solution ? a_solution : extremals[a].shape.cost < extremals[b].shape.cost;
    });
    Result best = r;
    double best_objective = INFINITY;
    int best_from = r.search.returned;
    for (const std::size_t i : order) {
      Extremal& o = extremals[i];
      if (wall_seconds() > s.time_limit_s || o.shape.cost >= best_objective) continue;
      o.bounded_tried = true;
      Result from = r;
      from.x = o.x;
      from.x_start = o.x_start;
      log.from = static_cast<int>(i) == r.search.returned ? "" : "from extremal " + std::to_string(i) + ", ";
      std::vector<std::string> changes;
      if (!active_set_passes(s, bounds, from, false, solve, admissible, log, changes)) continue;
      o.bounded_objective = objective_of(s, from.x);
      o.bounded_passes = from.passes;
      if (o.bounded_objective < best_objective) {
        best_objective = o.bounded_objective;
        best = from;
        best_from = static_cast<int>(i);
        final_set = state.active;
        steps = changes;
        consistent = true;
      }
    }
    if (!consistent && wall_seconds() <= s.time_limit_s) {
      log.from = "cold: ";
      best = r;
      steps.clear();
      consistent = active_set_passes(s, bounds, best, true, solve, admissible, log, steps);
      final_set = state.active;
    }
    SearchRecord record = std::move(r.search);
    r = best;
    r.search = std::move(record);
    if (consistent) {
      r.search.returned = best_from;
      r.search.reason = "the lowest objective with the bounds reached from the " +
                        std::to_string(r.search.extremals.size()) + " distinct extremals of pass 1";
    }
    if (!consistent) {
      r.status = "not_converged";
      if (r.detail.empty()) r.detail = "no pass over the bounds' active set converged";
    }
  }
  state.active = final_set;
  r.attempts = log.attempts;
  r.iterations = log.iterations;
  r.evaluations = log.evaluations;
  r.legs = log.legs;
  r.homotopy = log.homotopy;
  r.continuation = log.continuation;
  if (r.passes > 1) {
    std::string changes;
    for (const auto& c : steps) changes += (changes.empty() ? "" : " ") + c;
    std::string each;
    for (const auto& m : log.methods) each += (each.empty() ? "" : "; ") + m;
    r.method = std::to_string(r.passes) + " passes over the bounds' active set (" + changes + "): " + each;
  }
  const bool converged = r.status == "converged";
  const std::vector<double> last = converged ? bound_values(s, r.x) : first;
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    const bool active = state.active[k] != 0;
    const double nu = converged ? r.x[bounds[k].multiplier] : 0.0;
    r.bounds.push_back({bounds[k].name, bounds[k].meaning, first[k], active, last[k], nu});
  }
  return r;
}

}  // namespace helios_rt

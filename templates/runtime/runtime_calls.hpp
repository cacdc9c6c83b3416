// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, what a module may call (templates/runtime/runtime_calls.hpp): the
// helpers the runtime offers a program's modules: its parameters, dual numbers, the targets, the
// propagator and its propagate, the bounds' rows, the solves a SOLVE module wraps, and the entry
// point.
// helios_runtime.hpp includes it; a program includes only that header.
// ---------------------------------------------------------------------------------------------
#pragma once

#include "runtime_records.hpp"

namespace helios_rt {

// The problem's numbers (times, units, the derivation's parameters) are run-time values of the
// program, not compiled constants, so that one compiled program serves every problem of its
// structure (helios-solve's compile cache, tools/lib/src/solve/README.md). Each is a global set
// from its literal, registered by name; `shoot --parameters FILE` replaces every one of them
// before anything reads them (load_parameters). Without a file the literals stand.
//   HELIOS_PARAMETER(Tmax, 3.3285303900382108);            // double Tmax
//   HELIOS_PARAMETER_ARRAY(kStateToPhysical, 1.0, 2.0);     // double kStateToPhysical[2]
struct ParameterRegistration {
  ParameterRegistration(const char* name, double* values, int count, bool array);
};
#define HELIOS_PARAMETER(name, value) \
  double name = value;                \
  const ::helios_rt::ParameterRegistration name##_parameter(#name, &name, 1, false)
#define HELIOS_PARAMETER_ARRAY(name, ...) \
  double name[] = {__VA_ARGS__};          \
  const ::helios_rt::ParameterRegistration name##_parameter(#name, name, sizeof(name) / sizeof(double), true)

// Reads a parameters file, {"schema": "helios/parameters", "values": {"NAME": number or [numbers]}},
// into the registered parameters: every one of them, no other name, finite numbers, an array's
// length. Throws std::runtime_error with a one-line message naming the file and the value.
void load_parameters(const std::string& path);

// Seconds since the program's first call.
double wall_seconds();

// ---- Dual numbers: the shooting function's exact first derivatives (forward mode) -------------
// The RESIDUAL module is a template on its scalar. On double it is the shooting function; on Dual
// each value has its derivatives in the variables (the shooting variables, or a leg's), the
// propagation carries them by the variational equations (with the switching-time and event-time
// corrections), and the result is the exact Jacobian. A Dual is its value and the row of its
// derivatives in the thread's tape (dual.hpp), so it is as small as a double's pair and a generated
// expression on it compiles about as fast as on double (with the derivatives inside the value,
// g++ took 78-146 s for S10's module). In namespace ad, so that only argument-dependent lookup
// finds its functions (sqrt, pow, ...): an unqualified sqrt on a double in the runtime stays std's.
namespace ad {

int width();  // the variables of the Jacobian being evaluated (set by dual_jacobian)

struct Dual {
  double v = 0;
  int id = -1;  // its derivatives' row in the thread's tape; -1: a constant (all zero)
  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT(google-explicit-constructor): a constant
};
// d a / d x_j, and a new Dual of `value` with the derivatives d[0 .. width()) (nullptr: a constant).
double derivative(const Dual& a, int j);
Dual with_derivatives(double value, const double* d);

// The operations, out of line in the library (a generated expression is a chain of calls).
Dual chain(Dual a, double value, double slope) noexcept;                  // f(a) with f'(a) = slope
Dual chain(Dual a, Dual b, double value, double da, double db) noexcept;  // f(a, b)
Dual operator+(Dual a) noexcept;
Dual operator-(Dual a) noexcept;
Dual operator+(Dual a, Dual b) noexcept;
Dual operator-(Dual a, Dual b) noexcept;
Dual operator*(Dual a, Dual b) noexcept;
Dual operator/(Dual a, Dual b) noexcept;
Dual operator+(Dual a, double b) noexcept;
Dual operator+(double a, Dual b) noexcept;
Dual operator-(Dual a, double b) noexcept;
Dual operator-(double a, Dual b) noexcept;
Dual operator*(Dual a, double b) noexcept;
Dual operator*(double a, Dual b) noexcept;
Dual operator/(Dual a, double b) noexcept;
Dual operator/(double a, Dual b) noexcept;
inline bool operator<(Dual a, Dual b) noexcept {
  return a.v < b.v;
}
inline bool operator>(Dual a, Dual b) noexcept {
  return a.v > b.v;
}
inline bool operator<=(Dual a, Dual b) noexcept {
  return a.v <= b.v;
}
inline bool operator>=(Dual a, Dual b) noexcept {
  return a.v >= b.v;
}
Dual sqrt(Dual a) noexcept;
Dual pow(Dual a, double k) noexcept;
Dual pow(Dual a, Dual b) noexcept;
Dual pow(double a, Dual b) noexcept;
Dual exp(Dual a) noexcept;
Dual log(Dual a) noexcept;
Dual sin(Dual a) noexcept;
Dual cos(Dual a) noexcept;
Dual tan(Dual a) noexcept;
Dual asin(Dual a) noexcept;
Dual acos(Dual a) noexcept;
Dual atan(Dual a) noexcept;
Dual atan2(Dual a, Dual b) noexcept;  // atan2(y = a, x = b)
Dual abs(Dual a) noexcept;

}  // namespace ad

using ad::Dual;

// Where the targets are (targets.hpp): a planet's (or an orbit body's) normalized state at
// normalized time t and its rate, and a coasting target's state at t1 from y0 at t0. On a Dual
// time, with their derivatives through it.
std::array<double, 6> ephemeris_state(const std::string& body, double t);
std::array<double, 6> ephemeris_rate(const std::string& body, double t);
std::array<double, 6> coast_state(const std::array<double, 6>& y0, double t0, double t1);
std::array<Dual, 6> ephemeris_state(const std::string& body, const Dual& t);
std::array<Dual, 6> ephemeris_rate(const std::string& body, const Dual& t);
std::array<Dual, 6> coast_state(const std::array<double, 6>& y0, double t0, const Dual& t1);

// Throttle modes (controls.hpp). With eps > 0, H is strictly convex in u: u = 0 where
// dH/du(0) >= 0, u = 1 where dH/du(1) <= 0, otherwise u solves dH/du = 0. At eps = 0 both slopes
// equal the switching function.
enum Mode : int { kOff = 0, kInterior = 1, kFull = 2 };
// The mode at y, and the optimal control in a mode (the RESIDUAL module's H at a free final time).
Mode mode_at(const double* y, const Multipliers& mult);
void control_in_mode(const double* y, Mode mode, const Multipliers& mult, double* control);

class Dop853;

// Integrates y from t0 to t1 under the optimal control, one mode at a time (propagator.hpp).
class Propagator {
 public:
  explicit Propagator(const Settings& s);
  ~Propagator();
  Propagator(const Propagator&) = delete;
  Propagator& operator=(const Propagator&) = delete;

  std::vector<Sample>* samples = nullptr;  // when set, every accepted step is recorded
  std::vector<Switch>* switches = nullptr;
  double max_step = INFINITY;  // limits steps when recording, for smooth plots

  // Multiple shooting (nodes.hpp): where set, each of the RESIDUAL module's arcs is propagated in
  // `segments` equal parts, and at every node (the start of each arc after the first, and between
  // parts) it continues from the node's values (ny each, in order) instead of its own, which minus
  // the node's are written to the defects; with `reached` instead, its own values (and the node's
  // time in `times`) are only appended.
  struct ArcNodes {
    int segments = 1;
    int arcs = 0, used = 0;  // arcs begun and nodes passed in this evaluation
    const double* values = nullptr;
    double* defects = nullptr;
    const Dual* dual_values = nullptr;
    Dual* dual_defects = nullptr;
    std::vector<double>* reached = nullptr;
    std::vector<double> times;
  };
  ArcNodes* nodes = nullptr;

  // Homotopy devices of the global search (search/), off by default. fuel_weight > 0: the
  // throttle of a minimum-time problem is priced as fuel, w lambda0 (Tmax/c)(u - eps u (1 - u))
  // added to H (its companion problem at a held final time; every propagation with this
  // propagator). end_rotation: the position and velocity triples of the state and the costates
  // are rotated by this row-major 3x3 matrix at the end of each call of the free function
  // propagate(prop, ...), so the rows compare the rotated end with the target (the
  // transfer-angle continuation).
  double fuel_weight = 0;
  const std::array<double, 9>* end_rotation = nullptr;
  // The next propagate continues the last arc from a node inside it: not a new arc, and its first
  // sample is not recorded again.
  bool continues_arc = false;

  // The bounds psi <= 0 (bounds.hpp): whether bound k is in the active set its settings carry
  // (Settings::active_bounds), and psi of each bound at the last evaluation (bound_row).
  bool bound_active(int k) const;
  std::vector<double> bound_values;
  // The window fraction shooting variable k is held at (Settings::window_edges), NaN where free.
  double held_fraction(int k) const;
  // The conditions g > 0 the rows leave to the runtime (the derivation's must_be_positive: the
  // rows also hold on the target's mirror), each g and its meaning at the last evaluation
  // (side_condition).
  struct SideValue {
    double g = INFINITY;
    const char* meaning = "";
  };
  std::vector<SideValue> side_values;

  // With `tangents`: also carries k tangent directions of z = (y, lambda0) by the variational
  // equations (the same steps as y, so they are the derivatives of the integration itself), with
  // the jump each switch makes in them.
  struct Tangents {
    double* Y;  // (ny + 1) x k, row-major; row ny (lambda0) is constant
    int k;
  };
  void propagate(double t0, double t1, double* y, const Multipliers& mult, Tangents* tangents = nullptr);

 private:
  // One step of y and the tangents from t to t + h in `mode` (y_new has ny entries).
  void tangent_step(double t, const double* y, double h, Mode mode, const Multipliers& mult, Tangents& tangents,
                    double* y_new);
  // The tangents' jump at a switch at y from mode `from` (stay function `crossed`) to mode `to`.
  static void switch_jump(double t, const double* y, Mode from, int crossed, Mode to, const Multipliers& mult,
                          Tangents& tangents);
  template <class Rhs>
  double locate_switch(Rhs& rhs, double t, const double* y, Mode mode, const Multipliers& mult, int crossed, double ga,
                       double gb, double b);
  int dip(double t, const double* y, const double* f0, double h, const double* y1, const double* f1, Mode mode,
          const Multipliers& mult, double& b, std::array<double, 2>& g_at_b);
  static Mode next_mode(Mode mode, int crossed, const Multipliers& mult);
  void record(double t, const double* y, Mode mode, const Multipliers& mult);

  const Settings& settings_;
  std::unique_ptr<Dop853> stepper_;
  std::unique_ptr<Dop853> tangent_stepper_;  // y and k tangents; its error is y's alone
  std::vector<double> tangent_work_;         // its step's state, slopes, results and matrix A
  int arc_ = 0;
};

// What the RESIDUAL module's template calls, on double and on Dual: the multipliers of the
// dynamics (lambda0, eps), the propagation from t0 to t1 (on Dual: by the variational equations,
// with the derivatives in t0 and t1), and H at (t, y) under the optimal control.
struct DualMultipliers {
  Dual lambda0;
  double eps;
};
inline Multipliers multipliers(double lambda0, double eps) {
  return {lambda0, eps};
}
inline DualMultipliers multipliers(const Dual& lambda0, double eps) {
  return {lambda0, eps};
}
void propagate(Propagator& prop, double t0, double t1, double* y, const Multipliers& mult);
void propagate(Propagator& prop, const Dual& t0, const Dual& t1, Dual* y, const DualMultipliers& mult);
double optimal_hamiltonian(double t, const double* y, const Multipliers& mult);
Dual optimal_hamiltonian(const Dual& t, const Dual* y, const DualMultipliers& mult);

// F and J (column-major) of a function of n variables at x, from the function on dual numbers:
// x seeded as the unit directions, so F's derivatives are J's columns.
void dual_jacobian(int n, const double* x, double* F, double* J,
                   const std::function<void(const Dual* x, Dual* F)>& dual_function);

// Row k of the shooting function for bound k: records psi (prop.bound_values) and returns it when
// the bound is active (prop.bound_active(k), the settings' active set), else the inactive
// expression (its multiplier).
double bound_row(Propagator& prop, int k, double psi, double inactive);
Dual bound_row(Propagator& prop, int k, const Dual& psi, const Dual& inactive);
// The row of a time window's transversality condition (its fraction is shooting variable k): the
// condition itself, or frac - held where the propagator's settings hold that window at an edge.
double window_row(Propagator& prop, int k, double frac, double transversality);
Dual window_row(Propagator& prop, int k, const Dual& frac, const Dual& transversality);
// Records side condition k, g > 0 (its value and meaning), on the propagator.
void side_condition(Propagator& prop, int k, double g, const char* meaning);
void side_condition(Propagator& prop, int k, const Dual& g, const char* meaning);

// The SOLVE module's calls: `initial_guess(rng, x)` draws a start, `admissible(x)` accepts a
// solution (lambda0 > 0).
using Guess = std::function<void(std::mt19937_64& rng, double* x)>;
using Admissible = std::function<bool(const double* x)>;
using Solve = std::function<Result(const Settings& s)>;
// Problems without interior events: the global search (search/pipeline.hpp).
Result homotopy_solve(const Settings& s, const Guess& initial_guess, const Admissible& admissible);
// Problems with interior events: search_attempts complete attempts (search/attempts.hpp).
Result events_homotopy_solve(const Settings& s, const LegPlan& legs, const EventPlan& events,
                             const Guess& initial_guess, const Admissible& admissible);
// Problems with bounds psi <= 0: the passes over their active set around `solve` (bounds.hpp).
Result two_pass_solve(const Settings& s, const std::vector<Bound>& bounds, const Solve& solve,
                      const Admissible& admissible);

// The entry point (report.hpp): reads the settings, solves, writes the outcome and trajectory.
int run(int argc, char** argv);

}  // namespace helios_rt

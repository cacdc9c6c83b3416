// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, public header (templates/runtime/helios_runtime.hpp): what a generated
// shooting program sees of the runtime, declarations only. The runtime itself (the other headers
// of templates/runtime, compiled by runtime.cpp) is the static library libhelios-runtime.a, built
// once with the tools; helios-solve compiles a program against this header and links it with the
// library.
//
// The program defines what the library calls:
//   - kProblem, the problem's shape (its sizes, units, names), read by the runtime at run time;
//   - the problem's numbers, each a HELIOS_PARAMETER (below), which a parameters file may replace;
//   - the modules DYNAMICS (dynamics, hamiltonian), SWITCH (direction_control, throttle_slopes
//     when the problem has a throttle), RESIDUAL (shooting_function; shooting_legs with events;
//     coast_dynamics with a coasting target) and SOLVE (solve_problem);
//   - main, which calls run.
// ---------------------------------------------------------------------------------------------
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios_rt {

// The largest problem the library's fixed-size arrays hold (run refuses a larger one).
constexpr int kMaxStates = 16;
constexpr int kMaxControls = 8;
constexpr int kMaxNY = 2 * kMaxStates;  // states then costates

// A body propagated on its Keplerian orbit instead of the ephemeris model: its elements a
// (normalized), e, i, raan, argp, mean anomaly (rad) and their epoch (normalized time), a
// HELIOS_PARAMETER_ARRAY of the program.
struct OrbitBody {
  const char* name;
  const double* elements;  // a, e, i_rad, raan_rad, argp_rad, mean_anomaly_rad, epoch
};

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

// The problem as the runtime reads it (the PROBLEM block's constants, defined by the program).
// Its numbers are references to the program's parameters, so they read the loaded values.
struct ProblemShape {
  const char* id;
  int num_states, num_controls;
  int throttle_index;  // -1: no throttle (one mode)
  int num_vars;
  int mass_index;     // -1: no mass state (a sail)
  bool minimum_fuel;  // the objective is the propellant (minimum fuel or initial mass), else the time
  const double& t0;
  const double& tf;      // the final time, or the upper end of its window when it is free
  const double& tf_min;  // the lower end of the final time's window (tf when it is fixed)
  const double& homotopy_start;
  const double &time_unit_days, &length_unit_km, &speed_unit_km_s, &epoch_mjd2000, &mass_unit_kg;
  const double& exhaust_velocity_m_s;
  const double& mu;
  const char* const* state_names;
  const char* const* state_columns;
  const double* state_to_physical;
  const char* const* control_names;
  const char* const* variable_names;
  const char* const* equation_names;
  const OrbitBody* orbit_bodies;
  int num_orbit_bodies;
};
extern const ProblemShape kProblem;

struct Multipliers {
  double lambda0 = 1;
  double eps = 1;
  // The companion problem's price of the throttle (search.hpp, minimum time from minimum fuel):
  // 0 in the problem itself. Set by the runtime's propagate from Propagator::fuel_weight.
  double fuel_weight = 0;
};

struct numerical_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// DYNAMICS module: state and costate right-hand sides and H at time t for a given control vector.
void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy);
double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult);
// SWITCH module: the continuous controls (all but the throttle) and dH/du at u = 0 and u = 1.
// A problem without a throttle (throttle_index < 0) has one mode and no throttle_slopes.
void direction_control(const double* y, double* control);
void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper);
// JACOBIAN module (generated from the derivation by GiNaC): the exact first derivatives in
// z = (y, lambda0) (nz = ny + 1 = 2 num_states + 1) of the right-hand side at fixed control,
// dfdz[i * nz + j] = d dy_i / d z_j and dfdu[i * nc + k] = d dy_i / d control_k (nc =
// num_controls), and of the direction law, dcontrol_dy[k * ny + j] (the throttle's row zero):
// the variational equations' pieces.
void dynamics_jacobian(double t, const double* y, const double* control, const Multipliers& mult, double* dfdz,
                       double* dfdu);
void direction_jacobian(const double* y, double* dcontrol_dy);
// With a throttle: d/dz_j of throttle_slopes' at_lower and at_upper (nz entries each).
void throttle_slopes_jacobian(const double* y, const Multipliers& mult, double* d_lower, double* d_upper);
// Unpowered dynamics of a coasting target (RESIDUAL module, when the problem has one).
void coast_dynamics(const double* y, double* dy);

// The solver settings (schemas/settings.schema.json lists them).
struct Settings {
  unsigned seed = 1;
  int max_attempts = 100000;
  double time_limit_s = 600;
  double rtol = 1e-13, atol = 1e-13;
  double hybrd_tol = 1e-12;
  double accept_residual = 1e-8;  // intermediate homotopy steps
  double final_residual = 1e-10;  // the gate at eps = 0
  double eps_start = kProblem.homotopy_start;
  double eps_min = 1e-6;  // below this the next step is eps = 0
  double eps_first_ratio = 0.5;
  int leg_attempts = 20;  // random guesses per leg before the attempt is abandoned
  // The global search (search.hpp): starts at eps_start are drawn until the Good-Turing chance
  // that the next one finds a new extremal is at most search_saturation (draws.hpp), at most
  // search_starts of them (0: no cap); the lowest-cost distinct extremals are continued to eps = 0
  // search_continued at a time (problems without interior events); complete attempts (problems
  // with them); its own time budget (0: only time_limit_s) and threads (0: the cores).
  int search_starts = 0;
  double search_saturation = 0.01;
  int search_continued = 4;
  int search_attempts = 4;
  double search_time_s = 60;
  int threads = 0;
  // Problems without interior events: every distinct extremal at eps_start continued (false: only
  // those whose cost there, a lower bound of their objective, can still beat the best); the
  // families of extremals explored by the transfer angle (families.hpp); a minimum-time problem
  // with a throttle also solved from its minimum-fuel companion (minimum_time.hpp).
  bool search_continue_all = false;
  bool search_families = true;
  bool search_fuel_companion = true;
  // The integrator's rtol and atol during the search (never tighter than rtol and atol; 0: those):
  // every distinct extremal it reaches at eps = 0 is then polished at rtol and atol.
  double search_tol = 1e-10;
  // The solution polished by multiple shooting (nodes.hpp): nodes at interior events and between
  // equal parts of each arc, at most this many days apart on average (0: not polished).
  double node_spacing_days = 200;
  int max_steps = 200000;  // integrator steps per arc
  // The shooting Jacobian: "exact" (the program's shooting_jacobian, hybrj) where the program has
  // one, else "finite-difference" (hybrd's forward differences).
  std::string jacobian = "exact";
  // A neighbour's converged shooting variables at eps = 0 (a sweep's cell, helios-solve
  // --warm-start), in kProblem.variable_names' order; empty: a cold start (the global search).
  std::vector<double> warm_start;
  // With a warm start: return the warm solve's result even when it fails, with no search (a
  // sweep's cross-check of a cell from a neighbour asks only what that neighbour's extremal reaches).
  bool warm_only = false;
};

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

struct Sample {
  int arc;  // samples of one propagate() call share an arc; H may jump only between arcs
  double t;
  std::array<double, kMaxNY> y;  // the first 2 num_states entries
  std::array<double, kMaxControls> control;
  double H, S;
};

struct Switch {
  double t;
  double throttle_after;
};

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

  // Homotopy devices of the global search (search.hpp), off by default. fuel_weight > 0: the
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

// The shooting function of the RESIDUAL module, with the bookkeeping hybrd1 needs.
void shooting_function(const double* x, double eps, Propagator& prop, double* F);
// Its exact Jacobian (RESIDUAL module, when the program has the JACOBIAN module): F and
// J[i + j * n] = dF_i / dx_j (column-major, as cminpack's hybrj takes it).
void shooting_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J);
// The shooting function on dual numbers of any width (RESIDUAL module, with the JACOBIAN module,
// of a problem without interior events; one with them has shooting_legs_dual): the Jacobian of a
// system built on it, such as multiple shooting's (nodes.hpp).
void shooting_function_dual(const Dual* x, double eps, Propagator& prop, Dual* F);
// F and J (column-major) of a function of n variables at x, from the function on dual numbers:
// x seeded as the unit directions, so F's derivatives are J's columns.
void dual_jacobian(int n, const double* x, double* F, double* J,
                   const std::function<void(const Dual* x, Dual* F)>& dual_function);

// Problems with interior events also have the shooting function by legs (RESIDUAL module):
// stop_at = k solves leg k alone (it ends at event k as if the trajectory ended there);
// stop_at = -1 is multiple shooting: after event k the costates restart from starts[k*n...] and
// their mismatch with the jump conditions is written to continuity[k*n...].
template <class T>
struct LegsOf {
  int stop_at = -1;
  const T* starts = nullptr;
  T* continuity = nullptr;
};
using Legs = LegsOf<double>;
void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs);
// The same on dual numbers (RESIDUAL module, with the JACOBIAN module): the legs' exact Jacobians.
void shooting_legs_dual(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs);
// shooting_legs_dual under shooting_legs's name: code written once for either scalar calls one.
inline void shooting_legs(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs) {
  shooting_legs_dual(x, eps, prop, F, legs);
}

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

// The events' own shooting variables and rows (RESIDUAL module), for the continuation onto the
// events (continuation.hpp). An event is passable when it is instantaneous and its state map is
// the identity with its parameters at 0: the trajectory of the problem without it (its
// multipliers and parameters 0, its epoch held) then solves every row of the event but its
// constraint c = 0.
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

// Row k of the shooting function for bound k: records psi and returns it when the bound is
// active, else the inactive expression (its multiplier).
double bound_row(int k, double psi, double inactive);
Dual bound_row(int k, const Dual& psi, const Dual& inactive);

// What a solve records: homotopy, leg and continuation steps, the search's extremals, the result.
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
  bool pruned = false;  // not continued: its cost at eps_start, a lower bound of its branch's objective, could not beat the best
  int arrived = -1;     // the extremal at eps = 0 it was continued to (-1: none)
  std::string origin;   // how it was found where not by a start (the transfer angle from another)
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
  bool polished = true;  // it converged again at the integrator's own tolerance (search_tol)
  bool bounded_tried = false;
  double bounded_objective = NAN;
  int bounded_passes = 0;
};

// A neighbour of an extremal looked for along its family (families.hpp): from the extremal at
// eps = 0 `from`, one revolution more (+1) or fewer (-1); how (already reached by the search, an
// extremal at eps_start of that count continued, or the transfer angle) and what it found (an
// extremal at eps = 0, -1: none).
struct FamilyProbe {
  int from = -1, direction = 0;
  double revolutions = 0;
  std::string how;
  int found = -1;
};

// What the global search did (search.hpp), for solution.json.
struct SearchRecord {
  std::string method;
  int threads = 1;
  int starts = 0;           // starts (or complete attempts) drawn
  int converged_start = 0;  // starts converged at eps_start (problems with events: events-off draws)
  int eventless_draws = 0;  // draws of the problem with its events off (passable events)
  int continued = 0;        // eps_start extremals continued to eps = 0
  int converged_final = 0;  // solves that reached eps = 0
  double seconds = 0;
  bool cut_by_time = false;
  // Whether the draws stopped saturated (draws.hpp), the Good-Turing chance of a new extremal per
  // draw where they stopped, and why they stopped.
  bool saturated = false;
  double unseen = 1;
  std::string stopped;
  std::vector<FamilyProbe> family;
  // A minimum-time problem's minimum-fuel companion (minimum_time.hpp): its draws at the held
  // final time and its distinct solutions (arrived: the extremal at eps = 0 reached from each).
  double companion_tf_days = 0;
  int companion_draws = 0, companion_converged = 0;
  std::vector<StartExtremal> companion_solutions;
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
  // Multiple shooting (nodes.hpp): the state and costates at each node (ny each; empty: single
  // shooting), their continuity defects, the nodes' times, and max|F| of x alone by single
  // shooting.
  std::vector<double> nodes, continuity, node_times;
  int node_segments = 1;  // each arc's parts
  double single_shooting_residual = NAN;
  double eps = 1;
  double max_residual = 0;
  int evaluations = 0;
  int attempts = 0;
  int iterations = 0;
  std::vector<HomotopyStep> homotopy;
  std::vector<ContinuationStep> continuation;
  SearchRecord search;
  // How the solve started: "cold" (the global search), "warm" (from Settings::warm_start) or
  // "cold-after-warm-failed"; start_detail says why when it is not plain.
  std::string start = "cold";
  std::string start_detail;
};

// The SOLVE module's calls: `initial_guess(rng, x)` draws a start, `admissible(x)` accepts a
// solution (lambda0 > 0).
using Guess = std::function<void(std::mt19937_64& rng, double* x)>;
using Admissible = std::function<bool(const double* x)>;
using Solve = std::function<Result(const Settings& s)>;
// Problems without interior events: the global search (search.hpp's MultiStart).
Result homotopy_solve(const Settings& s, const Guess& initial_guess, const Admissible& admissible);
// Problems with interior events: search_attempts complete attempts (search.hpp).
Result events_homotopy_solve(const Settings& s, const LegPlan& legs, const EventPlan& events,
                             const Guess& initial_guess, const Admissible& admissible);
// Problems with bounds psi <= 0: the passes over their active set around `solve` (bounds.hpp).
Result two_pass_solve(const Settings& s, const std::vector<Bound>& bounds, const Solve& solve,
                      const Admissible& admissible);

// SOLVE module: the whole solve.
Result solve_problem(const Settings& settings);

// The entry point (report.hpp): reads the settings, solves, writes the outcome and trajectory.
int run(int argc, char** argv);

}  // namespace helios_rt

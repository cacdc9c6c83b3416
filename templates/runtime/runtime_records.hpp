// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, records (templates/runtime/runtime_records.hpp): the records the
// runtime and a program share: the problem's shape, the settings, the legs' and events' plans,
// the bounds, and what a solve records (its steps, the search, the result and its status).
// helios_runtime.hpp includes it; a program includes only that header.
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

// What the search minimizes: the flight time, the propellant (minimum fuel or initial mass), or a
// Mayer term on the final state, phi = -|r(tf)| or -(|v(tf)|^2/2 - mu/|r(tf)|) (both maximized).
enum class Objective { time, propellant, final_radius, final_energy };

// The problem as the runtime reads it (the PROBLEM block's constants, defined by the program).
// Its numbers are references to the program's parameters, so they read the loaded values.
struct ProblemShape {
  const char* id;
  int num_states, num_controls;
  int throttle_index;  // -1: no throttle (one mode)
  int num_vars;
  int mass_index;  // -1: no mass state (a sail)
  Objective objective;
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
  // The final constraint still holds after a coast from any state that meets it (an orbit with the
  // position on it free, two-body dynamics): a transfer that arrives early may coast to the final
  // time (search/time_route.hpp's minimum time plus a coast). A program that does not say so: false.
  bool final_coast_keeps_target = false;
  // An engine of constant mass (no mass state): the rate of its L1 cost at full throttle from the
  // program's parameters, Tmax/c (the objective the propellant in kg) or Tmax/m (the delta-v in
  // m/s, where no exhaust velocity is given). A program with a mass state or none: nullptr.
  double (*throttle_cost_rate)() = nullptr;
  // The parameters the thrust is proportional to, jointly (the derivation's role thrust_scale: Tmax,
  // or a solar-electric engine's powers), nullptr-terminated: the thrust continuation multiplies
  // them all. A program that lists none: the parameter named Tmax, where it has one.
  const char* const* thrust_scale = nullptr;
  // The full-throttle mass flow follows the position (a solar-electric engine, whose thrust follows
  // the Sun's distance): the routes that assume a constant flow skip, saying so.
  bool mass_flow_varies = false;
};
extern const ProblemShape kProblem;  // the program defines it (module_interface.hpp)

struct Multipliers {
  double lambda0 = 1;
  double eps = 1;
  // The companion problem's price of the throttle (search/companion.hpp, minimum time from minimum fuel):
  // 0 in the problem itself. Set by the runtime's propagate from Propagator::fuel_weight.
  double fuel_weight = 0;
};

struct numerical_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The solver settings (schemas/settings.schema.json lists them).
struct Settings {
  unsigned seed = 1;
  int max_attempts = 100000;
  double time_limit_s = 3600;
  double rtol = 1e-13, atol = 1e-13;
  double hybrd_tol = 1e-12;
  double accept_residual = 1e-8;  // intermediate homotopy steps
  double final_residual = 1e-10;  // the gate at eps = 0
  double eps_start = kProblem.homotopy_start;
  double eps_min = 1e-6;  // below this the next step is eps = 0
  double eps_first_ratio = 0.5;
  int leg_attempts = 20;  // random guesses per leg before the attempt is abandoned
  // The global search (search/pipeline.hpp): starts at eps_start are drawn until the Good-Turing
  // chance that the next one finds a new extremal is at most search_saturation (search/draws.hpp),
  // at most search_starts of them (0: kDefaultStartCap); the lowest-cost distinct extremals are
  // continued to eps = 0 search_continued at a time (problems without interior events); complete
  // attempts (problems with them); threads (0: the cores). Every stopping rule counts work: a run
  // stops on the clock only at time_limit_s (the safety net, said in the record), or at
  // search_time_s where a user sets one (0, the default: none).
  int search_starts = 0;
  double search_saturation = 0.01;
  int search_continued = 4;
  int search_attempts = 4;
  double search_time_s = 0;
  int threads = 0;
  // Problems without interior events: every distinct extremal at eps_start continued (false: only
  // those whose cost there, a lower bound of their objective, can still beat the best); the
  // families of extremals explored by the transfer angle (search/families.hpp); a minimum-time problem
  // with a throttle also solved from its minimum-fuel companion (search/companion.hpp).
  bool search_continue_all = false;
  bool search_families = true;
  bool search_fuel_companion = true;
  bool search_thrust_continuation = true;
  // A minimum-fuel problem at a fixed final time also solved from its minimum-time extremal
  // (search/time_route.hpp): "always" (the default: starts that saturate can miss the best extremal,
  // and where they settle the route is cheap), "auto" only where the search leaves it unsettled
  // (as for the thrust continuation: many revolutions or no extremal, the starts not saturated),
  // "never".
  std::string search_fuel_from_time = "always";
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
  // Not a settings file's: the active set of the bounds psi <= 0 (bounds.hpp's passes set it on
  // their copy of the settings), bound k active where active_bounds[k] != 0 (none: every bound
  // inactive). Each propagator reads it from its settings (Propagator::bound_active), so every
  // thread of a search sees the set of the solve it belongs to.
  std::vector<char> active_bounds;
  // Not a settings file's: the time windows held at an edge (search/edge.hpp), per shooting
  // variable: NaN (or past the end) where the variable is free, else the window fraction its
  // transversality row is replaced by (window_row: the row becomes x_k - held).
  std::vector<double> window_edges;
};

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
  double revolutions = NAN;  // of the solution reached, where the continuation follows them
  double tf_days = NAN;      // its flight time, where the continuation follows the thrust
};

// Where a continuation path arrived (search/companion.hpp, search/thrust.hpp): the problem's own
// extremal at its end, if it got there, and every step on the way.
struct PathArrival {
  bool arrived = false;
  double reached = NAN;       // the path's parameter where it stopped (its last converged step)
  double reached_time = NAN;  // the flight time there (normalized), where the path knows it
  std::vector<double> x, F;
  double max_residual = INFINITY;
  int info = 0;
  std::vector<ContinuationStep> steps;
};

// What tells one extremal from another (homotopy.hpp's shape_of): the revolutions about the
// central body (the angle the position sweeps about the initial angular momentum, over 2 pi), the
// throttle's mode changes (at eps = 0 its bang-bang switches), and the cost at its eps: the
// propellant of the smoothed problem (the integral of u - eps u (1 - u), in propellant units) for
// a throttle, else the flight time. At eps = 0 the cost is the objective.
struct Shape {
  double revolutions = 0;
  int switches = 0;
  double cost = INFINITY;
  // The meaning of the first side condition g > 0 that fails (the extremal ends on the mirror of
  // a target: derivation's must_be_positive), empty when all hold: such an extremal is never returned.
  std::string off_side;
};

// A distinct solution at eps_start, and how many starts reached it.
struct StartExtremal {
  std::vector<double> x;
  Shape shape;
  double max_residual = 0;
  int first_start = 0, reached = 0;
  bool continued = false;
  bool pruned =
      false;  // not continued: its cost at eps_start, a lower bound of its branch's objective, could not beat the best
  int arrived = -1;    // the extremal at eps = 0 it was continued to (-1: none)
  std::string origin;  // how it was found where not by a start (the transfer angle from another)
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
  // Its free final time lies outside the final time's window (never returned; search/pool.hpp).
  bool outside_window = false;
  // Its final time in days where the final time is free (the window's check and an infeasibility
  // verdict read it), NaN where it is fixed.
  double tf_days = NAN;
  std::string route;  // the route of the search that reached it first (search/pipeline.hpp)
  // The window edges it is an extremal at (Settings::window_edges; empty: none held), and there the
  // released transversality row's value, which the edge's cost gradient is (search/edge.hpp).
  std::vector<double> window_edges;
  double edge_transversality = NAN;
  bool bounded_tried = false;
  double bounded_objective = NAN;
  int bounded_passes = 0;
};

// A neighbour of an extremal looked for along its family (search/families.hpp): from the extremal at
// eps = 0 `from`, one revolution more (+1) or fewer (-1); how (already reached by the search, an
// extremal at eps_start of that count continued, or the transfer angle) and what it found (an
// extremal at eps = 0, -1: none).
struct FamilyProbe {
  int from = -1, direction = 0;
  double revolutions = 0;
  std::string how;
  int found = -1;
};

// What the global search did (search/pipeline.hpp), for solution.json.
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
  // Whether the draws stopped saturated (search/draws.hpp), the Good-Turing chance of a new extremal per
  // draw where they stopped, and why they stopped.
  bool saturated = false;
  double unseen = 1;
  std::string stopped;
  std::vector<FamilyProbe> family;
  // A minimum-time problem's minimum-fuel companion (search/companion.hpp): its draws at the held
  // final time and its distinct solutions (arrived: the extremal at eps = 0 reached from each).
  double companion_tf_days = 0;
  int companion_draws = 0, companion_converged = 0;
  std::vector<StartExtremal> companion_solutions;
  // The thrust continuation of a many-revolution transfer (search/thrust.hpp): every search
  // at a raised thrust and every step down, and whether it arrived at the problem's thrust.
  std::vector<ContinuationStep> thrust_continuation;
  bool thrust_continuation_arrived = false;
  // A minimum-fuel problem's route from its minimum-time extremals (search/time_route.hpp): each path
  // (where it started, the minimum time it reached, whether that one was reached before, the
  // extremal at eps = 0 it arrived at) and every step.
  struct TimeRoutePath {
    std::string from;
    double tf_min_days = NAN, revolutions = NAN;
    bool reached_before = false;
    int extremal = -1;
  };
  std::vector<TimeRoutePath> time_route_paths;
  std::vector<ContinuationStep> time_route;
  std::vector<StartExtremal> start_extremals;
  std::vector<Extremal> extremals;
  int returned = -1;  // index into extremals
  std::string reason;
  // What each route of the search did (search/pipeline.hpp), in the order they ran: its name, what
  // it found or why it was skipped, the extremals at eps = 0 it added and its function evaluations.
  struct RouteRun {
    std::string name, outcome;
    int added = 0, evaluations = 0;
    bool ran = false;
  };
  std::vector<RouteRun> routes;
  // The shortest final time at which the transfer was found possible (days; NaN: not sought), how,
  // and whether the search for it settled; the stated bound it is compared with (a minimum-time
  // problem's window end or a fixed time of flight). Where it exceeds the bound the verdict is
  // infeasible (search/chooser.hpp).
  double minimum_time_days = NAN, bound_days = NAN;
  bool minimum_time_settled = false;
  std::string minimum_time_how;
  // A minimum-time problem's time scale, measured by a search at a raised thrust where the
  // window allows many revolutions (search/scale.hpp): the factor, the minimum time and revolutions
  // found there, and what they make of the problem's own (the flight time inversely proportional to
  // the thrust).
  struct TimeScale {
    double factor = 0, raised_tf_days = NAN, raised_revolutions = NAN, estimate_days = NAN, revolutions = NAN;
    bool saturated = false;  // the starts of the search there saturated
  } time_scale;
  // A minimum-fuel problem whose final constraint a coast keeps (final_coast_keeps_target): the
  // propellant of its minimum-time transfer completed by a coast to the final time (normalized;
  // NaN: none), a feasible transfer no returned extremal may cost more than (search/chooser.hpp).
  double coast_bound = NAN;
  // The run's time limit (time_limit_s) was reached: the one way two runs of a seed may differ.
  bool time_limit_hit = false;
};

// How a solve ended. The default says the solver did not run (a Result nobody solved); the
// runtime's solves end converged, infeasible (the transfer needs longer than the problem allows,
// with the minimum time that shows it), not converged or timed out. Its text (status_text) is
// written only where solution.json and stdout are.
enum class Status { kNotSolved, kConverged, kInfeasible, kNotConverged, kTimeout };
// "not_solved", "converged", "infeasible", "not_converged", "timeout": solution.json's status.
const char* status_text(Status status);

struct Result {
  Status status = Status::kNotSolved;
  std::string method = "single shooting";
  int passes = 1;
  std::vector<BoundReport> bounds;
  // The window edges the solution is held at, and its released transversality row (Extremal's).
  std::vector<double> window_edges;
  double edge_transversality = NAN;
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

}  // namespace helios_rt

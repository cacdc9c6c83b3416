// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, outcome (templates/runtime/outcome.hpp): what a solve records: homotopy,
// leg and continuation steps, the search's extremals, the result.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

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

}  // namespace helios_rt

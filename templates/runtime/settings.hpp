// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, settings (templates/runtime/settings.hpp): the solver settings
// (schemas/settings.schema.json lists them) and the wall clock.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

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

inline double wall_seconds() {
  using clock = std::chrono::steady_clock;
  static const auto start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the warm start (templates/runtime/search/warm.hpp): a sweep's cell
// solved from its converged neighbour's shooting variables, without a search; where that fails the
// pipeline (pipeline.hpp) searches cold.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The warm start: the neighbour's shooting variables at eps = 0 as the first guess, in the
// normalized units of the runtime (the length, time and mass units do not depend on the epoch or
// the flight time, so a neighbour's costates at its departure are this cell's guess at its own;
// they are not propagated). First a direct solve at eps = 0, then continuations in eps from
// small smoothing (1e-2, then 1e-1) down to 0, each from the neighbour's variables. The first to
// reach eps = 0 is the result; none: r.detail says so and the caller searches cold.
template <class Admissible>
Result warm_solve(const Settings& s, Admissible& admissible) {
  Result r;
  r.status = Status::kNotConverged;  // until a warm solve reaches eps = 0
  r.start = "warm";
  r.search.method = "warm start from a neighbour's solution (no search)";
  r.search.threads = 1;
  const double started = wall_seconds();
  int evaluations = 0;
  bool ok = false;
  std::vector<double> x;
  for (const double eps0 : {0.0, 1e-2, 1e-1}) {
    if (out_of_time(s)) break;
    x = s.warm_start;
    Result path;
    Shooter shooter(s, kContinuationStart);
    double res = 0;
    int info = 0;
    try {
      if (eps0 == 0) {
        ok = homotopy_step(shooter, x, 0.0, s.final_residual, path, admissible, info, res);
        path.x_start = x;
        path.info = info;
      } else {
        Settings from = s;
        from.eps_start = eps0;
        ok = homotopy_to_zero(from, shooter, x, path, admissible, res);
      }
    } catch (const numerical_error&) {
      ok = false;
    }
    evaluations += shooter.evaluations;
    r.iterations += path.iterations;
    r.homotopy.insert(r.homotopy.end(), path.homotopy.begin(), path.homotopy.end());
    if (!ok) continue;
    r.status = Status::kConverged;
    r.x = x;
    r.x_start = path.x_start;
    r.F = shooter.last_F;
    r.eps = 0;
    r.max_residual = res;
    r.info = path.info;
    r.method = eps0 == 0 ? "single shooting at eps = 0 from a neighbour's solution"
                         : "single shooting, eps continuation from " + std::to_string(eps0).substr(0, 4) +
                               " starting at a neighbour's solution";
    break;
  }
  r.evaluations = evaluations;
  r.attempts = 1;
  r.search.seconds = wall_seconds() - started;
  if (!ok) r.detail = "the warm start from the neighbour's solution did not reach eps = 0";
  return r;
}

}  // namespace

}  // namespace helios_rt

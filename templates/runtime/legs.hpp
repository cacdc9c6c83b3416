// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, legs (templates/runtime/legs.hpp): problems with interior events: the
// legs solved alone, joined by multiple shooting.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The legs solved alone joined: from their variables x and each later leg's start state
// (`starts`), multiple shooting over [x, starts] (F = [the problem's equations, costate
// continuity]) continued in eps to 0, then polished by single shooting. True when it converged (r
// then holds the solution).
template <class Admissible>
bool join_legs(const Settings& s, std::vector<double> x, const std::vector<double>& starts, Admissible& admissible,
               Shooter& single, Result& r, int& evaluations) {
  const int N = kProblem.num_vars;
  const int size = N + static_cast<int>(starts.size());
  const auto multiple = [N](const auto* z, double eps, Propagator& prop, auto* F) {
    using T = std::remove_cv_t<std::remove_pointer_t<decltype(z)>>;
    const LegsOf<T> legs{-1, z + N, F + N};
    legs_function(z, eps, prop, F, &legs);
  };
  Shooter shooter(s, function_on_either_scalar(size, multiple));
  std::vector<double> z(x);
  z.insert(z.end(), starts.begin(), starts.end());
  double res = 0;
  bool converged = false;
  if (homotopy_to_zero(s, shooter, z, r, admissible, res)) {
    x.assign(z.begin(), z.begin() + N);
    int info = 0;
    if (homotopy_step(single, x, 0.0, s.final_residual, r, admissible, info, res)) {
      r.status = Status::kConverged;
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

// Problems with interior events (the RESIDUAL module's LegPlan): an attempt first solves the
// legs one after the other at eps_start, each as if the trajectory ended at its event (leg k
// starts from the state leg k-1 reached); from those, multiple shooting over all legs is
// continued in eps to 0 and the solution is polished by single shooting. The legs are small
// problems that converge from random guesses where the whole one rarely does. True when the
// attempt converged (r then holds the solution).
template <class Guess, class Admissible>
bool legs_attempt(const Settings& s, const LegPlan& plan, Guess&& initial_guess, Admissible&& admissible,
                  std::mt19937_64& rng, Shooter& single, Result& r, int& evaluations) {
  const int n = kProblem.num_states, N = kProblem.num_vars;
  const int events = static_cast<int>(plan.variables.size()) - 1;
  std::uniform_real_distribution<double> symmetric(-1.0, 1.0);
  std::vector<double> x(N), starts(static_cast<std::size_t>(events * n));
  const auto guess = [&] {
    initial_guess(rng, x.data());
    for (const int i : plan.held_at_zero) x[i] = 0;
    if (r.attempts == 1)
      for (const int i : plan.time_fractions) x[i] = 0.5;  // first attempt: the middle of every window
    const std::vector<char>& active = s.active_bounds;
    for (const auto& w : plan.window_edges)
      if (static_cast<std::size_t>(w.bound) < active.size() && active[w.bound]) x[w.fraction] = w.edge;
  };
  guess();
  bool legs_solved = true;
  for (int k = 0; k <= events && legs_solved; ++k) {
    const auto& own = plan.variables[k];
    const int m = static_cast<int>(own.size()) + (k > 0 ? n : 0);
    // Leg k's variables z in the whole x and the starts, on double or on Dual.
    const auto leg_call = [&, k](const auto* z, double eps, Propagator& prop, auto* F) {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(z)>>;
      std::vector<T> xx(x.begin(), x.end()), st(starts.begin(), starts.end());
      for (std::size_t j = 0; j < own.size(); ++j) xx[own[j]] = z[j];
      if (k > 0)
        for (int i = 0; i < n; ++i) st[(k - 1) * n + i] = z[own.size() + i];
      const LegsOf<T> legs{k, st.data(), nullptr};
      legs_function(xx.data(), eps, prop, F, &legs);
    };
    Shooter shooter(s, function_on_either_scalar(m, leg_call));
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
  return legs_solved && join_legs(s, x, starts, admissible, single, r, evaluations);
}

}  // namespace

}  // namespace helios_rt

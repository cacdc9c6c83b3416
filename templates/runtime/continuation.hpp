// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, continuation (templates/runtime/continuation.hpp): problems with
// passable events: the continuation from the problem without them onto them.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

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

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, continuation (templates/runtime/continuation.hpp): problems with
// passable events: the continuation from the problem without them onto them.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// One attempt of the continuation onto the events, all at eps_start, as five stages that each
// solve from the point the last one reached (x: the shooting variables, and `reference`: each
// event's held epoch as a window fraction):
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
// Every solve of the first four is recorded in r.continuation, the last one's in r.homotopy.
template <class Guess, class Admissible>
class EventContinuation {
 public:
  EventContinuation(const Settings& s, const EventPlan& plan, Guess& initial_guess, Admissible& admissible,
                    std::mt19937_64& rng, Result& r)
      : s_(s),
        plan_(plan),
        initial_guess_(initial_guess),
        admissible_(admissible),
        rng_(rng),
        r_(r),
        eps_(s.eps_start),
        nev_(static_cast<int>(plan.events.size())),
        N(kProblem.num_vars),
        reference_(static_cast<std::size_t>(nev_), 0.5),
        prop_(s),
        F_(N),
        off_(
            s, [this](const double* x, double e, Propagator& p, double* F, double* J) { held_off(x, e, p, F, J); },
            kContinuationStart) {}

  // The stages after events off, from the events-off solution `eventless`; `use` counts the
  // attempts from it before this one: the first (0) places the epochs closest to the targets,
  // later ones draw them. True when it converged (r then holds the solution).
  bool run(const std::vector<double>& eventless, int use) {
    x_ = eventless;
    const bool closest = use == 0;
    return epochs(closest) && targets() && parameters(closest) && eps_to_zero();
  }

  // Events off from one scale-free random guess (the stage's draw `draw`): true with the solution
  // in `eventless` when it converged.
  bool solve_eventless(int draw, std::vector<double>& eventless) {
    if (!events_off(draw)) return false;
    eventless = x_;
    return true;
  }

  // The function evaluations of every stage run.
  int evaluations() const { return evaluations_ + off_.evaluations; }

 private:
  // The problem with its events off: each event's rows hold its variables at their off values
  // (with J, the rows' Jacobian too: a unit row each).
  void held_off(const double* x, double eps, Propagator& prop, double* F, double* J) const {
    shooting_function_and_jacobian(x, eps, prop, F, J);
    const auto hold = [&](int row, int v, double value) {
      F[row] = value;
      if (J) unit_row(J, N, row, v);
    };
    for (int k = 0; k < nev_; ++k) {
      const EventRows& e = plan_.events[k];
      for (const auto& [v, row] : e.constraints) hold(row, v, x[v]);
      if (e.epoch[0] >= 0) hold(e.epoch[1], e.epoch[0], x[e.epoch[0]] - reference_[k]);
      for (const auto& [v, row] : e.parameters) hold(row, v, x[v]);
    }
  }

  // Sets each event's variables to their off values: nu = 0, parameters 0, epochs at the reference.
  void snap(std::vector<double>& x) const {
    for (int k = 0; k < nev_; ++k) {
      const EventRows& e = plan_.events[k];
      for (const auto& [v, row] : e.constraints) x[v] = 0;
      if (e.epoch[0] >= 0) x[e.epoch[0]] = reference_[k];
      for (const auto& [v, row] : e.parameters) x[v] = 0;
    }
  }

  // With the event off its jump rows read lambda(t-) - lambda(t+) = 0: the costates after it that are
  // shooting variables are set to those before it (event by event, as each one moves the next).
  void carry_costates(std::vector<double>& x) {
    for (int pass = 0; pass < nev_; ++pass) {
      try {
        shooting_function(x.data(), eps_, prop_, F_.data());
      } catch (const numerical_error&) {
        return;
      }
      for (const auto& e : plan_.events)
        for (const auto& [v, row] : e.costates)
          if (std::isfinite(F_[row])) x[v] += F_[row];
    }
  }

  // One recorded solve of a stage at eps_start: true when it converged to an admissible x.
  bool solve(Shooter& shooter, std::vector<double>& x, const char* stage, double value) {
    int info = 0;
    double res = 0;
    ++r_.iterations;
    const bool ok = shooter.solve(x, eps_, s_.accept_residual, info, res) && admissible_(x.data());
    r_.continuation.push_back({stage, value, ok, res, shooter.last_step_evaluations});
    return ok;
  }

  // A scale-free random guess with the events off (see the stages above).
  void draw_eventless_guess() {
    initial_guess_(rng_, x_.data());
    double norm2 = 0;
    for (const int i : plan_.sphere) {
      x_[i] = i == plan_.multiplier ? 1.0 : (unit_(rng_) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, -3.0 + 3.0 * unit_(rng_));
      norm2 += x_[i] * x_[i];
    }
    for (const int i : plan_.sphere) x_[i] /= std::sqrt(norm2);
    snap(x_);
    carry_costates(x_);
  }

  // Events off, from a scale-free random guess, in the variables and rows of no event (the
  // event's own are set from them: nu = 0, parameters 0, epochs at the reference, the costates
  // after it carried over); when those are not as many, in all of them with the event's rows held.
  // Recorded as the events-off solve `draw`.
  bool events_off(int draw) {
    std::vector<int> own_variables, own_rows;
    {
      std::vector<bool> event_variable(N), event_row(N);
      for (const auto& e : plan_.events) {
        for (const auto* pairs : {&e.constraints, &e.parameters, &e.costates})
          for (const auto& [v, row] : *pairs) event_variable[v] = event_row[row] = true;
        if (e.epoch[0] >= 0) event_variable[e.epoch[0]] = event_row[e.epoch[1]] = true;
      }
      for (int i = 0; i < N; ++i) {
        if (!event_variable[i]) own_variables.push_back(i);
        if (!event_row[i]) own_rows.push_back(i);
      }
    }
    x_.assign(N, 0.0);
    const bool reduced = own_variables.size() == own_rows.size();
    std::vector<double> base(N);
    // The whole x (on z's scalar) from the own variables z, the rest at base's values.
    const auto expand = [&](const auto* z, auto& xx) {
      xx.assign(base.begin(), base.end());
      for (std::size_t j = 0; j < own_variables.size(); ++j) xx[own_variables[j]] = z[j];
    };
    // The eventless rows G of the own variables z, on double or on Dual: the costates after each
    // event carried over (xx[v] += its jump row) as often as there are events.
    const auto eventless = [&](const auto* z, double e, Propagator& p, auto* G) {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(z)>>;
      std::vector<T> xx, FF(N);
      expand(z, xx);
      for (int pass = 0; pass <= nev_; ++pass) {
        legs_function(xx.data(), e, p, FF.data(), static_cast<const LegsOf<T>*>(nullptr));
        bool carried = false;
        for (const auto& ev : plan_.events)
          for (const auto& [v, row] : ev.costates) {
            xx[v] = xx[v] + FF[row];
            carried = true;
          }
        if (!carried) break;
      }
      for (std::size_t j = 0; j < own_rows.size(); ++j) G[j] = FF[own_rows[j]];
    };
    Shooter shooter_eventless(s_, function_on_either_scalar(static_cast<int>(own_variables.size()), eventless),
                              kContinuationStart);
    draw_eventless_guess();
    if (!reduced) return solve(off_, x_, "events off", draw);
    base = x_;
    std::vector<double> z(own_variables.size());
    for (std::size_t j = 0; j < z.size(); ++j) z[j] = x_[own_variables[j]];
    int info = 0;
    double res = 0;
    ++r_.iterations;
    bool off_solved = shooter_eventless.solve(z, eps_, s_.accept_residual, info, res);
    expand(z.data(), x_);
    carry_costates(x_);
    off_solved = off_solved && admissible_(x_.data());
    r_.continuation.push_back(
        {"events off", static_cast<double>(draw), off_solved, res, shooter_eventless.last_step_evaluations});
    evaluations_ += shooter_eventless.evaluations;
    return off_solved;
  }

  // The squared offset of event k's target from trajectory z (its c rows; INFINITY where z fails).
  double target_offset(const std::vector<double>& z, int k) {
    try {
      shooting_function(z.data(), eps_, prop_, F_.data());
    } catch (const numerical_error&) {
      return INFINITY;
    }
    double d2 = 0;
    for (const auto& [v, row] : plan_.events[k].constraints) d2 += F_[row] * F_[row];
    return std::isfinite(d2) ? d2 : INFINITY;
  }

  // Reference epochs: where the eventless trajectory passes closest to each target (on 41 points
  // of its window: the first attempt from the eventless solution), or at random (later ones).
  bool epochs(bool closest) {
    for (int k = 0; k < nev_; ++k) {
      const int v = plan_.events[k].epoch[0];
      if (v < 0) continue;
      if (closest) {
        std::vector<double> z = x_;
        double best = INFINITY;
        for (int j = 0; j <= 40; ++j) {
          z[v] = j / 40.0;
          const double d = target_offset(z, k);
          if (d < best) {
            best = d;
            reference_[k] = z[v];
          }
        }
      } else {
        reference_[k] = unit_(rng_);
      }
      x_[v] = reference_[k];
    }
    snap(x_);
    carry_costates(x_);
    if (!solve(off_, x_, "epochs", 0)) return false;
    snap(x_);  // exactly 0: a finite-difference step on a variable of 1e-80 would be lost
    return true;
  }

  // Targets: the Newton homotopy from the eventless trajectory's offsets F0, tau 0 -> 1 in
  // adaptive steps, each from a secant predictor along the path, or where the path bends from x
  // itself.
  bool targets() {
    std::vector<double> F0(N);
    try {
      shooting_function(x_.data(), eps_, prop_, F0.data());
    } catch (const numerical_error&) {
      return false;
    }
    double tau = 0;
    const Function toward_targets = [&](const double* z, double e, Propagator& p, double* G, double* J) {
      shooting_function_and_jacobian(z, e, p, G, J);
      for (int i = 0; i < N; ++i) G[i] -= (1 - tau) * F0[i];
      for (const auto& ev : plan_.events)
        for (const auto& [v, row] : ev.parameters) {
          G[row] = z[v];
          if (J) unit_row(J, N, row, v);
        }
    };
    Shooter shooter(s_, toward_targets, kContinuationStart);
    std::vector<double> previous = x_;
    double tau_previous = 0, step = 0.1;
    bool reached = false;
    while (!reached && wall_seconds() <= s_.time_limit_s) {
      const double from = tau, next = std::min(1.0, tau + step);
      std::vector<double> trial = x_;
      tau = next;
      bool solved = false;
      if (from > 0) {
        for (int i = 0; i < N; ++i) trial[i] += (x_[i] - previous[i]) / (from - tau_previous) * (next - from);
        solved = solve(shooter, trial, "targets", next);
        if (!solved) trial = x_;
      }
      if (solved || solve(shooter, trial, "targets", next)) {
        previous = x_;
        tau_previous = from;
        x_ = trial;
        reached = next >= 1.0;
        step *= 1.5;
      } else {
        tau = from;
        step *= 0.5;
        if (step < 1e-3) break;
      }
    }
    evaluations_ += shooter.evaluations;
    return reached;
  }

  // Parameters: from 0 to stationarity, kappa from large to 0 (none: nothing to do).
  bool parameters(bool closest) {
    double stationarity = 0;
    try {
      shooting_function(x_.data(), eps_, prop_, F_.data());
    } catch (const numerical_error&) {
      return false;
    }
    for (const auto& ev : plan_.events)
      for (const auto& [v, row] : ev.parameters) {
        has_parameters_ = true;
        stationarity = std::max(stationarity, std::fabs(F_[row]));
      }
    if (!has_parameters_) return true;
    double kappa = 0;
    // The penalty's weight of each parameter: 1 on the first attempt from the eventless solution,
    // log-uniform in [0.1, 10] on later ones, so that they follow other paths.
    std::vector<double> weight(N, 1.0);
    if (!closest)
      for (auto& w : weight) w = std::pow(10.0, -1.0 + 2.0 * unit_(rng_));
    const Function penalized = [&](const double* z, double e, Propagator& p, double* G, double* J) {
      shooting_function_and_jacobian(z, e, p, G, J);
      const int m = plan_.multiplier;
      for (const auto& ev : plan_.events)
        for (const auto& [v, row] : ev.parameters) {
          const double k = kappa * weight[v];
          G[row] += k * z[m] * z[v];
          if (J) {
            J[row + v * N] += k * z[m];
            J[row + m * N] += k * z[v];
          }
        }
    };
    Shooter shooter(s_, penalized, kContinuationStart);
    // The first kappa moves the parameters by about 1e-3.
    const double start = stationarity > 0 ? stationarity / (1e-3 * x_[plan_.multiplier]) : 1.0;
    // The predictor: the path's tangent dx/dkappa at the last solution (with the exact Jacobian),
    // else the secant in log(kappa) from the last two solutions (the parameters move fast where
    // kappa meets the cost's own curvature).
    std::vector<double> previous, tangent;  // the solution before x on the path (none before the first kappa)
    double log_previous = 0, log_current = 0, current = 0;
    bool on_path = false;     // x solves at log_current (before the first kappa it holds p = 0)
    bool tangent_ok = false;  // `tangent` is the path's at x (kappa = current)
    const auto path_tangent = [&] {
      std::vector<double> G, J, dG(N, 0.0);
      if (!shooter.jacobian_at(x_, eps_, G, J)) return false;
      for (const auto& ev : plan_.events)
        for (const auto& [v, row] : ev.parameters) dG[row] = weight[v] * x_[plan_.multiplier] * x_[v];
      tangent.resize(N);
      for (int i = 0; i < N; ++i) tangent[i] = -dG[i];
      return solve_linear(N, J, tangent);
    };
    const bool ok = continue_to_zero(s_, start, [&](double value) {
      kappa = value;
      std::vector<double> trial = x_;
      bool solved = false;
      if (on_path && (tangent_ok || (value > 0 && !previous.empty()))) {
        for (int i = 0; i < N; ++i)
          trial[i] += tangent_ok
                          ? tangent[i] * (value - current)
                          : (x_[i] - previous[i]) * (std::log(value) - log_current) / (log_current - log_previous);
        solved = solve(shooter, trial, "parameters", value);
        if (!solved) trial = x_;  // the path bends: from the last solution itself
      }
      if (!solved && !solve(shooter, trial, "parameters", value)) return false;
      if (value > 0) {
        if (on_path) {
          previous = x_;
          log_previous = log_current;
        }
        log_current = std::log(value);
        on_path = true;
      }
      x_ = trial;
      current = value;
      tangent_ok = value > 0 && path_tangent();
      return true;
    });
    evaluations_ += shooter.evaluations;
    return ok;
  }

  // A parameter that moves nothing at the solution z (a swing-by's plane angle at delta = 0 or
  // pi) leaves its stationarity row satisfied for any value: a coordinate pole, not an optimum.
  bool at_pole(const std::vector<double>& z) {
    std::vector<double> G0(N), G(N);
    try {
      shooting_function(z.data(), 0.0, prop_, G0.data());
      for (const auto& ev : plan_.events)
        for (const auto& [v, row] : ev.parameters) {
          std::vector<double> moved = z;
          moved[v] += 1e-4;
          shooting_function(moved.data(), 0.0, prop_, G.data());
          double change = 0, size = 0;
          for (int i = 0; i < N; ++i) {
            bool own = false;
            for (const auto& e2 : plan_.events)
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
  }

  // eps to 0 on the whole problem (to the intermediate gate), then the polish to the final gate:
  // hybrd1 from there, else once more from the continuation's start. Fills r when it converged.
  bool eps_to_zero() {
    Settings to_zero = s_;
    to_zero.final_residual = std::max(s_.final_residual, s_.accept_residual);
    Shooter full(s_, kContinuationStart), polish(s_);
    double res = 0;
    int info = 0;
    bool converged = homotopy_to_zero(to_zero, full, x_, r_, admissible_, res);
    if (converged) {
      std::vector<double> y = x_;
      Shooter* last = &polish;
      converged = homotopy_step(polish, y, 0.0, s_.final_residual, r_, admissible_, info, res);
      if (!converged) {
        y = x_;
        last = &full;
        converged = homotopy_step(full, y, 0.0, s_.final_residual, r_, admissible_, info, res);
      }
      if (converged && has_parameters_ && at_pole(y)) converged = false;
      if (converged) {
        r_.status = Status::kConverged;
        r_.method = std::string("events off, then continuation onto the events' targets") +
                    (has_parameters_ ? ", then their parameters" : "") +
                    ", then eps continuation, then single shooting";
        r_.info = info;
        r_.x = y;
        r_.F = last->last_F;
        r_.eps = 0;
        r_.max_residual = res;
      }
    }
    evaluations_ += full.evaluations + polish.evaluations;
    return converged;
  }

  const Settings& s_;
  const EventPlan& plan_;
  Guess& initial_guess_;
  Admissible& admissible_;
  std::mt19937_64& rng_;
  Result& r_;
  const double eps_;  // every stage but the last solves at eps_start
  const int nev_;
  const int N;  // the shooting variables
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::vector<double> x_;          // the point on the path: the last stage's solution
  std::vector<double> reference_;  // each event's held epoch (window fraction) while it is off
  bool has_parameters_ = false;    // the events have Category-C parameters (the parameters stage ran)
  Propagator prop_;                // the stages' own evaluations outside a solve
  std::vector<double> F_;
  Shooter off_;  // the problem with its events off (held_off)
  int evaluations_ = 0;
};

// One attempt of the continuation onto the events (EventContinuation) from `eventless`, a
// solution of the problem with its events off, attempted from `use` times before. True when it
// converged (r then holds the solution); its function evaluations are added to `evaluations`.
template <class Guess, class Admissible>
bool continuation_attempt(const Settings& s, const EventPlan& plan, Guess&& initial_guess, Admissible&& admissible,
                          std::mt19937_64& rng, const std::vector<double>& eventless, int use, Result& r,
                          int& evaluations) {
  EventContinuation<std::remove_reference_t<Guess>, std::remove_reference_t<Admissible>> attempt(s, plan, initial_guess,
                                                                                                 admissible, rng, r);
  const bool converged = attempt.run(eventless, use);
  evaluations += attempt.evaluations();
  return converged;
}

// The problem with its events off solved from one scale-free random guess (draw `draw`): true with
// its solution in `eventless`. Its solve is recorded in r.continuation.
template <class Guess, class Admissible>
bool eventless_draw(const Settings& s, const EventPlan& plan, Guess&& initial_guess, Admissible&& admissible,
                    std::mt19937_64& rng, int draw, std::vector<double>& eventless, Result& r, int& evaluations) {
  EventContinuation<std::remove_reference_t<Guess>, std::remove_reference_t<Admissible>> stage(s, plan, initial_guess,
                                                                                               admissible, rng, r);
  const bool converged = stage.solve_eventless(draw, eventless);
  evaluations += stage.evaluations();
  return converged;
}

}  // namespace

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, global search (templates/runtime/search.hpp): the last search header
// of runtime.hpp (what its searches share about the extremals they reach, which may be returned
// and the choice of the best, is extremals.hpp). A converged shooting solution is an extremal,
// not necessarily the optimum: on multi-revolution transfers the extremal a random start reaches
// is a matter of chance. So the solve is a search (problems without interior events, MultiStart):
//   1. starts: seeded guesses, each solved at eps_start (eps = 1: the smooth, energy-like
//      problem), drawn until saturated (draws.hpp: the Good-Turing chance that another start
//      finds a new extremal at most search_saturation) within half of the search's time budget;
//      a minimum-time problem with a throttle is first solved from its minimum-fuel companion
//      (minimum_time.hpp), its random starts one more source of extremals;
//   2. the converged ones are told apart by what makes them different (revolutions about the
//      central body, throttle mode changes, the shooting variables) and ranked by their own cost
//      at eps_start, a lower bound of the objective their branch reaches at eps = 0;
//   3. every one whose cost could still beat the best objective found is continued in eps to 0,
//      cheapest first;
//   4. the family of the best extremal is walked by the transfer angle (families.hpp): its
//      neighbours with one revolution fewer and more, then theirs, while the objective improves;
//   5. the distinct extremals at eps = 0 are compared: the lowest objective is returned, and the
//      record says whether the starts saturated (stderr too, where they did not).
// A minimum-fuel problem at a fixed final time that the search leaves unsettled is also solved
// from its minimum-time extremals (fuel_from_time.hpp), and a minimum-time one by continuation on
// the thrust (thrust_continuation.hpp).
// Problems with interior events search over search_attempts complete attempts (each a
// continuation onto the events from a solution of the problem without them, searched first, or a
// solve by legs: events_homotopy_solve). The search integrates at search_tol and polishes every
// extremal at eps = 0 at the integrator's own tolerance before comparing.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// Problems without interior events: the multi-start search at eps_start, the distinct extremals
// that can still beat the best continued to eps = 0, their families explored, the best kept (see
// the top of this file).
template <class Guess, class Admissible>
class MultiStart {
 public:
  // The search runs at `coarse` (search_settings(fine)); its extremals are polished at `fine`.
  MultiStart(const Settings& fine, const Settings& coarse, Guess& guess, Admissible& admissible)
      : fine_(fine),
        s_(coarse),
        guess_(guess),
        admissible_(admissible),
        rec_(r_.search),
        started_(wall_seconds()),
        deadline_(s_.search_time_s > 0 ? std::min(s_.time_limit_s, started_ + s_.search_time_s) : s_.time_limit_s),
        draw_deadline_(started_ + 0.5 * (deadline_ - started_)) {
    rec_.threads = search_threads(coarse);
    rec_.method = "multi-start at eps = " + eps_text() +
                  " until saturated, the distinct extremals that could beat the best continued to eps = 0, " +
                  "their families explored by the transfer angle";
  }

  Result solve() {
    if (s_.search_fuel_companion && has_fuel_companion()) {
      rec_.method = "minimum time from the minimum-fuel companion (tf held, then released); " + rec_.method;
      minimum_time_from_fuel();
    }
    explore(s_.search_starts > 0 ? std::min(s_.search_starts, s_.max_attempts) : s_.max_attempts, draw_deadline_);
    continue_promising();
    if (s_.search_families) walk_families();
    // While nothing has arrived, more starts up to max_attempts, past search_starts and past
    // saturation (the estimate counts what was reached at eps_start, and none of it reached eps = 0).
    while (rec_.extremals.empty() && time_left() && rec_.starts < s_.max_attempts) {
      explore(std::min(s_.max_attempts, rec_.starts + std::max(kMinDraws, rec_.starts)), deadline_);
      continue_promising();
    }
    if (s_.search_thrust_continuation && many_revolutions()) thrust_continuation();
    if (has_time_route() &&
        (s_.search_fuel_from_time == "always" || (s_.search_fuel_from_time == "auto" && unsettled())))
      fuel_from_minimum_time();
    r_.attempts = rec_.starts;
    r_.evaluations = evaluations_;
    r_.iterations = rec_.starts + rec_.continued;
    say_if_not_saturated(rec_, s_, progress_);
    finish_search(fine_, s_, r_, started_,
                  "from " + std::to_string(rec_.continued) + " of " + std::to_string(rec_.start_extremals.size()) +
                      " distinct extremals at eps_start, found by " + std::to_string(rec_.starts) + " starts" +
                      (rec_.family.empty() ? "" : " and the transfer angle"),
                  "no start reached eps = 0 (" + std::to_string(rec_.starts) + " starts, " +
                      std::to_string(rec_.converged_start) + " converged at eps_start)",
                  progress_);
    return r_;
  }

 private:
  std::string eps_text() const { return std::to_string(s_.eps_start).substr(0, 4); }
  bool time_left() const { return wall_seconds() < deadline_; }
  void count(int evaluations) {
    const std::lock_guard<std::mutex> lock(mutex_);
    evaluations_ += evaluations;
  }

  // Draws starts until they are saturated, `cap` starts were drawn or `deadline` passes (the
  // first time half of the search's budget); records why they stopped.
  void explore(int cap, double deadline) {
    draw(cap, deadline);
    rec_.saturated = saturated(s_, rec_.start_extremals, rec_.starts, rec_.converged_start, min_converged());
    char why[160];
    if (rec_.saturated)
      std::snprintf(why, sizeof why, "saturated: the chance that another start finds a new extremal is %.3g <= %.3g",
                    rec_.unseen, s_.search_saturation);
    else if (rec_.starts >= cap)
      std::snprintf(why, sizeof why, "the cap of %d starts (search_starts, max_attempts)", cap);
    else
      std::snprintf(why, sizeof why, "the time budget (search_time_s %.0f s, time_limit_s %.0f s)",
                    s_.search_time_s, s_.time_limit_s);
    rec_.stopped = why;
    progress_.stage(std::to_string(rec_.starts) + " starts at eps = " + eps_text() + ": " +
                    std::to_string(rec_.converged_start) + " converged, " +
                    std::to_string(rec_.start_extremals.size()) + " distinct extremals; " + rec_.stopped);
  }

  // The converged starts saturation asks for: none where the minimum-fuel companion supplied
  // extremals already (the starts are one more source), else kMinConverged.
  int min_converged() const { return rec_.companion_converged > 0 && !rec_.extremals.empty() ? 0 : kMinConverged; }

  // Draws starts (from the next one) until saturated, `cap` starts or `deadline`.
  void draw(int cap, double deadline) {
    rec_.unseen = draw_until_saturated(
        s_, rec_.threads, kStartStream, rec_.start_extremals, rec_.starts, rec_.converged_start, rec_.cut_by_time, cap,
        deadline, min_converged(), [&](int k, std::mt19937_64& rng) { return start(k, rng); },
        [&](int k) { progress_.tick(std::to_string(k) + " starts at eps = " + eps_text()); });
  }

  // Start k at eps_start from the guess its generator draws.
  StartRun start(int, std::mt19937_64& rng) {
    StartRun run;
    run.x.assign(kProblem.num_vars, 0.0);
    guess_(rng, run.x.data());
    Shooter shooter(s_);
    int info = 0;
    run.ok = shooter.solve(run.x, s_.eps_start, s_.accept_residual, info, run.res) && admissible_(run.x.data());
    if (run.ok) run.shape = shape_of(s_, run.x, s_.eps_start);
    count(shooter.evaluations);
    return run;
  }

  // Continues the eps_start extremals not continued yet, lowest cost first, search_continued of
  // them in the first batch and a thread's worth after. The cost of an extremal at eps_start is a
  // lower bound of the objective its branch reaches at eps = 0 (along a smooth branch
  // dJ/deps = -integral u (1 - u) dt <= 0, the envelope theorem), so one whose cost is not below
  // the best objective found cannot beat it: it is marked pruned instead (all are continued with
  // search_continue_all). While none has arrived, the next ones go regardless.
  void continue_promising() {
    bool first = rec_.continued == 0;
    for (;;) {
      std::vector<int> order = untried();
      if (order.empty() || !time_left()) return;
      const double best = best_objective(rec_);
      std::vector<int> batch;
      const std::size_t size = first ? std::max(1, s_.search_continued) : rec_.threads;
      for (const int i : order) {
        if (batch.size() >= size) break;
        if (!s_.search_continue_all && std::isfinite(best) && rec_.start_extremals[i].shape.cost >= best) {
          rec_.start_extremals[i].pruned = true;
          continue;
        }
        batch.push_back(i);
      }
      if (batch.empty()) return;
      continue_extremals(batch);
      first = false;
    }
  }

  // The eps_start extremal `which` continued to eps = 0: true with `e` filled when it arrived.
  // Each eps step starts hybrd's trust region next to the last solution and must keep the
  // branch's revolutions: hybrd can land on another extremal's branch (seen on S13: from the
  // 3-revolution branch to the 4-revolution one), and the path would then report that extremal as
  // this one's continuation.
  bool continue_one(int which, Extremal& e) {
    const StartExtremal& from = rec_.start_extremals[which];
    Shooter shooter(s_, kContinuationStart);
    Result path;
    std::vector<double> x = from.x;
    double res = 0, revolutions = from.shape.revolutions;
    const auto on_branch = [&](const std::vector<double>& to, double eps) {
      const double now = shape_of(s_, to, eps).revolutions;
      if (std::fabs(now - revolutions) > 0.25) return false;
      revolutions = now;
      char line[96];
      std::snprintf(line, sizeof line, "continuing the extremal at eps_start %d: eps = %.3g", which, eps);
      progress_.tick(line);
      return true;
    };
    const bool ok = homotopy_to_zero(s_, shooter, x, path, admissible_, res, on_branch);
    count(shooter.evaluations);
    if (!ok) return false;
    e.x = x;
    e.x_start = path.x_start;
    e.F = shooter.last_F;
    e.max_residual = res;
    e.info = path.info;
    e.homotopy = path.homotopy;
    e.shape = shape_of(s_, x, 0.0);  // its cost is the objective
    e.method = "single shooting, eps continuation from the extremal at eps_start " + std::to_string(which) +
               (from.origin.empty() ? " (start " + std::to_string(from.first_start) + ")" : " (" + from.origin + ")");
    return true;
  }

  // Continues the given eps_start extremals to eps = 0 in parallel, merged in the order given.
  void continue_extremals(const std::vector<int>& which) {
    std::vector<Extremal> arrived(which.size());
    std::vector<char> ok(which.size(), 0);
    parallel_for(static_cast<int>(which.size()), rec_.threads, [&](int i) {
      if (time_left()) ok[i] = continue_one(which[i], arrived[i]);
    });
    for (std::size_t i = 0; i < which.size(); ++i) {
      StartExtremal& from = rec_.start_extremals[which[i]];
      from.continued = true;
      ++rec_.continued;
      if (!ok[i]) continue;
      ++rec_.converged_final;
      const int k =
          merge_extremal(rec_.extremals, arrived[i].x, arrived[i].shape, from.first_start, std::move(arrived[i]));
      Extremal& e = rec_.extremals[k];
      e.reached += from.reached - 1;  // every start that reached `from` led here
      e.from.push_back(which[i]);
      from.arrived = k;
    }
    const double best = best_objective(rec_);
    progress_.stage(std::to_string(rec_.continued) + " continued to eps = 0: " + std::to_string(rec_.extremals.size()) +
                    " distinct extremals" + (std::isfinite(best) ? ", best " + objective_text(best) : ""));
  }

  // The eps_start extremals not continued yet, lowest cost first.
  std::vector<int> untried() const {
    std::vector<int> order;
    for (std::size_t i = 0; i < rec_.start_extremals.size(); ++i)
      if (!rec_.start_extremals[i].continued) order.push_back(static_cast<int>(i));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return rec_.start_extremals[a].shape.cost < rec_.start_extremals[b].shape.cost;
    });
    return order;
  }

  // The family walk (families.hpp): from the best extremal, its neighbours with one revolution
  // fewer and one more, each taken from the search where it has one of that count (reached, or at
  // eps_start and not continued: continued now), else turned from the best by the transfer angle;
  // then again from the new best, until a round finds no better one. Every neighbour looked for
  // is recorded (rec.family).
  void walk_families() {
    std::vector<std::pair<int, int>> tried;  // (extremal, direction)
    for (;;) {
      const int best = best_index(rec_);
      if (best < 0 || !time_left()) return;
      const double before = best_objective(rec_);
      for (const int direction : {-1, 1}) {
        if (std::find(tried.begin(), tried.end(), std::make_pair(best, direction)) != tried.end()) continue;
        tried.emplace_back(best, direction);
        if (time_left()) look_for_neighbour(best, direction);
      }
      if (!(best_objective(rec_) < before)) return;
    }
  }

  // One neighbour of extremal `of` (see walk_families).
  void look_for_neighbour(int of, int direction) {
    FamilyProbe probe;
    probe.from = of;
    probe.direction = direction;
    probe.revolutions = rec_.extremals[of].shape.revolutions + direction;
    const auto near = [&](const Shape& shape) { return std::fabs(shape.revolutions - probe.revolutions) < 0.5; };
    for (std::size_t i = 0; i < rec_.extremals.size() && probe.found < 0; ++i)
      if (near(rec_.extremals[i].shape)) {
        probe.how = "reached by the search";
        probe.found = static_cast<int>(i);
      }
    for (std::size_t i = 0; i < rec_.start_extremals.size() && probe.found < 0 && probe.how.empty(); ++i)
      if (near(rec_.start_extremals[i].shape) && !rec_.start_extremals[i].continued) {
        probe.how = "an extremal at eps_start of that count";
        probe.found = continue_if_promising(static_cast<int>(i), probe.how);
      }
    if (probe.how.empty()) probe.found = turn(of, direction, probe.how);
    char line[160];
    std::snprintf(line, sizeof line, "family of extremal %d: %s %.2f revolutions (%s): %s", of,
                  direction < 0 ? "one fewer," : "one more,", probe.revolutions, probe.how.c_str(),
                  probe.found < 0 ? "none" : ("extremal " + std::to_string(probe.found)).c_str());
    progress_.stage(line);
    rec_.family.push_back(probe);
  }

  // The eps_start extremal k continued to eps = 0 where its cost, a lower bound of its objective
  // (continue_promising), is below the best objective; else marked pruned and `how` says so.
  // Returns the extremal at eps = 0 reached (-1: none).
  int continue_if_promising(int k, std::string& how) {
    StartExtremal& e = rec_.start_extremals[k];
    if (!s_.search_continue_all && e.shape.cost >= best_objective(rec_)) {
      e.pruned = true;
      how += ", not continued: its cost at eps_start, a lower bound of its objective, is not below the best";
      return -1;
    }
    continue_extremals({k});
    how += ", continued";
    return rec_.start_extremals[k].arrived;
  }

  // The transfer angle from extremal `of`: from its eps_start extremal where it has one (the turned
  // solution joins them and is continued to eps = 0), else from itself at eps = 0. Returns the
  // extremal at eps = 0 reached (-1: none).
  int turn(int of, int direction, std::string& how) {
    const Extremal& e = rec_.extremals[of];
    std::vector<ContinuationStep> steps;
    int evaluations = 0;
    if (!e.from.empty()) {
      const int parent = e.from.front();
      std::vector<double> x = rec_.start_extremals[parent].x;
      how = "transfer angle from the extremal at eps_start " + std::to_string(parent);
      const bool ok =
          turn_one_revolution(s_, x, s_.eps_start, direction, s_.accept_residual, admissible_, steps, evaluations);
      count(evaluations);
      if (!ok) return -1;
      StartExtremal entry;
      entry.origin = how;
      const int k = merge_extremal(rec_.start_extremals, x, shape_of(s_, x, s_.eps_start), -1, std::move(entry));
      if (rec_.start_extremals[k].continued) return rec_.start_extremals[k].arrived;
      return continue_if_promising(k, how);
    }
    std::vector<double> x = e.x;
    how = "transfer angle from it at eps = 0";
    const bool ok = turn_one_revolution(s_, x, 0.0, direction, s_.final_residual, admissible_, steps, evaluations);
    count(evaluations);
    if (!ok) return -1;
    Extremal entry;
    entry.F = shooting_residuals(x);
    entry.max_residual = max_abs(entry.F);
    entry.method = "single shooting, transfer angle from extremal " + std::to_string(of);
    entry.continuation = std::move(steps);
    return merge_extremal(rec_.extremals, x, shape_of(s_, x, 0.0), -1, std::move(entry));
  }

  // The minimum-fuel companion (minimum_time.hpp): its starts at eps = 1 with tf held (companion_hold),
  // drawn until saturated within a quarter of the budget; each distinct solution, cheapest first,
  // continued down in tf and released into the problem itself.
  void minimum_time_from_fuel() {
    const FreeFinalTime f = free_final_time();
    const double hold = companion_hold(), eps = 1;
    const double quarter = started_ + 0.25 * (deadline_ - started_);
    std::vector<StartExtremal>& list = rec_.companion_solutions;
    bool cut = false;
    draw_until_saturated(
        s_, rec_.threads, kCompanionStream, list, rec_.companion_draws, rec_.companion_converged, cut,
        s_.max_attempts, quarter, kMinConverged,
        [&](int, std::mt19937_64& rng) {
          StartRun run;
          run.x.assign(kProblem.num_vars, 0.0);
          guess_(rng, run.x.data());
          std::vector<double> z = without_held(run.x, f.variable);
          Shooter shooter(s_, companion_function(f, hold));
          int info = 0;
          run.ok = shooter.solve(z, eps, s_.accept_residual, info, run.res);
          run.x = with_held(z, f.variable, hold);
          run.ok = run.ok && admissible_(run.x.data());
          if (run.ok) run.shape = shape_of(s_, run.x, eps, 1.0);
          count(shooter.evaluations);
          return run;
        },
        [&](int k) { progress_.tick(std::to_string(k) + " starts of the minimum-fuel companion"); });
    if (!list.empty()) rec_.companion_tf_days = flight_days(list.front().x, eps);
    progress_.stage(std::to_string(rec_.companion_draws) + " starts of the minimum-fuel companion (tf held at " +
                    std::to_string(rec_.companion_tf_days).substr(0, 6) + " days): " +
                    std::to_string(rec_.companion_converged) + " converged, " + std::to_string(list.size()) +
                    " distinct");
    std::vector<int> order(list.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return list[a].shape.cost < list[b].shape.cost; });
    std::vector<CompanionArrival> arrivals(order.size());
    parallel_for(static_cast<int>(order.size()), rec_.threads, [&](int i) {
      if (!time_left()) return;
      int evaluations = 0;
      arrivals[i] = companion_to_minimum_time(s_, list[order[i]].x, hold, eps, admissible_, evaluations);
      count(evaluations);
    });
    for (std::size_t i = 0; i < order.size(); ++i) {
      StartExtremal& from = list[order[i]];
      from.continued = true;
      CompanionArrival& a = arrivals[i];
      if (!a.arrived) continue;
      ++rec_.converged_final;
      Extremal entry;
      entry.F = a.F;
      entry.max_residual = a.max_residual;
      entry.info = a.info;
      entry.method = "minimum time released from the minimum-fuel companion's solution " +
                     std::to_string(order[i]) + ", continued down to tf held at window fraction " +
                     std::to_string(a.held).substr(0, 6);
      entry.continuation = std::move(a.steps);
      from.arrived = merge_extremal(rec_.extremals, a.x, shape_of(s_, a.x, 0.0), -1, std::move(entry));
    }
    const double best = best_objective(rec_);
    progress_.stage("minimum time from the companion: " + std::to_string(rec_.extremals.size()) +
                    " distinct extremals" + (std::isfinite(best) ? ", best " + objective_text(best) : ""));
  }

  // Whether the search leaves a many-revolution transfer unsettled (unsettled()), for the thrust
  // continuation: only for minimum time (a flight at full thrust, whose time the scaled window
  // follows) where no target moves on the calendar (no epoch, no body on an orbit): a raised thrust
  // shortens the flight, and a moving target would be met elsewhere, another transfer than the
  // problem's.
  bool many_revolutions() const {
    return kProblem.objective == Objective::time && kProblem.epoch_mjd2000 == 0 && kProblem.num_orbit_bodies == 0 &&
           unsettled();
  }

  // Whether the search leaves the problem unsettled: its best extremal winds more than
  // kFewRevolutions times, or it found none, and the starts did not saturate on kMinConverged
  // converged ones at least. Starts that saturate with fewer (the companion's extremals stop the
  // draws: draws.hpp) say only that starts find nothing, not that the extremals found are the best.
  bool unsettled() const {
    if (rec_.saturated && rec_.converged_start >= kMinConverged && !rec_.extremals.empty()) return false;
    const int best = best_index(rec_);
    return best < 0 || rec_.extremals[best].shape.revolutions > kFewRevolutions;
  }

  // The thrust continuation (thrust_continuation.hpp), with a budget of its own (search_time_s
  // again, within time_limit_s): the thrust raised until a search there returns an extremal of few
  // revolutions (search_at_raised_thrust), then its best extremals continued down to the problem's
  // thrust, one after the other (they share the program's thrust), and merged with the search's.
  void thrust_continuation() {
    const ThrustScaling scaling;
    if (!scaling) return;
    const double stage_end = std::min(s_.time_limit_s, wall_seconds() + std::max(s_.search_time_s, 0.0));
    double factor = 1;
    const Result raised = search_at_raised_thrust(scaling, stage_end, factor);
    scaling.set(0);
    if (raised.status != Status::kConverged) {
      progress_.stage("thrust continuation: no search at a raised thrust returned a transfer of few revolutions");
      return;
    }
    const double sigma = std::log(factor);
    // The distinct extremals the search there reached, lowest objective first (the best path down
    // need not start from the best extremal up there), kThrustBranches of them.
    std::vector<const Extremal*> branches;
    for (const Extremal& e : raised.search.extremals)
      if (returnable(e)) branches.push_back(&e);
    std::stable_sort(branches.begin(), branches.end(),
                     [](const Extremal* a, const Extremal* b) { return a->shape.cost < b->shape.cost; });
    if (branches.size() > static_cast<std::size_t>(kThrustBranches)) branches.resize(kThrustBranches);
    const std::vector<ContinuationStep> raising = rec_.thrust_continuation;
    for (std::size_t k = 0; k < branches.size() && wall_seconds() < stage_end; ++k) {
      int evaluations = 0;
      const double end = wall_seconds() + (stage_end - wall_seconds()) / static_cast<double>(branches.size() - k);
      // At the integrator's own tolerance: over tens of revolutions the search's leaves F a floor
      // near 1e-6 (measured at 0.5 N), above the acceptance.
      PathArrival a = continue_thrust_down(fine_, scaling, branches[k]->x, sigma, admissible_, evaluations, end);
      scaling.set(0);
      count(evaluations);
      rec_.thrust_continuation.insert(rec_.thrust_continuation.end(), a.steps.begin(), a.steps.end());
      const std::string which = "the extremal " + std::to_string(k + 1) + " of " + std::to_string(branches.size()) +
                                " of the search at " + std::to_string(scaling.thrust_N(sigma)).substr(0, 7) +
                                " N (x" + std::to_string(static_cast<int>(factor)) + ")";
      if (!a.arrived) {
        progress_.stage("thrust continuation from " + which + ": stopped at " +
                        std::to_string(a.steps.back().value).substr(0, 7) + " N");
        continue;
      }
      rec_.thrust_continuation_arrived = true;
      ++rec_.converged_final;
      Extremal entry;
      entry.F = a.F;
      entry.max_residual = a.max_residual;
      entry.info = a.info;
      entry.method = "single shooting, continued down the maximum thrust from " + which;
      entry.continuation = raising;
      entry.continuation.insert(entry.continuation.end(), a.steps.begin(), a.steps.end());
      const Shape shape = shape_of(s_, a.x, 0.0);
      merge_extremal(rec_.extremals, a.x, shape, -1, std::move(entry));
      progress_.stage("thrust continuation from " + which + ": arrived with " + objective_text(shape.cost) + ", " +
                      std::to_string(shape.revolutions).substr(0, 6) + " revolutions");
    }
  }

  // The thrust raised by `factor` until a search there (itself without the thrust continuation,
  // half of what is left of the stage) returns an extremal of at most kFewRevolutions: the factor
  // guessed from the revolutions seen (they fall about as the thrust rises), quadrupled where the
  // search there finds none, at most 2^kMaxThrustDoublings. Each search is recorded in
  // rec_.thrust_continuation; the scaling is left at the last factor.
  Result search_at_raised_thrust(const ThrustScaling& scaling, double stage_end, double& factor) {
    const auto factor_for = [](double revolutions) {
      return std::exp2(std::ceil(std::log2(std::max(2.0, revolutions / kFewRevolutions))));
    };
    const int best = best_index(rec_);
    factor = best < 0 ? 4.0 : factor_for(rec_.extremals[best].shape.revolutions);
    while (factor <= std::exp2(kMaxThrustDoublings) && wall_seconds() < stage_end) {
      const double sigma = std::log(factor);
      scaling.set(sigma);
      progress_.stage("thrust raised to " + std::to_string(scaling.thrust_N(sigma)).substr(0, 7) + " N (x" +
                      std::to_string(static_cast<int>(factor)) + "), the final time's window scaled by 1/" +
                      std::to_string(static_cast<int>(factor)) + ": the search there");
      Settings fine = fine_, coarse = s_;
      for (Settings* level : {&fine, &coarse}) {
        level->search_thrust_continuation = false;
        level->search_fuel_from_time = "never";
        level->search_time_s = std::max(1.0, 0.5 * (stage_end - wall_seconds()));
      }
      Result raised = MultiStart(fine, coarse, guess_, admissible_).solve();
      count(raised.evaluations);
      const bool found = raised.status == Status::kConverged;
      ContinuationStep step{"raised thrust: the search there [N]", scaling.thrust_N(sigma), found,
                            found ? raised.max_residual : INFINITY, raised.evaluations};
      step.revolutions = found ? shape_of(s_, raised.x, 0.0).revolutions : NAN;
      rec_.thrust_continuation.push_back(step);
      if (found && step.revolutions <= kFewRevolutions) return raised;
      factor *= found ? factor_for(step.revolutions) : 4.0;
    }
    return {};
  }

  // The route from the minimum-time extremals (fuel_from_time.hpp), at the integrator's own
  // tolerance, one path at a time: from each of the kTimeRouteSources lowest-cost extremals at
  // eps_start down to a minimum-time extremal, and from each distinct one up to the problem's final
  // time and on to eps = 0, the arrivals merged with the search's extremals. Where every minimum-time
  // extremal so reached winds more than kFewRevolutions times (or none was reached), the minimum
  // time is also sought at a raised thrust and continued down to the problem's
  // (time_route_by_raised_thrust).
  void fuel_from_minimum_time() {
    rec_.method += "; minimum fuel also continued from the minimum-time extremals";
    FinalTime tf;
    const double stage_end = std::min(s_.time_limit_s, wall_seconds() + std::max(s_.search_time_s, 0.0));
    double fewest = INFINITY;
    for (const int k : lowest_cost(rec_.start_extremals)) {
      if (wall_seconds() >= stage_end) break;
      TimeRouteArrival a;
      std::vector<double> z;
      int evaluations = 0;
      const bool reached = minimum_time_from_fuel_solution(fine_, tf, rec_.start_extremals[k].x, s_.eps_start, z, a,
                                                           evaluations);
      count(evaluations);
      if (reached) fewest = std::min(fewest, minimum_time_revolutions(s_, tf, z));
      fuel_from_time_path("the extremal at eps_start " + std::to_string(k), tf, reached ? &z : nullptr, a);
    }
    if (s_.search_thrust_continuation && !(fewest <= kFewRevolutions)) time_route_by_raised_thrust(tf, stage_end);
  }

  // The indices of the kTimeRouteSources lowest-cost extremals of `list`.
  static std::vector<int> lowest_cost(const std::vector<StartExtremal>& list) {
    constexpr std::size_t kTimeRouteSources = 3;
    std::vector<int> order(list.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return list[a].shape.cost < list[b].shape.cost; });
    if (order.size() > kTimeRouteSources) order.resize(kTimeRouteSources);
    return order;
  }

  // The minimum time at a raised thrust: the fuel problem searched there (search_at_raised_thrust:
  // its final time scaled inversely, so it winds fewer times), its lowest-cost extremals at eps_start
  // taken down to minimum-time extremals there, and those continued down the thrust to the
  // problem's (continue_thrust_down along the minimum-time system), then up to its final time.
  void time_route_by_raised_thrust(FinalTime& tf, double stage_end) {
    const ThrustScaling scaling;
    if (!scaling) return;
    double factor = 1;
    const Result raised = search_at_raised_thrust(scaling, stage_end, factor);
    const double sigma = std::log(factor);
    const std::string where = " of the search at " + std::to_string(scaling.thrust_N(sigma)).substr(0, 7) + " N";
    const int l0 = lambda0_variable();
    const double held = 0;
    ThrustPath along{held_multiplier_function(tf, l0, held), [&](double v) { tf.rescale(v); },
                     [&](const std::vector<double>& z) { return minimum_time_revolutions(s_, tf, z); }};
    auto positive_time = [&](const double* z) { return z[l0] > 0; };
    std::vector<double> seen;  // the minimum times reached at the raised thrust (fractions)
    for (const int k : lowest_cost(raised.search.start_extremals)) {
      if (wall_seconds() >= stage_end || raised.status != Status::kConverged) break;
      scaling.set(sigma);
      tf.rescale(sigma);
      TimeRouteArrival a;
      std::vector<double> z;
      int evaluations = 0;
      bool reached = minimum_time_from_fuel_solution(fine_, tf, raised.search.start_extremals[k].x, s_.eps_start, z, a,
                                                     evaluations);
      const bool repeated = reached && std::any_of(seen.begin(), seen.end(), [&](double f) {
                              return std::fabs(f - z[l0]) <= 1e-7 * f;
                            });
      if (reached && !repeated) {
        seen.push_back(z[l0]);
        PathArrival down = continue_thrust_down(fine_, scaling, z, sigma, positive_time, evaluations, stage_end, along);
        a.steps.insert(a.steps.end(), down.steps.begin(), down.steps.end());
        reached = down.arrived;
        if (reached) z = down.x;
      }
      scaling.set(0);
      tf.rescale(0);
      count(evaluations);
      if (!repeated) fuel_from_time_path("the extremal at eps_start " + std::to_string(k) + where, tf, reached ? &z : nullptr, a);
    }
    scaling.set(0);
    tf.rescale(0);
  }

  // One path of the route from its minimum-time extremal z at the problem's thrust (null: none was
  // reached; its steps in `a`): up to the problem's final time unless that minimum time was reached
  // before, recorded, and its arrival merged with the search's extremals.
  void fuel_from_time_path(const std::string& from, const FinalTime& tf, const std::vector<double>* z,
                           TimeRouteArrival& a) {
    SearchRecord::TimeRoutePath path;
    path.from = from;
    if (z) {
      const int l0 = lambda0_variable();
      path.tf_min_days = (*z)[l0] * tf.unit() * kProblem.time_unit_days;
      path.revolutions = minimum_time_revolutions(s_, tf, *z);
      for (const auto& p : rec_.time_route_paths)
        if (std::fabs(p.tf_min_days - path.tf_min_days) <= 1e-7 * path.tf_min_days) path.reached_before = true;
      if (!path.reached_before) {
        int evaluations = 0;
        fuel_path_from_minimum_time(fine_, tf, *z, admissible_, a, evaluations);
        count(evaluations);
      }
    }
    rec_.time_route.insert(rec_.time_route.end(), a.steps.begin(), a.steps.end());
    const std::string t_min = std::isfinite(path.tf_min_days)
                                  ? "t_min " + std::to_string(path.tf_min_days * 24).substr(0, 9) + " h"
                                  : std::string("no minimum time reached");
    if (a.arrived) {
      ++rec_.converged_final;
      Extremal entry;
      entry.F = a.F;
      entry.max_residual = a.max_residual;
      entry.info = a.info;
      entry.method = "single shooting, minimum fuel continued from the minimum-time extremal (" + t_min +
                     ") reached from " + from;
      entry.continuation = a.steps;
      entry.homotopy = a.homotopy;
      const Shape shape = shape_of(s_, a.x, 0.0);
      path.extremal = merge_extremal(rec_.extremals, a.x, shape, -1, std::move(entry));
      progress_.stage("minimum fuel from the minimum-time extremal (" + t_min + ", from " + from + "): " +
                      objective_text(shape.cost) + ", " + std::to_string(shape.revolutions).substr(0, 6) +
                      " revolutions");
    } else {
      progress_.stage("minimum time from " + from + ": " + t_min +
                      (path.reached_before ? ", reached before"
                       : z                 ? "; minimum fuel from it did not reach the problem's final time"
                                           : ""));
    }
    rec_.time_route_paths.push_back(path);
  }

  // The flight time of x in days (its trajectory's span).
  double flight_days(const std::vector<double>& x, double eps) const {
    try {
      const RecordedPath path = recorded_path(s_, x, eps, INFINITY, {}, 1, 1.0);
      return (path.samples.back().t - path.samples.front().t) * kProblem.time_unit_days;
    } catch (const numerical_error&) {
      return NAN;
    }
  }

  // The shooting function's rows at x (eps = 0).
  std::vector<double> shooting_residuals(const std::vector<double>& x) const {
    std::vector<double> F(x.size());
    Propagator prop(s_);
    shooting_function(x.data(), 0.0, prop, F.data());
    return F;
  }
  static double max_abs(const std::vector<double>& v) {
    double m = 0;
    for (const double a : v) m = std::max(m, std::fabs(a));
    return m;
  }

  const Settings& fine_;
  const Settings& s_;
  Guess& guess_;
  Admissible& admissible_;
  Result r_;
  SearchRecord& rec_;
  const double started_, deadline_, draw_deadline_;
  Progress progress_;
  std::mutex mutex_;
  int evaluations_ = 0;
};

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
    if (wall_seconds() > s.time_limit_s) break;
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

// Problems without interior events: the global search (MultiStart). `initial_guess(rng, x)` draws
// a start.
// With a warm start (a sweep's converged neighbour) the search runs only when the warm solve fails
// and the settings allow it (not warm_only).
Result homotopy_solve(const Settings& s, const Guess& initial_guess, const Admissible& admissible) {
  const Settings coarse = search_settings(s);
  if (s.warm_start.empty())
    return MultiStart<const Guess, const Admissible>(s, coarse, initial_guess, admissible).solve();
  Result warm = warm_solve(s, admissible);
  if (warm.status == Status::kConverged || s.warm_only) return warm;
  Result r = MultiStart<const Guess, const Admissible>(s, coarse, initial_guess, admissible).solve();
  r.start = "cold-after-warm-failed";
  r.start_detail = warm.detail;
  r.evaluations += warm.evaluations;
  return r;
}

// Problems whose events can all be switched off: the problem without them, solved from draws
// j = 0, 1, ... (one scale-free random guess each, from the generator of (seed, j) on a stream of
// its own) in batches of kSearchBatch on the search's threads, until a batch has converged draws
// or search_attempts x leg_attempts draws were made. Its distinct solutions go into
// rec.start_extremals (converged_start, eventless_draws), lowest cost at eps_start first; returns
// the solve that found each.
template <class Guess, class Admissible>
std::vector<ContinuationStep> eventless_search(const Settings& s, const EventPlan& events, Guess& initial_guess,
                                               Admissible& admissible, double started, SearchRecord& rec,
                                               int& evaluations, Progress& progress) {
  std::vector<ContinuationStep> found_by;
  const int most = std::max(1, s.search_attempts) * std::max(1, s.leg_attempts);
  std::mutex count;
  while (rec.eventless_draws < most && rec.converged_start == 0 && search_time_left(s, started)) {
    const int from = rec.eventless_draws, to = std::min(most, from + kSearchBatch);
    std::vector<Result> solves(static_cast<std::size_t>(to - from));
    std::vector<std::vector<double>> x(solves.size());
    std::vector<char> ran(solves.size(), 0), ok(solves.size(), 0);
    parallel_for(to - from, rec.threads, [&](int i) {
      if (!search_time_left(s, started)) return;
      std::mt19937_64 rng = start_generator(s.seed, from + i, kEventlessStream);
      int e = 0;
      ok[i] = eventless_draw(s, events, initial_guess, admissible, rng, from + i, x[i], solves[i], e);
      ran[i] = 1;
      const std::lock_guard<std::mutex> lock(count);
      evaluations += e;
    });
    for (int i = 0; i < to - from; ++i) {
      if (!ran[i]) {
        rec.cut_by_time = true;
        continue;
      }
      ++rec.eventless_draws;
      if (!ok[i]) continue;
      ++rec.converged_start;
      StartExtremal entry;
      entry.max_residual = solves[i].continuation.back().max_residual;
      const std::size_t before = rec.start_extremals.size();
      merge_extremal(rec.start_extremals, x[i], shape_of(s, x[i], s.eps_start), from + i, std::move(entry));
      if (rec.start_extremals.size() > before) found_by.push_back(solves[i].continuation.back());
    }
  }
  std::vector<std::size_t> order(found_by.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rec.start_extremals[a].shape.cost < rec.start_extremals[b].shape.cost;
  });
  std::vector<StartExtremal> sorted;
  std::vector<ContinuationStep> sorted_by;
  for (const std::size_t i : order) {
    sorted.push_back(std::move(rec.start_extremals[i]));
    sorted_by.push_back(found_by[i]);
  }
  rec.start_extremals = std::move(sorted);
  progress.stage(std::to_string(rec.eventless_draws) + " draws with the events off: " +
                 std::to_string(rec.converged_start) + " converged, " + std::to_string(rec.start_extremals.size()) +
                 " distinct");
  return sorted_by;
}

// Attempt k's outcome into the record: a converged one's extremal told apart from those already
// reached (or counted with its twin), and the events-off solution it continued marked as arrived.
inline void record_attempt(const Settings& s, int k, int eventless, Result& a, SearchRecord& rec) {
  ++rec.starts;
  if (a.status != Status::kConverged) return;
  ++rec.converged_final;
  Extremal entry;
  entry.F = a.F;
  entry.x_start = a.x_start;
  entry.max_residual = a.max_residual;
  entry.info = a.info;
  entry.method = a.method;
  entry.homotopy = std::move(a.homotopy);
  entry.legs = std::move(a.legs);
  entry.continuation = std::move(a.continuation);
  const int i = merge_extremal(rec.extremals, a.x, shape_of(s, a.x, 0.0), k, std::move(entry));
  rec.extremals[i].from.push_back(k);
  if (eventless > 0 && rec.start_extremals[k % eventless].arrived < 0) rec.start_extremals[k % eventless].arrived = i;
}

// Why the attempts stopped after `attempts_made`, and the chance that an extremal went unseen.
inline void record_stop(const Settings& s, int attempts_made, bool saturated, SearchRecord& rec) {
  rec.saturated = saturated;
  rec.unseen = unseen_chance(rec.extremals, rec.starts);
  rec.stopped = rec.saturated ? "saturated: every extremal reached by more than one attempt"
                : attempts_made >= s.max_attempts
                    ? "the cap of " + std::to_string(s.max_attempts) + " attempts (max_attempts)"
                    : "the time budget (search_time_s, time_limit_s)";
}

// Problems with interior events: search_attempts complete attempts, independent of one another.
// When every event is passable, the problem without them is searched first (eventless_search) and
// attempt k continues onto the events from its distinct solutions in turn (k mod their number;
// the first attempt from each places the epochs where it passes closest to the targets); an
// attempt that does not converge so tries the legs. The converged ones are told apart and the best
// kept; more attempts follow while none has converged. The attempts run at search_settings(fine);
// the extremals are polished at `fine`.
Result events_homotopy_solve(const Settings& fine, const LegPlan& legs, const EventPlan& events,
                             const Guess& initial_guess, const Admissible& admissible) {
  const Settings s = search_settings(fine);
  Result r;
  if (!s.warm_start.empty())
    r.start_detail = "a warm start is not used on problems with interior events: the search starts cold";
  SearchRecord& rec = r.search;
  rec.threads = search_threads(s);
  rec.method = events.passable ? "the problem with its events off searched first; then complete attempts, each a "
                                 "continuation onto the events from its distinct solutions in turn, else legs, then "
                                 "multiple shooting"
                               : "complete attempts: legs, then multiple shooting, then single shooting";
  r.method = rec.method;
  const double started = wall_seconds();
  Progress progress;
  int evaluations = 0;
  std::mutex count;
  std::atomic<int> done{0};
  // The solve that found each distinct events-off solution (rec.start_extremals).
  const std::vector<ContinuationStep> eventless_solves =
      events.passable ? eventless_search(s, events, initial_guess, admissible, started, rec, evaluations, progress)
                      : std::vector<ContinuationStep>{};
  const int eventless = static_cast<int>(rec.start_extremals.size());
  const auto attempt = [&](int k, Result& a) {
    std::mt19937_64 rng = start_generator(s.seed, k);
    Shooter single(s);
    a.attempts = k + 1;  // legs_attempt: attempt 1 starts in the middle of every window
    int attempt_evaluations = 0;
    if (eventless > 0) {  // the events-off solutions in turn, lowest cost first
      a.continuation.push_back(eventless_solves[k % eventless]);
      continuation_attempt(s, events, initial_guess, admissible, rng, rec.start_extremals[k % eventless].x,
                           k / eventless, a, attempt_evaluations);
    }
    if (a.status != Status::kConverged && search_time_left(s, started))
      legs_attempt(s, legs, initial_guess, admissible, rng, single, a, attempt_evaluations);
    const std::lock_guard<std::mutex> lock(count);
    evaluations += attempt_evaluations + single.evaluations;
  };
  int next = 0;
  // Attempts go on past search_attempts while none has converged, or while the extremals reached
  // do not look saturated (draws.hpp's estimate over the attempts: some extremal reached by one
  // attempt only).
  const auto saturated = [&] {
    return s.search_saturation > 0 && rec.starts >= s.search_attempts && !rec.extremals.empty() &&
           unseen_chance(rec.extremals, rec.starts) <= s.search_saturation;
  };
  while (search_time_left(s, started) && next < s.max_attempts && (next < s.search_attempts || !saturated())) {
    const int to = std::min(s.max_attempts, next < s.search_attempts ? s.search_attempts : next + rec.threads);
    std::vector<Result> results(static_cast<std::size_t>(to - next));
    std::vector<char> ran(results.size(), 0);
    parallel_for(to - next, rec.threads, [&](int i) {
      if (!search_time_left(s, started)) return;
      attempt(next + i, results[i]);
      ran[i] = 1;
      progress.tick(std::to_string(next + ++done) + " attempts done");
    });
    for (int i = 0; i < to - next; ++i) {
      if (!ran[i]) {
        rec.cut_by_time = true;
        continue;
      }
      if (eventless > 0) {
        rec.start_extremals[(next + i) % eventless].continued = true;
        ++rec.continued;
      }
      record_attempt(s, next + i, eventless, results[i], rec);
    }
    done = 0;
    next = to;
    const double best = best_objective(rec);
    progress.stage(std::to_string(rec.starts) + " attempts: " + std::to_string(rec.converged_final) + " converged, " +
                   std::to_string(rec.extremals.size()) + " distinct extremals" +
                   (std::isfinite(best) ? ", best " + objective_text(best) : ""));
  }
  record_stop(s, next, saturated(), rec);
  say_if_not_saturated(rec, s, progress);
  r.attempts = rec.starts;
  r.evaluations = evaluations;
  r.iterations = rec.starts;
  finish_search(fine, s, r, started, "from " + std::to_string(rec.starts) + " complete attempts",
                "no attempt reached eps = 0 (" + std::to_string(rec.starts) + " attempts)", progress);
  return r;
}

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the thrust route (templates/runtime/search/thrust.hpp): a
// many-revolution transfer reached from a few-revolution one along the maximum thrust.
// ---------------------------------------------------------------------------------------------
// At low thrust a transfer winds many times about the central body, the shooting function's basin
// shrinks with the revolutions, and random starts find poor extremals or none. At a higher thrust
// the same transfer takes few revolutions, where the search is reliable. The problem family
//   Tmax(sigma) = Tmax e^sigma,   the final time's window [tf_min, tf] e^-sigma,
// (a transfer at full thrust takes a time close to inversely proportional to the thrust, so its
// final time keeps its place in the scaled window) is the problem itself at sigma = 0. The route
// raises the thrust until a search there returns an extremal of few revolutions, then continues
// its best extremals down to sigma = 0 (continue_thrust_down), the revolutions recorded at every
// step. The parameters are the program's, shared by its threads (knobs.hpp): the continuation runs
// alone, one path after the other. Every rule counts: the doublings of the thrust, the branches
// continued, the steps (which halve on failure down to a smallest one); no clock but the run's
// time limit.
#pragma once

namespace helios_rt {

namespace {

// The most doublings of the thrust tried.
constexpr int kMaxThrustDoublings = 10;
// The most extremals of the search at the raised thrust continued down.
constexpr int kThrustBranches = 3;
// The most solves of one continuation down the thrust.
constexpr int kMaxThrustSolves = 4000;
// The most searches where every branch continued down ended at a fold.
constexpr int kMaxThrustRestarts = 4;

// The system a continuation down the thrust follows (continue_thrust_down).
struct ThrustPath {
  Function function = shooting_function_and_jacobian;
  std::function<void(double sigma)> set;
  std::function<double(const std::vector<double>& x)> revolutions;
  // The flight time of x times the thrust's scale e^sigma (nearly constant along a branch; NaN:
  // not checked): by default the free final time's, from its window fraction.
  std::function<double(const std::vector<double>& x, double sigma)> time_thrust = free_time_thrust;

  static double free_time_thrust(const std::vector<double>& x, double sigma) {
    static const int at = free_final_time().variable;
    if (at < 0) return NAN;
    return (kProblem.tf_min + (kProblem.tf - kProblem.tf_min) * x[at] - kProblem.t0) * std::exp(sigma);
  }
};

// Whether a step of the continuation over `dsigma` stays on its branch or moves to a better one:
// the flight time times the thrust's scale it reached (`reached`) against the one the path's
// tangent predicted (`predicted`; NaN: no prediction, no check). Along a branch that product
// changes slowly and smoothly (GTO to GEO: 888 N h at 60 N, 846 N h at 20 N), so the prediction
// misses it by the step's second order only; a step that lands on a worse extremal's branch jumps
// up (seen: 850 to 946 N h between 0.67 N and 0.5 N, the revolutions from 67 to 131) and is
// refused. A step to a better branch (a retry past a fold, where the branch followed ends) is
// taken: for a minimum the better one is what matters.
inline bool stays_on_branch(double predicted, double reached, double dsigma) {
  if (!std::isfinite(predicted) || !std::isfinite(reached) || !(predicted > 0)) return true;
  return std::log(reached / predicted) <= 0.005 + 0.1 * dsigma * dsigma;
}

// A continuation in the thrust's scale sigma (ThrustFollower::follow): at each step a tangent
// predictor (dx/dsigma = -J^-1 dF/dsigma) and hybrd from it; a step that fails is retried from
// predictions perturbed at random (relative scales 1e-3 to 1e-1, kThrustRetries of them) before it
// is halved, so that where the branch being followed turns back (a fold: below some thrust the
// extremal of that shape no longer exists) the continuation goes on on a neighbouring one, never a
// worse one (stays_on_branch); it stops when the step falls below 1e-3 in sigma, or after
// kMaxThrustSolves solves in all. The revolutions of every solution reached are recorded (a jump
// shows a change of branch).
template <class Admissible, class Tick>
class ThrustFollower {
 public:
  ThrustFollower(const Settings& s, ProgramKnobs& knobs, Admissible& admissible, Tick& tick, const ThrustPath& along)
      : s_(s),
        knobs_(knobs),
        admissible_(admissible),
        tick_(tick),
        along_(along),
        shooter_(s, along.function, kContinuationStart),
        rng_(s.seed) {}

  // x at `sigma` followed toward `to` (either way); sigma is left at the last scale reached. With
  // `to_next_branch`, it stops at the first step that lands on a cheaper branch (its flight time
  // times the thrust's scale 0.2 % or more below the tangent's prediction, which a step along a
  // branch meets to second order) and returns true. It gives up where a step's flight time times
  // the thrust's scale exceeds `give_up_above`.
  bool follow(std::vector<double>& x, double& sigma, double to, const char* stage, std::vector<ContinuationStep>& steps,
              bool to_next_branch = false, double give_up_above = INFINITY) {
    const double direction = to >= sigma ? 1.0 : -1.0;
    double step = std::min(0.25, std::fabs(to - sigma));
    set(sigma);
    bool predicted = predict(x, sigma);
    while (direction * (to - sigma) > 0 && solves_ < kMaxThrustSolves && !out_of_time(s_)) {
      const double next = direction > 0 ? std::min(to, sigma + step) : std::max(to, sigma - step);
      set(next);
      std::vector<double> trial;
      bool ok = false;
      double prediction = NAN, reached = NAN;  // the flight time times the thrust's scale predicted, reached
      const int retries = std::fabs(next - sigma) <= perturb_within_ ? kThrustRetries : 0;
      for (int attempt = 0; attempt <= retries && !ok && !out_of_time(s_); ++attempt) {
        trial = x;
        if (predicted) {
          for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent_[i] * (next - sigma);
          prediction = along_.time_thrust(trial, next);
        }
        if (attempt > 0) {
          const double scale = std::pow(10.0, -3.0 + 2.0 * (attempt - 1) / std::max(1, kThrustRetries - 1));
          for (double& v : trial) v *= 1 + scale * unit_(rng_);
        }
        int info = 0;
        double res = 0;
        ++solves_;
        // Every step at the acceptance of intermediate steps; the search polishes the arrival.
        ok = shooter_.solve(trial, 0.0, s_.accept_residual, info, res) && admissible_(trial.data());
        if (ok) {
          reached = along_.time_thrust(trial, next);
          ok = stays_on_branch(prediction, reached, next - sigma);
        }
        ContinuationStep record{stage, knobs_.thrust_N(next), ok, res, shooter_.last_step_evaluations};
        if (ok) {
          record.revolutions = revolutions_of(trial);
          record.tf_days = reached * std::exp(-next) * kProblem.time_unit_days;
          info_ = info;
          max_residual_ = res;
          tick_(record.value, record.revolutions);
        }
        steps.push_back(record);
      }
      if (!ok) {
        set(sigma);
        step *= 0.5;
        if (step < 1e-3) break;
        continue;
      }
      x = trial;
      sigma = next;
      step = std::min(step * 1.5, 0.5);
      if (to_next_branch && std::log(reached / prediction) < -0.002) return true;
      if (reached > give_up_above) return false;
      if (direction * (to - sigma) > 0) predicted = predict(x, sigma);
    }
    return false;
  }

  // Perturbed retries (above) only on steps of at most `step` in sigma; a longer step that fails is
  // halved at once (its prediction, not a fold, is what failed).
  void perturb_within(double step) { perturb_within_ = step; }

  int evaluations() const { return shooter_.evaluations; }
  const std::vector<double>& last_F() const { return shooter_.last_F; }
  int info() const { return info_; }
  double max_residual() const { return max_residual_; }
  void set(double sigma) {
    knobs_.scale_thrust(sigma);
    if (along_.set) along_.set(sigma);
  }

 private:
  static constexpr int kThrustRetries = 8;
  double revolutions_of(const std::vector<double>& x) const {
    return along_.revolutions ? along_.revolutions(x) : shape_of(s_, x, 0.0).revolutions;
  }
  // dx/dsigma at the current point, dF/dsigma by a difference over 1e-7.
  bool predict(const std::vector<double>& x, double sigma) {
    return parameter_tangent(
        shooter_, x, 0.0, [this](double v) { set(v); }, sigma, 1e-7, tangent_);
  }

  const Settings& s_;
  ProgramKnobs& knobs_;
  Admissible& admissible_;
  Tick& tick_;
  const ThrustPath& along_;
  Shooter shooter_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{-1.0, 1.0};
  std::vector<double> tangent_;
  int solves_ = 0, info_ = 0;
  double max_residual_ = INFINITY, perturb_within_ = INFINITY;
};

// How far below the problem's thrust the next branch is looked for (ThrustFollower's
// to_next_branch), the longest step (in sigma) of that path retried from perturbed predictions, and
// the record's stage of that path.
constexpr double kNextBranchScale = 1.2;
constexpr double kNextBranchPerturbedStep = 0.025;
constexpr const char* kNextBranchStage = "the next branch: maximum thrust [N] below and back";

// From the solution x (eps = 0) at `sigma0` down to sigma = 0 (ThrustFollower). Along a path the
// branches of a many-revolution transfer cross: each, followed down, first improves (its flight
// time times the thrust falls) and then worsens until it folds, where the path goes on on the
// branch of about one revolution more (GTO to GEO: 858.6 N h at 7.37 N on one, 849.4 N h at 7.17 N
// on the next). So the path may arrive on the worsening stretch of a branch while the next one is
// already cheaper there: from the arrival the path goes on down (at most to the thrust over
// kNextBranchScale, and not once it has worsened 2 % on its own branch) until it reaches the next
// branch, which is followed back up to sigma = 0 unless it rises 0.5 % above the arrival on the way
// (a branch followed up worsens steeply toward its end: GTO to GEO at 0.5 N, 849.9 N h at 0.409 N,
// 856.0 at 0.430, 872.5 at 0.464). The cheapest arrival is the path's. On this path a failed step
// is retried from perturbed predictions only when it is short (kNextBranchPerturbedStep, 2.5 % of
// the thrust), else halved at once: the landing on the next branch comes from such a retry near the
// fold of the branch left (at 0.5 N, a step of 1.9 %, the sixth attempt), while at a long step
// they mostly repeat a prediction too far out (at 0.5 N the failed attempts at steps of 3-18 % were
// over 80 % of this path's evaluations, nine at each such step). The branches of fewer
// revolutions are not looked for above the problem's thrust: the path left each of them at its
// fold, above the problem's thrust, so none reaches it (a probe up the thrust from every arrival of
// the GTO to GEO family, 20 N to 0.5 N, found none). The knobs are set to sigma0 first and left at
// the last sigma reached (the caller restores them). `along` is the system followed: the shooting
// function itself by default, or another with the same variables (time_route.hpp's minimum-time
// system), whose own parameters `along.set` moves with sigma, whose revolutions `along.revolutions`
// tells and whose flight time times thrust `along.time_thrust` gives. `tick(thrust_N, revolutions)`
// reports progress.
template <class Admissible, class Tick>
PathArrival continue_thrust_down(const Settings& s, ProgramKnobs& knobs, std::vector<double> x, double sigma0,
                                 Admissible& admissible, int& evaluations, Tick&& tick, const ThrustPath& along = {}) {
  PathArrival out;
  ThrustFollower<Admissible, Tick> follower(s, knobs, admissible, tick, along);
  const auto arrive_at = [&](const std::vector<double>& at) {
    out.x = at;
    out.F = follower.last_F();
    out.info = follower.info();
    out.max_residual = follower.max_residual();
  };
  double sigma = sigma0;
  follower.follow(x, sigma, 0.0, "maximum thrust [N], the final time's window scaled inversely", out.steps);
  out.reached = knobs.thrust_N(sigma);
  out.reached_time = along.time_thrust(x, sigma) * std::exp(-sigma);
  if (sigma == 0) {
    out.arrived = true;
    arrive_at(x);
    // The next branch: past the problem's thrust onto a cheaper one, and back.
    const double arrival = along.time_thrust(x, 0);
    std::vector<double> next = x;
    double at = 0;
    follower.perturb_within(kNextBranchPerturbedStep);
    if (follower.follow(next, at, -std::log(kNextBranchScale), kNextBranchStage, out.steps, true, 1.02 * arrival)) {
      follower.follow(next, at, 0.0, kNextBranchStage, out.steps, false, 1.005 * arrival);
      if (at == 0 && along.time_thrust(next, 0) < arrival) arrive_at(next);
    }
    follower.set(0.0);
  }
  evaluations += follower.evaluations();
  return out;
}

// A search of the problem as the knobs leave it (the thrust raised), with the routes a nested
// search runs (pipeline.hpp); where the flight time is known to be about `estimate` (normalized)
// its companion and starts start from it (scale.hpp).
Result nested_search(SearchContext& parent, double estimate = NAN);

// The factor by which to raise the thrust so that a transfer of `revolutions` winds at most
// kFewRevolutions times (the revolutions fall about as the thrust rises): a power of two, 2 at least.
inline double raise_factor(double revolutions) {
  return std::exp2(std::ceil(std::log2(std::max(2.0, revolutions / kFewRevolutions))));
}

// The thrust raised by `factor` (guessed from the revolutions seen, quadrupled where the search
// there finds none, at most 2^kMaxThrustDoublings) until a search there returns an extremal of at
// most kFewRevolutions. Each search is recorded in `record`; the knobs are left at the last factor.
inline Result search_at_raised_thrust(SearchContext& c, double& factor, std::vector<ContinuationStep>& record) {
  const int best = best_index(c.rec());
  factor = best < 0 ? 4.0 : raise_factor(c.rec().extremals[best].shape.revolutions);
  while (factor <= std::exp2(kMaxThrustDoublings) && !c.out_of_time()) {
    const double sigma = std::log(factor);
    c.knobs.scale_thrust(sigma);
    c.progress.stage("thrust raised to " + number_text(c.knobs.thrust_N(sigma)) + " N (x" + number_text(factor) +
                     "), the final time's window scaled by 1/" + number_text(factor) + ": the search there");
    Result raised = nested_search(c);
    c.count(raised.evaluations);
    const bool found = raised.status == Status::kConverged;
    ContinuationStep step{"raised thrust: the search there [N]", c.knobs.thrust_N(sigma), found,
                          found ? raised.max_residual : INFINITY, raised.evaluations};
    step.revolutions = found ? shape_of(c.coarse, raised.x, 0.0).revolutions : NAN;
    record.push_back(step);
    if (found && step.revolutions <= kFewRevolutions) return raised;
    factor *= found ? raise_factor(step.revolutions) : 4.0;
  }
  return {};
}

// The route: the thrust raised until a search there returns a transfer of few revolutions
// (search_at_raised_thrust), then its best extremals continued down to the problem's thrust, one
// after the other (they share the program's thrust), and entered into the pool.
class ThrustRoute : public Route {
 public:
  const char* name() const override { return "thrust continuation"; }
  std::string skip(const SearchContext& c) const override {
    if (!c.coarse.search_thrust_continuation) return "search_thrust_continuation is off";
    if (c.nested) return "inside a search at a raised thrust";
    if (kProblem.objective != Objective::time) return "not a minimum-time problem";
    if (!targets_fixed_in_time()) return "a target moves on the calendar: a raised thrust would meet it elsewhere";
    if (!c.knobs.thrust_scalable()) return "the program has no maximum thrust to scale";
    if (settled(c.rec()) && !c.many_revolutions_expected())
      return "the search settled the problem with few revolutions";
    return "";
  }

  std::string run(SearchContext& c) override {
    SearchRecord& rec = c.rec();
    double factor = 1;
    // The time scale's search, where it found a transfer of few revolutions, else a search of its own.
    const bool measured =
        c.scale_search.status == Status::kConverged && rec.time_scale.raised_revolutions <= kFewRevolutions;
    if (measured) factor = rec.time_scale.factor;
    Result raised = measured ? c.scale_search : search_at_raised_thrust(c, factor, rec.thrust_continuation);
    c.knobs.restore();
    if (raised.status != Status::kConverged) {
      c.progress.stage("thrust continuation: no search at a raised thrust returned a transfer of few revolutions");
      return "no search at a raised thrust returned a transfer of few revolutions";
    }
    double sigma = std::log(factor);
    const std::string first = number_text(c.knobs.thrust_N(sigma));
    int arrived = 0, restarts = 0;
    for (;;) {
      double lowest = sigma, time = NAN;  // the lowest scale any branch reached, its flight time
      arrived = continue_branches(c, raised, sigma, lowest, time);
      if (arrived > 0 || restarts >= kMaxThrustRestarts || !(lowest < sigma - 1e-3) || c.out_of_time()) break;
      // Every branch ended at a fold above the problem's thrust: a search where they went lowest.
      ++restarts;
      sigma = lowest;
      c.knobs.scale_thrust(sigma);
      c.progress.stage("thrust continuation: every branch ended above the problem's thrust; a search at " +
                       number_text(c.knobs.thrust_N(sigma)) + " N, where they went lowest");
      raised = nested_search(c, time);
      c.knobs.restore();
      c.count(raised.evaluations);
      ContinuationStep step{"raised thrust: the search there [N]", c.knobs.thrust_N(sigma),
                            raised.status == Status::kConverged, raised.max_residual, raised.evaluations};
      rec.thrust_continuation.push_back(step);
      if (raised.status != Status::kConverged) break;
    }
    return "from the search at " + first + " N (x" + number_text(factor) + ")" +
           (restarts > 0 ? ", " + std::to_string(restarts) + " more where the branches ended" : "") + "; " +
           std::to_string(arrived) + " branches arrived at " + number_text(c.knobs.own_thrust_N()) + " N";
  }

 private:
  // The kThrustBranches best distinct extremals of the search `raised` at the scale sigma (the
  // best path down need not start from the best extremal up there), continued down one after the
  // other (they share the program's thrust), each arrival entered into the pool. Returns how many
  // arrived; `lowest` is the lowest scale any reached, and `time` the flight time there.
  int continue_branches(SearchContext& c, const Result& raised, double sigma, double& lowest, double& time) {
    SearchRecord& rec = c.rec();
    std::vector<const Extremal*> branches;
    for (const Extremal& e : raised.search.extremals)
      if (returnable(e)) branches.push_back(&e);
    std::stable_sort(branches.begin(), branches.end(),
                     [](const Extremal* a, const Extremal* b) { return a->shape.cost < b->shape.cost; });
    if (branches.size() > static_cast<std::size_t>(kThrustBranches)) branches.resize(kThrustBranches);
    const std::vector<ContinuationStep> raising = rec.thrust_continuation;
    const double target_N = c.knobs.own_thrust_N();
    int arrived = 0;
    for (std::size_t k = 0; k < branches.size() && !c.out_of_time(); ++k) {
      int evaluations = 0;
      const std::string which = "the extremal " + std::to_string(k + 1) + " of " + std::to_string(branches.size()) +
                                " of the search at " + number_text(c.knobs.thrust_N(sigma)) + " N";
      const auto tick = [&](double thrust_N, double revolutions) {
        c.progress.tick("thrust continuation from " + which + ": " + number_text(thrust_N) + " N of " +
                        number_text(target_N) + " N, " + number_text(revolutions, 4) + " revolutions");
      };
      // At the integrator's own tolerance: over tens of revolutions the search's leaves F a floor
      // near 1e-6 (measured at 0.5 N), above the acceptance.
      PathArrival a = continue_thrust_down(c.fine, c.knobs, branches[k]->x, sigma, c.admissible, evaluations, tick);
      c.knobs.restore();
      c.count(evaluations);
      rec.thrust_continuation.insert(rec.thrust_continuation.end(), a.steps.begin(), a.steps.end());
      if (std::log(a.reached / target_N) < lowest) {
        lowest = std::log(a.reached / target_N);
        time = a.reached_time;
      }
      if (!a.arrived) {
        c.progress.stage("thrust continuation from " + which + ": ended at " + number_text(a.reached) + " N");
        continue;
      }
      rec.thrust_continuation_arrived = true;
      ++arrived;
      Extremal entry =
          arrival_extremal(c.coarse, a, "single shooting, continued down the maximum thrust from " + which);
      entry.continuation.insert(entry.continuation.begin(), raising.begin(), raising.end());
      const Shape shape = entry.shape;
      c.pool.enter(name(), std::move(entry));
      c.progress.stage("thrust continuation from " + which + ": arrived with " + objective_text(shape.cost) + ", " +
                       number_text(shape.revolutions, 5) + " revolutions");
    }
    return arrived;
  }
};

}  // namespace

}  // namespace helios_rt

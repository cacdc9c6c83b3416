// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the families route (templates/runtime/search/families.hpp): the
// transfer-angle continuation, by which the search looks for the neighbours of an extremal along
// its family, and the walk along the family of the best extremal while the objective improves.
//
// The extremals of a rendezvous with many revolutions form a family ordered by the revolutions
// they sweep (the objective often monotone along it), and random starts may never land in the
// basin of the best member. A member with one revolution fewer (or more) is reached from a known
// one by turning the target: the rows compare the end state, rotated by -theta about the
// departure's angular momentum (state and costates alike: Propagator::end_rotation), with the
// target, so they ask for the target turned by theta. theta goes from 0 to -2 pi (one revolution
// fewer) or 2 pi (one more) by continuation, each step predicted along the path's tangent and
// required to sweep its step in theta / 2 pi revolutions more than the last (within a quarter;
// with a free final time the target's own motion adds a little). At
// |theta| = 2 pi the turned target is the target itself: the rotation is switched off and the
// solution, solved once more, is an extremal of the problem as stated with one revolution fewer
// (more). Nothing of the intermediate problems reaches the answer: they are a path to a start.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// The rotation by angle a about the unit vector k (row-major), by Rodrigues' formula.
inline std::array<double, 9> rotation_about(const std::array<double, 3>& k, double a) {
  const double c = std::cos(a), s = std::sin(a), v = 1 - c;
  return {c + v * k[0] * k[0],        v * k[0] * k[1] - s * k[2], v * k[0] * k[2] + s * k[1],
          v * k[1] * k[0] + s * k[2], c + v * k[1] * k[1],        v * k[1] * k[2] - s * k[0],
          v * k[2] * k[0] - s * k[1], v * k[2] * k[1] + s * k[0], c + v * k[2] * k[2]};
}

// The unit angular momentum of a trajectory's first sample (the axis of Shape::revolutions).
inline bool departure_axis(const RecordedPath& path, std::array<double, 3>& k) {
  if (path.samples.empty()) return false;
  const auto& y = path.samples.front().y;
  k = {y[1] * y[5] - y[2] * y[4], y[2] * y[3] - y[0] * y[5], y[0] * y[4] - y[1] * y[3]};
  const double n = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
  if (!(n > 0)) return false;
  for (double& c : k) c /= n;
  return true;
}

// The transfer-angle continuation (see the top of this file) of x, a solution of the shooting
// function at eps, to one sweeping `direction` (+1 or -1) revolutions more. True with x replaced by
// it, solved at eps to `accept` with the rotation off; every solve is appended to `steps` (stage
// "transfer angle", value theta in degrees) and counted in `evaluations`.
template <class Admissible>
bool turn_one_revolution(const Settings& s, std::vector<double>& x, double eps, int direction, double accept,
                         Admissible& admissible, std::vector<ContinuationStep>& steps, int& evaluations) {
  if (!end_rotation_possible()) return false;
  std::array<double, 3> axis{};
  try {
    if (!departure_axis(recorded_path(s, x, eps, INFINITY), axis)) return false;
  } catch (const numerical_error&) {
    return false;
  }
  double revolutions = shape_of(s, x, eps).revolutions;
  std::array<double, 9> R = rotation_about(axis, 0.0);
  bool rotated = true;
  const Function turned = [&](const double* z, double e, Propagator& prop, double* F, double* J) {
    prop.end_rotation = rotated ? &R : nullptr;
    try {
      shooting_function_and_jacobian(z, e, prop, F, J);
    } catch (...) {
      prop.end_rotation = nullptr;
      throw;
    }
    prop.end_rotation = nullptr;
  };
  Shooter shooter(s, turned, kContinuationStart);
  const auto at_angle = [&](double theta) { R = rotation_about(axis, -theta); };
  const auto solve_at = [&](std::vector<double>& z, double theta, double tolerance) {
    int info = 0;
    double res = 0;
    const bool ok = shooter.solve(z, eps, tolerance, info, res) && admissible(z.data());
    steps.push_back({"transfer angle", theta * 180 / M_PI, ok, res, shooter.last_step_evaluations});
    return ok;
  };
  const double target = direction * 2 * M_PI, smallest = 2 * M_PI / 256;
  double theta = 0, step = direction * 2 * M_PI / 8;
  std::vector<double> tangent;
  bool predicted = false;
  while (theta != target && wall_seconds() <= s.time_limit_s) {
    const double next = std::fabs(target - theta) <= std::fabs(step) ? target : theta + step;
    std::vector<double> trial = x;
    if (predicted)
      for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent[i] * (next - theta);
    at_angle(next);
    bool ok = solve_at(trial, next, s.accept_residual);
    const double now = ok ? shape_of(s, trial, eps).revolutions : 0;
    if (ok && std::fabs(now - revolutions - (next - theta) / (2 * M_PI)) > 0.25)
      ok = steps.back().converged = false;  // another branch

    if (!ok) {
      step *= 0.5;
      if (std::fabs(step) < smallest) break;
      continue;
    }
    x = trial;
    theta = next;
    revolutions = now;
    step = std::clamp(step * 1.5, -2 * M_PI / 4, 2 * M_PI / 4);
    // The tangent: dF/dtheta by a difference over 1e-6 rad.
    std::vector<double> F0(x.size()), F1(x.size());
    const double d = 1e-6 * direction;
    predicted = shooter.evaluate_at(x.data(), eps, F0.data());
    at_angle(theta + d);
    predicted = predicted && shooter.evaluate_at(x.data(), eps, F1.data());
    at_angle(theta);
    if (predicted) {
      for (std::size_t i = 0; i < x.size(); ++i) F1[i] = (F1[i] - F0[i]) / d;
      predicted = path_tangent(shooter, x, eps, F1, tangent);
    }
  }
  bool arrived = false;
  if (theta == target) {
    rotated = false;  // the turned target is the target: the problem as stated
    arrived = solve_at(x, theta, accept);
  }
  evaluations += shooter.evaluations;
  return arrived;
}

// The family walk: from the best extremal, its neighbours with one revolution fewer and one more,
// each taken from the search where it has one of that count (reached, or at eps_start and not
// continued: continued now), else turned from the best by the transfer angle; then again from the
// new best, until a round finds no better one. Every neighbour looked for is recorded (rec.family).
class FamiliesRoute : public Route {
 public:
  const char* name() const override { return "families"; }
  std::string skip(const SearchContext& c) const override {
    if (!c.coarse.search_families) return "search_families is off";
    if (best_index(c.rec()) < 0) return "no extremal to walk from";
    return "";
  }

  std::string run(SearchContext& c) override {
    std::vector<std::pair<int, int>> tried;  // (extremal, direction)
    const double first = best_objective(c.rec());
    for (;;) {
      const int best = best_index(c.rec());
      if (best < 0 || c.out_of_time()) break;
      const double before = best_objective(c.rec());
      for (const int direction : {-1, 1}) {
        if (std::find(tried.begin(), tried.end(), std::make_pair(best, direction)) != tried.end()) continue;
        tried.emplace_back(best, direction);
        if (!c.out_of_time()) look_for_neighbour(c, best, direction);
      }
      if (!(best_objective(c.rec()) < before)) break;
    }
    const double last = best_objective(c.rec());
    return std::to_string(tried.size()) + " neighbours looked for" +
           (last < first ? ", best improved to " + objective_text(last) : ", no better one");
  }

 private:
  // One neighbour of extremal `of` (see the class).
  void look_for_neighbour(SearchContext& c, int of, int direction) {
    SearchRecord& rec = c.rec();
    FamilyProbe probe;
    probe.from = of;
    probe.direction = direction;
    probe.revolutions = rec.extremals[of].shape.revolutions + direction;
    const auto near = [&](const Shape& shape) { return std::fabs(shape.revolutions - probe.revolutions) < 0.5; };
    for (std::size_t i = 0; i < rec.extremals.size() && probe.found < 0; ++i)
      if (near(rec.extremals[i].shape)) {
        probe.how = "reached by the search";
        probe.found = static_cast<int>(i);
      }
    for (std::size_t i = 0; i < rec.start_extremals.size() && probe.found < 0 && probe.how.empty(); ++i)
      if (near(rec.start_extremals[i].shape) && !rec.start_extremals[i].continued) {
        probe.how = "an extremal at eps_start of that count";
        probe.found = continue_if_promising(c, name(), static_cast<int>(i), probe.how);
      }
    // The revolutions are swept about the departure's angular momentum: a member that would sweep
    // fewer than none flies against its departure's motion, which no thrust of a transfer reverses.
    if (probe.how.empty() && probe.revolutions < 0) probe.how = "none: it would sweep fewer than no revolutions";
    if (probe.how.empty()) probe.found = turn(c, of, direction, probe.how);
    c.progress.stage("family of extremal " + std::to_string(of) + ": " +
                     (direction < 0 ? "one fewer, " : "one more, ") + number_text(probe.revolutions, 3) +
                     " revolutions (" + probe.how +
                     "): " + (probe.found < 0 ? "none" : "extremal " + std::to_string(probe.found)));
    rec.family.push_back(probe);
  }

  // The transfer angle from extremal `of`: from its eps_start extremal where it has one (the turned
  // solution joins them and is continued to eps = 0), else from itself at eps = 0. Returns the
  // extremal at eps = 0 reached (-1: none).
  int turn(SearchContext& c, int of, int direction, std::string& how) {
    SearchRecord& rec = c.rec();
    const Extremal& e = rec.extremals[of];
    std::vector<ContinuationStep> steps;
    int evaluations = 0;
    if (!e.from.empty()) {
      const int parent = e.from.front();
      StartRun run;
      run.x = rec.start_extremals[parent].x;
      how = "transfer angle from the extremal at eps_start " + std::to_string(parent);
      // A path to a start: on the looser integration, its arrival solved again at the search's.
      const Settings loose = loose_settings(c.coarse);
      bool ok = turn_one_revolution(loose, run.x, loose.eps_start, direction, loose.accept_residual, c.admissible,
                                    steps, evaluations);
      Shooter shooter(c.coarse, kContinuationStart);
      int info = 0;
      ok = ok && shooter.solve(run.x, c.coarse.eps_start, c.coarse.accept_residual, info, run.res) &&
           c.admissible(run.x.data());
      c.count(evaluations + shooter.evaluations);
      if (!ok) return -1;
      run.shape = shape_of(c.coarse, run.x, c.coarse.eps_start);
      const int k = c.pool.enter_start(rec.start_extremals, run, -1, how);
      if (rec.start_extremals[k].continued) return rec.start_extremals[k].arrived;
      return continue_if_promising(c, name(), k, how);
    }
    std::vector<double> x = e.x;
    how = "transfer angle from it at eps = 0";
    const bool ok =
        turn_one_revolution(c.coarse, x, 0.0, direction, c.coarse.final_residual, c.admissible, steps, evaluations);
    c.count(evaluations);
    if (!ok) return -1;
    return c.pool.enter(
        name(), solved_extremal(c.coarse, x, "single shooting, transfer angle from extremal " + std::to_string(of),
                                std::move(steps)));
  }
};

}  // namespace

}  // namespace helios_rt

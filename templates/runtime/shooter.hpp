// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, shooter (templates/runtime/shooter.hpp): the shooter: hybrd on the
// shooting function, and one recorded homotopy step.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

inline std::string hybrd_meaning(int info) {
  switch (info) {
    case 0:
      return "improper input parameters";
    case 1:
      return "relative error between two consecutive iterates is at most tol";
    case 2:
      return "number of calls to fcn has reached 200*(n+1)";
    case 3:
      return "tol is too small; no further improvement in x is possible";
    case 4:
      return "iteration is not making good progress";
    default:
      return "stopped by the shooting function (integration failure or time limit)";
  }
}

// How hybrd starts: hybrd1's choice (trust region 100 times the unscaled |x|) suits random guesses
// and the eps steps; a continuation step starts next to its solution and takes the trust region
// at |D x| with D the Jacobian's column norms (hybrd mode 1, factor 1), so it does not jump to
// another branch.
struct HybrdStart {
  double factor = 100;
  bool scaled = false;  // hybrd mode 1: D from the Jacobian's column norms; else D = 1 (mode 2)
};
constexpr HybrdStart kContinuationStart{1.0, true};

// Whether the solves of the shooting function use its exact Jacobian: the program has one (the
// JACOBIAN module) and the settings ask for it.
inline bool exact_jacobian(const Settings& s) {
  return kModules.shooting_jacobian != nullptr && s.jacobian == "exact";
}

// A function of the shooting variables for the shooter: F at x and, where J is not null, its
// Jacobian J (column-major, J[i + j n] = dF_i/dx_j; asked for only where exact_jacobian). The
// shooting function, or a homotopy of it with its own terms differentiated.
using Function = std::function<void(const double* x, double eps, Propagator& prop, double* F, double* J)>;

// The shooting function as a Function: shooting_jacobian where J is asked for.
inline void shooting_function_and_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J) {
  if (J)
    kModules.shooting_jacobian(x, eps, prop, F, J);
  else
    shooting_function(x, eps, prop, F);
}

// A Function of n variables from call(z, eps, prop, F), written once for either scalar: F on
// double, and where J is asked for, the same call on dual numbers (dual_jacobian).
template <class Call>
Function function_on_either_scalar(int n, Call call) {
  return [n, call](const double* z, double eps, Propagator& prop, double* F, double* J) {
    if (J)
      dual_jacobian(n, z, F, J, [&](const Dual* zd, Dual* Fd) { call(zd, eps, prop, Fd); });
    else
      call(z, eps, prop, F);
  };
}

// Row `row` of an n x n column-major Jacobian: the unit row of variable v (the row is x_v itself).
inline void unit_row(double* J, int n, int row, int v) {
  for (int j = 0; j < n; ++j) J[row + j * n] = j == v ? 1.0 : 0.0;
}

// Solves A v = b in place (A n x n, column-major, overwritten) by Gaussian elimination with
// partial pivoting. False when A is singular or v not finite.
inline bool solve_linear(int n, std::vector<double>& A, std::vector<double>& b) {
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int i = c + 1; i < n; ++i)
      if (std::fabs(A[i + c * n]) > std::fabs(A[p + c * n])) p = i;
    if (!(std::fabs(A[p + c * n]) > 0)) return false;
    if (p != c) {
      for (int j = c; j < n; ++j) std::swap(A[c + j * n], A[p + j * n]);
      std::swap(b[c], b[p]);
    }
    for (int i = c + 1; i < n; ++i) {
      const double l = A[i + c * n] / A[c + c * n];
      if (l == 0) continue;
      for (int j = c + 1; j < n; ++j) A[i + j * n] -= l * A[c + j * n];
      b[i] -= l * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    for (int j = c + 1; j < n; ++j) b[c] -= A[c + j * n] * b[j];
    b[c] /= A[c + c * n];
    if (!std::isfinite(b[c])) return false;
  }
  return true;
}

class Shooter {
 public:
  // The shooting function itself, with its exact Jacobian where the program has one.
  explicit Shooter(const Settings& s, HybrdStart start = {}) : Shooter(s, shooting_function_and_jacobian, start) {}
  Shooter(const Settings& s, Function function, HybrdStart start = {})
      : settings_(s), prop_(s), function_(std::move(function)), start_(start), exact_(exact_jacobian(s)) {}

  // hybrd1 (hybrj1 with the exact Jacobian) from x at eps; true if max|F| <= accept. Returns the
  // info code through `info`.
  bool solve(std::vector<double>& x, double eps, double accept, int& info, double& max_res) {
    eps_ = eps;
    failed_ = false;
    reached_.clear();
    const int n = static_cast<int>(x.size());
    size_ = n;
    std::vector<double> F(n), wa(static_cast<std::size_t>(n * (3 * n + 13)) / 2 + 1);
    const int before = evaluations;
    if (exact_) {
      std::vector<double> J(static_cast<std::size_t>(n * n));
      const int lr = n * (n + 1) / 2;
      std::vector<double> w(static_cast<std::size_t>(6 * n + lr));
      for (int j = 0; j < n; ++j) w[j] = 1;
      int nfev = 0, njev = 0;
      // hybrj1's call (100 (n + 1) evaluations of F, D = 1) with hybrd's start
      info = hybrj(&Shooter::callback_with_jacobian, this, n, x.data(), F.data(), J.data(), n, settings_.hybrd_tol,
                   100 * (n + 1), w.data(), start_.scaled ? 1 : 2, start_.factor, 0, &nfev, &njev, w.data() + 6 * n, lr,
                   w.data() + n, w.data() + 2 * n, w.data() + 3 * n, w.data() + 4 * n, w.data() + 5 * n);
      if (info == 5) info = 4;
    } else if (start_.factor == 100 && !start_.scaled) {
      info = hybrd1(&Shooter::callback, this, n, x.data(), F.data(), settings_.hybrd_tol, wa.data(),
                    static_cast<int>(wa.size()));
    } else {  // hybrd1's call with the trust region's start changed
      const int lr = n * (n + 1) / 2;
      double* w = wa.data();
      for (int j = 0; j < n; ++j) w[j] = 1;
      int nfev = 0;
      info = hybrd(&Shooter::callback, this, n, x.data(), F.data(), settings_.hybrd_tol, 200 * (n + 1), n - 1, n - 1,
                   0.0, w, start_.scaled ? 1 : 2, start_.factor, 0, &nfev, w + 6 * n + lr, n, w + 6 * n, lr, w + n,
                   w + 2 * n, w + 3 * n, w + 4 * n, w + 5 * n);
      if (info == 5) info = 4;
    }
    if (failed_) info = -1;
    if (!reached_.empty()) {  // stopped at a point that met stop_below: hybrd's x is its last iterate
      x = reached_;
      info = 1;
    }
    // hybrd1 returns the x of the smallest residual it saw; evaluate there for the record.
    if (!evaluate(x.data(), F.data())) {
      max_res = INFINITY;
      return false;
    }
    max_res = 0;
    for (double f : F) max_res = std::max(max_res, std::fabs(f));
    last_F = F;
    last_step_evaluations = evaluations - before;
    return std::isfinite(max_res) && max_res <= accept;
  }

  bool evaluate(const double* x, double* F) {
    try {
      function_(x, eps_, prop_, F, nullptr);
      ++evaluations;
      for (int i = 0; i < size_; ++i)
        if (!std::isfinite(F[i])) return false;
      return true;
    } catch (const numerical_error&) {
      return false;
    }
  }

  // F and the exact Jacobian J (column-major, n x n) at (x, eps): false when the program has no
  // exact Jacobian or the evaluation fails or is not finite.
  bool jacobian_at(const std::vector<double>& x, double eps, std::vector<double>& F, std::vector<double>& J) {
    if (!exact_) return false;
    const std::size_t n = x.size();
    F.resize(n);
    J.resize(n * n);
    counters().exact_jacobian_evaluations.fetch_add(1, std::memory_order_relaxed);
    try {
      function_(x.data(), eps, prop_, F.data(), J.data());
    } catch (const numerical_error&) {
      return false;
    }
    for (const double v : J)
      if (!std::isfinite(v)) return false;
    for (const double v : F)
      if (!std::isfinite(v)) return false;
    return true;
  }

  // F at (x, eps): false where the function fails or is not finite.
  bool evaluate_at(const double* x, double eps, double* F) {
    const double kept = eps_;
    eps_ = eps;
    const bool ok = evaluate(x, F);
    eps_ = kept;
    return ok;
  }

  // A solve stops at the first point whose max|F| is at most `residual` (0: hybrd's own tests
  // only): where the integration is looser than the tolerance hybrd works to, the iterations past
  // that point only chase the integration's noise.
  void stop_below(double residual) { stop_below_ = residual; }

  int evaluations = 0;
  int last_step_evaluations = 0;
  std::vector<double> last_F;
  Propagator& propagator() { return prop_; }

 private:
  static int callback(void* self, int n, const double* x, double* F, int iflag) {
    auto* me = static_cast<Shooter*>(self);
    Counters& c = counters();
    c.residual_evaluations.fetch_add(1, std::memory_order_relaxed);
    if (iflag == 2) {  // fdjac1's n calls in a row make one finite-difference Jacobian
      c.jacobian_residual_calls.fetch_add(1, std::memory_order_relaxed);
      if (me->jacobian_calls_++ % n == 0) c.jacobian_evaluations.fetch_add(1, std::memory_order_relaxed);
    } else {
      me->jacobian_calls_ = 0;
    }
    if (wall_seconds() > me->settings_.time_limit_s) {
      me->failed_ = true;
      return -1;
    }
    if (!me->evaluate(x, F)) {
      // A failed integration is a large residual, so hybrd backs off instead of stopping.
      for (int i = 0; i < n; ++i) F[i] = 1e6;
      return 0;
    }
    return iflag == 1 && me->met_stop(x, F) ? -1 : 0;
  }

  // Whether F at x meets stop_below; x is kept as the solve's answer where it does.
  bool met_stop(const double* x, const double* F) {
    if (!(stop_below_ > 0)) return false;
    for (int i = 0; i < size_; ++i)
      if (!(std::fabs(F[i]) <= stop_below_)) return false;
    reached_.assign(x, x + size_);
    return true;
  }

  // hybrj's function: F (iflag 1) or the exact Jacobian J (iflag 2) at x.
  static int callback_with_jacobian(void* self, int n, const double* x, double* F, double* J, int ldfjac, int iflag) {
    auto* me = static_cast<Shooter*>(self);
    Counters& c = counters();
    if (wall_seconds() > me->settings_.time_limit_s) {
      me->failed_ = true;
      return -1;
    }
    if (iflag == 1) {
      c.residual_evaluations.fetch_add(1, std::memory_order_relaxed);
      if (!me->evaluate(x, F)) {
        for (int i = 0; i < n; ++i) F[i] = 1e6;  // as in callback: hybrj backs off
        return 0;
      }
      return me->met_stop(x, F) ? -1 : 0;
    }
    c.exact_jacobian_evaluations.fetch_add(1, std::memory_order_relaxed);
    std::vector<double> F_at(static_cast<std::size_t>(n));
    bool finite = true;
    try {
      me->function_(x, me->eps_, me->prop_, F_at.data(), J);
      for (int k = 0; k < n * ldfjac; ++k) finite = finite && std::isfinite(J[k]);
    } catch (const numerical_error&) {
      finite = false;
    }
    // hybrj asks for a Jacobian only at a point whose F it has; a failed one stops this solve.
    if (!finite) {
      me->failed_ = true;
      return -1;
    }
    return 0;
  }

  const Settings& settings_;
  Propagator prop_;
  Function function_;
  HybrdStart start_;
  bool exact_ = false;
  int size_ = kProblem.num_vars;
  double eps_ = 1;
  bool failed_ = false;
  double stop_below_ = 0;
  std::vector<double> reached_;
  long long jacobian_calls_ = 0;  // iflag-2 calls since the last iflag-1 call
};

// The tangent dx/dp of a path F(x, p) = 0 at its solution x: -J^-1 dF/dp, with the shooter's exact
// Jacobian at x (dF_dp is overwritten). False without an exact Jacobian or where it fails.
inline bool path_tangent(Shooter& shooter, const std::vector<double>& x, double eps, std::vector<double>& dF_dp,
                         std::vector<double>& dx) {
  std::vector<double> F, J;
  if (!shooter.jacobian_at(x, eps, F, J)) return false;
  dx = std::move(dF_dp);
  for (double& v : dx) v = -v;
  return solve_linear(static_cast<int>(x.size()), J, dx);
}

// The tangent dx/dp of the solution path in a parameter p of the shooting function, held outside
// it (a held final time, the thrust's scaling): dF/dp by a difference over d, `set(v)` putting the
// parameter at v, left at `at`.
template <class Set>
bool parameter_tangent(Shooter& shooter, const std::vector<double>& x, double eps, Set&& set, double at, double d,
                       std::vector<double>& dx) {
  std::vector<double> F0(x.size()), F1(x.size());
  set(at);
  bool ok = shooter.evaluate_at(x.data(), eps, F0.data());
  set(at + d);
  ok = ok && shooter.evaluate_at(x.data(), eps, F1.data());
  set(at);
  if (!ok) return false;
  for (std::size_t i = 0; i < x.size(); ++i) F1[i] = (F1[i] - F0[i]) / d;
  return path_tangent(shooter, x, eps, F1, dx);
}

// The steps of a natural continuation in a parameter: the first, the smallest tried before the
// path is given up, and the largest.
struct ParameterSteps {
  double first, smallest, largest;
};

// The solution x of `shooter` followed in a parameter p (`set(v)` puts it at v) from `from`
// toward `to` while the steps converge: each step predicted along the path's tangent (dF/dp by a
// difference over `d`), grown by 1.5 after a success and halved after a failure; `accept(x)` must
// hold as well, and `stop(x)` ends the path after a step. Every step is recorded as `what`.
// Returns the last p reached, where x is the solution and the parameter is left.
template <class Set, class Accept, class Stop>
double follow_parameter(const Settings& s, Shooter& shooter, std::vector<double>& x, double eps, Set&& set, double from,
                        double to, double d, ParameterSteps steps, const char* what,
                        std::vector<ContinuationStep>& record, Accept&& accept, Stop&& stop) {
  const double direction = to >= from ? 1.0 : -1.0;
  double p = from, step = steps.first;
  std::vector<double> tangent;
  bool predicted = parameter_tangent(shooter, x, eps, set, p, d, tangent);
  while (direction * (to - p) > 0 && wall_seconds() <= s.time_limit_s) {
    const double next = direction > 0 ? std::min(to, p + step) : std::max(to, p - step), kept = p;
    std::vector<double> trial = x;
    if (predicted)
      for (std::size_t i = 0; i < x.size(); ++i) trial[i] += tangent[i] * (next - kept);
    set(next);
    int info = 0;
    double res = 0;
    const bool ok = shooter.solve(trial, eps, s.accept_residual, info, res) && accept(trial);
    record.push_back({what, next, ok, res, shooter.last_step_evaluations});
    if (!ok) {
      set(kept);
      step *= 0.5;
      if (step < steps.smallest) break;
      continue;
    }
    x = trial;
    p = next;
    step = std::min(step * 1.5, steps.largest);
    if (stop(x)) break;
    predicted = parameter_tangent(shooter, x, eps, set, p, d, tangent);
  }
  return p;
}

// One hybrd solve from x at eps, recorded in r: true if max|F| <= accept and x is admissible.
template <class Admissible>
bool homotopy_step(Shooter& shooter, std::vector<double>& x, double eps, double accept, Result& r,
                   Admissible&& admissible, int& info, double& res) {
  ++r.iterations;
  const bool ok = shooter.solve(x, eps, accept, info, res) && admissible(x.data());
  r.homotopy.push_back({eps, ok, res, shooter.last_step_evaluations});
  return ok;
}

}  // namespace

}  // namespace helios_rt

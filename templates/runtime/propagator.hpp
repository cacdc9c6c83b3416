// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, propagator (templates/runtime/propagator.hpp): the propagator: DOP853
// under the optimal control, one mode at a time, switches located to round-off.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

Propagator::Propagator(const Settings& s) : settings_(s), stepper_(std::make_unique<Dop853>(ny())) {}
Propagator::~Propagator() = default;

double Propagator::held_fraction(int k) const {
  const std::vector<double>& edges = settings_.window_edges;
  return static_cast<std::size_t>(k) < edges.size() ? edges[k] : NAN;
}

bool Propagator::bound_active(int k) const {
  const std::vector<char>& active = settings_.active_bounds;
  return static_cast<std::size_t>(k) < active.size() && active[k] != 0;
}

void Propagator::propagate(double t0, double t1, double* y, const Multipliers& module_mult, Tangents* tangents) {
  const IntegrationTimer timer;
  const Multipliers mult{module_mult.lambda0, module_mult.eps, fuel_weight};
  const bool new_arc = !continues_arc;
  continues_arc = false;
  if (new_arc) ++arc_;
  Mode mode = mode_at(y, mult);
  double t = t0;
  double h = std::min(t1 - t0, 1e-3 * (1 + std::fabs(t1 - t0)));
  std::array<double, kMaxNY> f0{}, ynew{}, fnew{};
  std::array<double, 2> g_old{}, g_new{};
  auto rhs = [&](double tt, const double* yy, double* dy) {
    std::array<double, kMaxControls> control{};
    control_in_mode(yy, mode, mult, control.data());
    dynamics(tt, yy, control.data(), mult, dy);
  };
  if (new_arc) record(t, y, mode, mult);
  int steps = 0;
  while (t < t1) {
    if (++steps > settings_.max_steps) throw numerical_error("integrator exceeded max_steps");
    h = std::min(h, max_step);
    const bool last = h >= t1 - t;
    if (last) h = t1 - t;
    rhs(t, y, f0.data());
    const double err =
        stepper_->step(rhs, t, y, f0.data(), h, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    if (!(err <= 1.0)) {
      h *= Dop853::step_factor(err);
      if (h < 1e-15 * (1 + std::fabs(t))) throw numerical_error("integrator step size underflow");
      continue;
    }
    const int ng = stay_functions(y, mode, mult, g_old.data());
    stay_functions(ynew.data(), mode, mult, g_new.data());
    int crossed = -1;
    double b = h;  // the switch lies in (0, b] of the step
    for (int k = 0; k < ng; ++k)
      if (g_old[k] >= 0 && g_new[k] < 0) crossed = k;
    if (crossed < 0 && ng > 0) crossed = dip(t, y, f0.data(), h, ynew.data(), fnew.data(), mode, mult, b, g_new);
    if (crossed < 0) {
      if (tangents) tangent_step(t, y, h, mode, mult, *tangents, ynew.data());
      t = last ? t1 : t + h;
      std::copy(ynew.begin(), ynew.begin() + ny(), y);
      record(t, y, mode, mult);
      h *= Dop853::step_factor(err);
      continue;
    }
    // Step to the far side of the switch's bracket so the new mode starts past the switch.
    const double hs = locate_switch(rhs, t, y, mode, mult, crossed, g_old[crossed], g_new[crossed], b);
    if (tangents) {
      tangent_step(t, y, hs, mode, mult, *tangents, ynew.data());
    } else {
      rhs(t, y, f0.data());
      stepper_->step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    }
    t += hs;
    std::copy(ynew.begin(), ynew.begin() + ny(), y);
    const Mode before = mode;
    mode = next_mode(mode, crossed, mult);
    if (tangents) switch_jump(t, y, before, crossed, mode, mult, *tangents);
    record(t, y, mode, mult);
    if (switches) {
      std::array<double, kMaxControls> control{};
      control_in_mode(y, mode, mult, control.data());
      switches->push_back({t, control[kProblem.throttle_index]});
    }
    // The new mode's stay function starts at round-off from 0: a long first step that ends past
    // the next switch would bracket that round-off instead. A short one moves clear of it, and
    // the step control grows the steps again.
    h = 1e-6 * (1 + std::fabs(t1 - t0));
  }
}

namespace {

// The variational equations' matrix A = df/dz + df/du du/dz at (t, y) in `mode` (ny x nz,
// row-major; z = (y, lambda0)), with the control there and f itself. The direction law's
// du/dy is the JACOBIAN module's; the interior throttle u = s0 / (s0 - s1) is differentiated here.
void variational_matrix(double t, const double* y, Mode mode, const Multipliers& mult, double* A, double* f) {
  const int n = ny(), nz = n + 1, nc = kProblem.num_controls;
  // NOTE: the arrays are left uninitialized: the JACOBIAN module writes every entry of its outputs
  // and dudz is written whole below (zero-filling them here cost as much as the products below).
  std::array<double, kMaxControls> control{};
  std::array<double, kMaxNY*(kMaxNY + 1)> dfdz;
  std::array<double, kMaxNY * kMaxControls> dfdu;
  std::array<double, kMaxControls*(kMaxNY + 1)> dudz;
  control_in_mode(y, mode, mult, control.data());
  dynamics(t, y, control.data(), mult, f);
  kModules.dynamics_jacobian(t, y, control.data(), mult, dfdz.data(), dfdu.data());
  {
    std::array<double, kMaxControls * kMaxNY> dcontrol_dy;
    kModules.direction_jacobian(y, dcontrol_dy.data());
    for (int k = 0; k < nc; ++k) {
      for (int j = 0; j < n; ++j) dudz[k * nz + j] = dcontrol_dy[k * n + j];
      dudz[k * nz + n] = 0;  // the direction law does not depend on lambda0
    }
  }
  const int u = kProblem.throttle_index;
  if (u >= 0) {
    for (int j = 0; j < nz; ++j) dudz[u * nz + j] = 0;
    if (mode == kInterior) {
      double s0 = 0, s1 = 0;
      std::array<double, kMaxNY + 1> d0{}, d1{};
      slopes(y, mult, s0, s1);
      slopes_jacobian(y, mult, d0.data(), d1.data());
      const double q = 1 / ((s0 - s1) * (s0 - s1));
      for (int j = 0; j < nz; ++j) dudz[u * nz + j] = (s0 * d1[j] - s1 * d0[j]) * q;
    }
  }
  for (int i = 0; i < n; ++i) {
    std::copy(dfdz.begin() + i * nz, dfdz.begin() + (i + 1) * nz, A + i * nz);
    for (int k = 0; k < nc; ++k) {
      const double b = dfdu[i * nc + k];
      if (b == 0) continue;
      for (int j = 0; j < nz; ++j) A[i * nz + j] += b * dudz[k * nz + j];
    }
  }
}

}  // namespace

void Propagator::tangent_step(double t, const double* y, double h, Mode mode, const Multipliers& mult,
                              Tangents& tangents, double* y_new) {
  const int n = ny(), nz = n + 1, k = tangents.k, size = n + n * k;
  if (!tangent_stepper_ || tangent_stepper_->size() != size) tangent_stepper_ = std::make_unique<Dop853>(size, n);
  const double* lambda0_row = tangents.Y + n * k;
  tangent_work_.resize(static_cast<std::size_t>(4 * size + n * nz));
  double *w = tangent_work_.data(), *f0 = w + size, *w_new = f0 + size, *f_new = w_new + size, *A = f_new + size;
  // w = (y, Y's first ny rows); w' = (f, A (Y; lambda0 row)).
  auto rhs = [&](double tt, const double* state, double* slope) {
    variational_matrix(tt, state, mode, mult, A, slope);
    const double* Y = state + n;
    double* dY = slope + n;
    std::fill(dY, dY + n * k, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < nz; ++j) {
        const double a = A[i * nz + j];
        if (a == 0) continue;
        const double* from = j < n ? Y + j * k : lambda0_row;
        for (int c = 0; c < k; ++c) dY[i * k + c] += a * from[c];
      }
  };
  std::copy(y, y + n, w);
  std::copy(tangents.Y, tangents.Y + n * k, w + n);
  rhs(t, w, f0);
  tangent_stepper_->step(rhs, t, w, f0, h, w_new, f_new, settings_.atol, settings_.rtol);
  std::copy(w_new, w_new + n, y_new);
  std::copy(w_new + n, w_new + size, tangents.Y);
}

// At a switch the state's slope jumps from f- to f+, and the switching time moves with the
// start: dt_s = -(grad g . dz) / (grad g . f-). The tangents after it are
// dz+ = dz- + (f+ - f-) (grad g . dz-) / (grad g . f-) (g the stay function that crossed 0).
void Propagator::switch_jump(double t, const double* y, Mode from, int crossed, Mode to, const Multipliers& mult,
                             Tangents& tangents) {
  if (kProblem.throttle_index < 0) return;
  const int n = ny(), k = tangents.k;
  std::array<double, kMaxNY> f_before{}, f_after{};
  std::array<double, kMaxControls> control{};
  control_in_mode(y, from, mult, control.data());
  dynamics(t, y, control.data(), mult, f_before.data());
  control_in_mode(y, to, mult, control.data());
  dynamics(t, y, control.data(), mult, f_after.data());
  std::array<double, kMaxNY + 1> d0{}, d1{}, grad{};
  slopes_jacobian(y, mult, d0.data(), d1.data());
  // The stay functions (controls.hpp): off s0, full -s1, interior (-s0, s1).
  for (int j = 0; j <= n; ++j) {
    if (from == kOff) grad[j] = d0[j];
    if (from == kFull) grad[j] = -d1[j];
    if (from == kInterior) grad[j] = crossed == 0 ? -d0[j] : d1[j];
  }
  double rate = 0;
  for (int j = 0; j < n; ++j) rate += grad[j] * f_before[j];
  if (rate == 0) throw numerical_error("a switch is tangent to its switching surface (grad g . f = 0)");
  for (int c = 0; c < k; ++c) {
    double g_dot_dz = 0;
    for (int j = 0; j <= n; ++j) g_dot_dz += grad[j] * tangents.Y[j * k + c];
    const double dt = g_dot_dz / rate;
    for (int i = 0; i < n; ++i) tangents.Y[i * k + c] += (f_after[i] - f_before[i]) * dt;
  }
}

// The switch of stay function `crossed` on the frozen-mode step from (t, y), which changes
// sign from ga (at 0) to gb (at b) over the step's length: Illinois regula falsi in the length,
// to round-off. Returns the bracket's far end (past the switch).
template <class Rhs>
double Propagator::locate_switch(Rhs& rhs, double t, const double* y, Mode mode, const Multipliers& mult, int crossed,
                                 double ga, double gb, double b) {
  std::array<double, kMaxNY> f0{}, ynew{}, fnew{};
  std::array<double, 2> g{};
  double a = 0;
  int side = 0;
  for (int it = 0; it < 100 && b - a > 4e-16 * (1 + std::fabs(t)); ++it) {
    double hs = (a * gb - b * ga) / (gb - ga);
    if (!(hs > a && hs < b)) hs = 0.5 * (a + b);
    rhs(t, y, f0.data());
    stepper_->step(rhs, t, y, f0.data(), hs, ynew.data(), fnew.data(), settings_.atol, settings_.rtol);
    stay_functions(ynew.data(), mode, mult, g.data());
    const double gs = g[crossed];
    if (gs == 0) return hs;
    if ((gs > 0) == (ga > 0)) {
      a = hs;
      ga = gs;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = hs;
      gb = gs;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return b;
}

// A mode that ends and resumes inside one step (a short arc whose switches the step's ends do
// not show; missing it makes the shooting function jump where the arc appears): the stay
// functions on the step's cubic Hermite interpolant at kDipPoints - 1 interior points, and where
// one is negative, the real sub-step there to confirm it. Returns the stay function that
// changes sign (-1: none), with b and g_at_b the sub-step's length and the stay functions at
// its end.
constexpr int kDipPoints = 12;
int Propagator::dip(double t, const double* y, const double* f0, double h, const double* y1, const double* f1,
                    Mode mode, const Multipliers& mult, double& b, std::array<double, 2>& g_at_b) {
  std::array<double, kMaxNY> yi{}, fi{};
  std::array<double, 2> g{};
  for (int j = 1; j < kDipPoints; ++j) {
    const double th = static_cast<double>(j) / kDipPoints, th2 = th * th, th3 = th2 * th;
    const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th, h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
    for (int i = 0, n = ny(); i < n; ++i) yi[i] = h00 * y[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
    const int ng = stay_functions(yi.data(), mode, mult, g.data());
    for (int k = 0; k < ng; ++k) {
      if (g[k] >= 0) continue;
      auto rhs = [&](double tt, const double* yy, double* dy) {
        std::array<double, kMaxControls> control{};
        control_in_mode(yy, mode, mult, control.data());
        dynamics(tt, yy, control.data(), mult, dy);
      };
      stepper_->step(rhs, t, y, f0, th * h, yi.data(), fi.data(), settings_.atol, settings_.rtol);
      stay_functions(yi.data(), mode, mult, g.data());
      if (g[k] < 0) {
        b = th * h;
        g_at_b = g;
        return k;
      }
    }
  }
  return -1;
}

Mode Propagator::next_mode(Mode mode, int crossed, const Multipliers& mult) {
  const bool bang = mult.eps == 0;
  if (mode == kOff) return bang ? kFull : kInterior;
  if (mode == kFull) return bang ? kOff : kInterior;
  return crossed == 0 ? kOff : kFull;
}

void Propagator::record(double t, const double* y, Mode mode, const Multipliers& mult) {
  if (!samples) return;
  Sample s;
  s.arc = arc_;
  s.t = t;
  std::copy(y, y + ny(), s.y.begin());
  control_in_mode(y, mode, mult, s.control.data());
  s.H = hamiltonian(t, y, s.control.data(), mult);
  s.S = switching_value(y, mult);
  samples->push_back(s);
}

// ---- The RESIDUAL module's calls on double and on Dual ----------------------------------------

namespace {

inline double value_of(double a) {
  return a;
}
inline double value_of(const Dual& a) {
  return a.v;
}

// An arc under multiple shooting (Propagator::ArcNodes): at each node it reaches (its start when
// it is not the first arc, then every 1/segments of it) y's values are recorded, or replaced by
// the node's with their difference as the defect; between nodes, `segment(from, to, y, inside)`
// propagates (inside: from a node inside the arc).
template <class T, class Segment>
void propagate_by_nodes(Propagator::ArcNodes& nodes, const T& t0, const T& t1, T* y, const T* values, T* defects,
                        Segment&& segment) {
  const int n = ny();
  const auto node = [&](const T& t) {
    const int k = nodes.used++;
    if (nodes.reached) {
      for (int i = 0; i < n; ++i) nodes.reached->push_back(value_of(y[i]));
      nodes.times.push_back(value_of(t));
      return;
    }
    for (int i = 0; i < n; ++i) {
      defects[k * n + i] = y[i] - values[k * n + i];
      y[i] = values[k * n + i];
    }
  };
  if (nodes.arcs++ > 0) node(t0);
  const int segments = std::max(1, nodes.segments);
  T from = t0;
  for (int k = 1; k <= segments; ++k) {
    const T to = k == segments ? t1 : t0 + (t1 - t0) * (static_cast<double>(k) / segments);
    segment(from, to, y, k > 1);
    if (k < segments) node(to);
    from = to;
  }
}

}  // namespace

namespace {

// The indices in y of the position and velocity triples and of their costates (-1: the problem
// has no such triple by the states' names rx ... vz): what a rotation of the end turns.
inline const std::array<std::array<int, 3>, 4>& rotated_triples() {
  static const std::array<std::array<int, 3>, 4> triples = [] {
    std::array<std::array<int, 3>, 4> out{};
    const char* names[2][3] = {{"rx", "ry", "rz"}, {"vx", "vy", "vz"}};
    for (int v = 0; v < 2; ++v)
      for (int c = 0; c < 3; ++c) {
        int at = -1;
        for (int i = 0; i < kProblem.num_states; ++i)
          if (std::string(kProblem.state_names[i]) == names[v][c]) at = i;
        out[v][c] = at;
        out[2 + v][c] = at < 0 ? -1 : kProblem.num_states + at;
      }
    return out;
  }();
  return triples;
}

// The rotation of the end (Propagator::end_rotation) applied to y, on double or on Dual (a problem
// without the triples is left as it is: the search turns only where end_rotation_possible).
template <class T>
void rotate_end(const std::array<double, 9>& R, T* y) {
  for (const auto& triple : rotated_triples()) {
    if (triple[0] < 0 || triple[1] < 0 || triple[2] < 0) continue;
    const T a = y[triple[0]], b = y[triple[1]], c = y[triple[2]];
    for (int i = 0; i < 3; ++i) y[triple[i]] = R[3 * i] * a + R[3 * i + 1] * b + R[3 * i + 2] * c;
  }
}

// Whether the end of a propagation can be rotated: the problem has position and velocity states
// named rx ... vz.
inline bool end_rotation_possible() {
  for (const auto& triple : rotated_triples())
    for (const int i : triple)
      if (i < 0) return false;
  return true;
}

}  // namespace

void propagate(Propagator& prop, double t0, double t1, double* y, const Multipliers& mult) {
  if (!prop.nodes) {
    prop.propagate(t0, t1, y, mult);
    if (prop.end_rotation) rotate_end(*prop.end_rotation, y);
    return;
  }
  propagate_by_nodes(*prop.nodes, t0, t1, y, prop.nodes->values, prop.nodes->defects,
                     [&](double from, double to, double* z, bool inside) {
                       prop.continues_arc = inside;
                       prop.propagate(from, to, z, mult);
                     });
}

namespace {

// f at (t, y) under the optimal control there.
void optimal_rhs(double t, const double* y, const Multipliers& mult, double* f) {
  std::array<double, kMaxControls> control{};
  control_in_mode(y, mode_at(y, mult), mult, control.data());
  dynamics(t, y, control.data(), mult, f);
}

// y(t1) from y(t0) with its derivatives: d y(t1) = Phi (d y(t0) - f(t0) d t0) + f(t1) d t1, where
// Phi carries z = (y, lambda0). Only the tangent directions that are not zero are propagated; when
// there are more of them than z has components, Phi itself is, and multiplied after.
void propagate_dual(Propagator& prop, const Dual& t0, const Dual& t1, Dual* y, const DualMultipliers& m) {
  const int n = ny(), nz = n + 1, nv = ad::width();
  const Multipliers mult{m.lambda0.v, m.eps, prop.fuel_weight};
  std::array<double, kMaxNY> yv{}, f{};
  for (int i = 0; i < n; ++i) yv[i] = y[i].v;
  optimal_rhs(t0.v, yv.data(), mult, f.data());
  std::vector<double> start(static_cast<std::size_t>(nz * nv));  // dz(t0), nz x nv
  for (int j = 0; j < nv; ++j) {
    const double dt0 = ad::derivative(t0, j);
    for (int i = 0; i < n; ++i) start[i * nv + j] = ad::derivative(y[i], j) - f[i] * dt0;
    start[n * nv + j] = ad::derivative(m.lambda0, j);
  }
  std::vector<int> columns;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nz; ++i)
      if (start[i * nv + j] != 0) {
        columns.push_back(j);
        break;
      }
  const bool whole = static_cast<int>(columns.size()) > nz;
  const int k = whole ? nz : static_cast<int>(columns.size());
  std::vector<double> Y(static_cast<std::size_t>(nz * k), 0.0);
  for (int i = 0; i < nz; ++i)
    for (int c = 0; c < k; ++c) Y[i * k + c] = whole ? (i == c ? 1.0 : 0.0) : start[i * nv + columns[c]];
  Propagator::Tangents tangents{Y.data(), k};
  prop.propagate(t0.v, t1.v, yv.data(), mult, k > 0 ? &tangents : nullptr);
  optimal_rhs(t1.v, yv.data(), mult, f.data());
  std::vector<double> dt1(static_cast<std::size_t>(nv)), d(dt1.size());
  for (int j = 0; j < nv; ++j) dt1[j] = ad::derivative(t1, j);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < nv; ++j) d[j] = f[i] * dt1[j];
    if (whole) {
      for (int c = 0; c < nz; ++c)
        for (int j = 0; j < nv; ++j) d[j] += Y[i * k + c] * start[c * nv + j];
    } else {
      for (int c = 0; c < k; ++c) d[columns[c]] += Y[i * k + c];
    }
    y[i] = ad::with_derivatives(yv[i], d.data());
  }
}

}  // namespace

// y(t1) from y(t0) with its derivatives (propagate_dual), from node to node under multiple shooting.
void propagate(Propagator& prop, const Dual& t0, const Dual& t1, Dual* y, const DualMultipliers& m) {
  if (!prop.nodes) {
    propagate_dual(prop, t0, t1, y, m);
    if (prop.end_rotation) rotate_end(*prop.end_rotation, y);
    return;
  }
  propagate_by_nodes(*prop.nodes, t0, t1, y, prop.nodes->dual_values, prop.nodes->dual_defects,
                     [&](const Dual& from, const Dual& to, Dual* z, bool inside) {
                       prop.continues_arc = inside;
                       propagate_dual(prop, from, to, z, m);
                     });
}

double optimal_hamiltonian(double t, const double* y, const Multipliers& mult) {
  std::array<double, kMaxControls> control{};
  control_in_mode(y, mode_at(y, mult), mult, control.data());
  return hamiltonian(t, y, control.data(), mult);
}

// H at the optimal control, differentiated by the envelope theorem: the control minimizes H, so
// dH = dH/dx dx + dH/dlambda dlambda + dH/dlambda0 dlambda0 at fixed control, where
// dH/dx = -lambda', dH/dlambda = x' (the costate and state equations) and dH/dlambda0 = L (H is
// linear in lambda0). The dynamics are autonomous (the JACOBIAN module is generated only then).
Dual optimal_hamiltonian(const Dual& t, const Dual* y, const DualMultipliers& m) {
  const int n = ny(), ns = kProblem.num_states, nv = ad::width();
  const Multipliers mult{m.lambda0.v, m.eps};
  std::array<double, kMaxNY> yv{}, f{};
  for (int i = 0; i < n; ++i) yv[i] = y[i].v;
  std::array<double, kMaxControls> control{};
  control_in_mode(yv.data(), mode_at(yv.data(), mult), mult, control.data());
  dynamics(t.v, yv.data(), control.data(), mult, f.data());
  const double running_cost = hamiltonian(t.v, yv.data(), control.data(), Multipliers{1.0, m.eps}) -
                              hamiltonian(t.v, yv.data(), control.data(), Multipliers{0.0, m.eps});
  std::vector<double> d(static_cast<std::size_t>(nv));
  for (int j = 0; j < nv; ++j) {
    d[j] = running_cost * ad::derivative(m.lambda0, j);
    for (int i = 0; i < ns; ++i) d[j] += -f[ns + i] * ad::derivative(y[i], j) + f[i] * ad::derivative(y[ns + i], j);
  }
  return ad::with_derivatives(hamiltonian(t.v, yv.data(), control.data(), mult), d.data());
}

}  // namespace helios_rt

// The sail normal's geometry and the verifier's own minimizer of H over the hemisphere.
#include "sail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace helios::verify::detail {
namespace {

constexpr int kSailCone = 12;   // cone-angle rows of the grid over the admissible hemisphere
constexpr int kSailClock = 24;  // clock-angle columns of that grid

// The admissible hemisphere at a point in cone angle theta in [0, pi/2] and clock angle phi:
// n = cos(theta) r_hat + sin(theta) (cos(phi) e1 + sin(phi) e2).
struct SailFrame {
  Vec3 r, e1, e2;
  Vec3 at(double theta, double phi) const {
    Vec3 n{};
    for (std::size_t k = 0; k < 3; ++k)
      n[k] = std::cos(theta) * r[k] + std::sin(theta) * (std::cos(phi) * e1[k] + std::sin(phi) * e2[k]);
    return n;
  }
};

SailFrame sail_frame(const Context& ctx, const Point& p) {
  SailFrame f;
  f.r = r_hat(ctx, p);
  const std::size_t k = std::fabs(f.r[0]) < 0.6 ? 0 : (std::fabs(f.r[1]) < 0.6 ? 1 : 2);
  Vec3 t{};
  t[k] = 1;
  const double c = dot(t, f.r);
  for (std::size_t j = 0; j < 3; ++j) f.e1[j] = t[j] - c * f.r[j];
  const double n = std::sqrt(dot(f.e1, f.e1));
  for (auto& x : f.e1) x /= n;
  f.e2 = {f.r[1] * f.e1[2] - f.r[2] * f.e1[1], f.r[2] * f.e1[0] - f.r[0] * f.e1[2],
          f.r[0] * f.e1[1] - f.r[1] * f.e1[0]};
  return f;
}

// Comparing values of H finds n* only to ~sqrt(machine epsilon); Newton on the tangential part
// of dH/dn (zero at an interior minimum) brings it to full precision.
Vec3 polish_sail(const Context& ctx, const Point& p, Vec3 n) {
  const Vec3 rh = r_hat(ctx, p);
  if (dot(n, rh) < 1e-3) return n;  // on (or next to) the rim: no stationarity to solve
  auto unit = [](Vec3 v) {
    const double l = std::sqrt(dot(v, v));
    for (auto& x : v) x /= l;
    return v;
  };
  const double h0 = ctx.hamiltonian_compiled(set_sail(ctx, p, n));
  Vec3 best = n;
  for (int it = 0; it < 6; ++it) {
    // Tangent basis at n, and F(s, t) = tangential gradient at unit(n + s b1 + t b2) on (b1, b2).
    Vec3 b1{}, b2{};
    const Vec3 seed = std::fabs(n[0]) < 0.6 ? Vec3{1, 0, 0} : (std::fabs(n[1]) < 0.6 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const double c = dot(seed, n);
    for (std::size_t k = 0; k < 3; ++k) b1[k] = seed[k] - c * n[k];
    b1 = unit(b1);
    b2 = {n[1] * b1[2] - n[2] * b1[1], n[2] * b1[0] - n[0] * b1[2], n[0] * b1[1] - n[1] * b1[0]};
    auto F = [&](double s, double t) {
      Vec3 m{};
      for (std::size_t k = 0; k < 3; ++k) m[k] = n[k] + s * b1[k] + t * b2[k];
      m = unit(m);
      const Point q = set_sail(ctx, p, m);
      const Vec3 g{ctx.dH_dn_compiled[0](q), ctx.dH_dn_compiled[1](q), ctx.dH_dn_compiled[2](q)};
      const double gm = dot(g, m);
      return std::array<double, 2>{dot(g, b1) - gm * dot(m, b1), dot(g, b2) - gm * dot(m, b2)};
    };
    const auto F0 = F(0, 0);
    if (std::fabs(F0[0]) + std::fabs(F0[1]) < 1e-15) break;
    const double e = 1e-7;
    const auto Fs = F(e, 0), Ft = F(0, e);
    const double j11 = (Fs[0] - F0[0]) / e, j21 = (Fs[1] - F0[1]) / e, j12 = (Ft[0] - F0[0]) / e,
                 j22 = (Ft[1] - F0[1]) / e, det = j11 * j22 - j12 * j21;
    if (!(std::fabs(det) > 0) || !std::isfinite(det)) break;
    const double ds = -(j22 * F0[0] - j12 * F0[1]) / det, dt = -(-j21 * F0[0] + j11 * F0[1]) / det;
    if (std::fabs(ds) + std::fabs(dt) > 0.1) break;
    Vec3 m{};
    for (std::size_t k = 0; k < 3; ++k) m[k] = n[k] + ds * b1[k] + dt * b2[k];
    n = unit(m);
  }
  // Keep the polished point only if it is admissible and no worse than the search's.
  const double h1 = ctx.hamiltonian_compiled(set_sail(ctx, p, n));
  if (dot(n, rh) >= 0 && std::isfinite(h1) && h1 <= h0 + 1e-12 * (1 + std::fabs(h0))) best = n;
  return best;
}

}  // namespace

Vec3 r_hat(const Context& ctx, const Point& p) {
  Vec3 r{};
  for (std::size_t k = 0; k < 3; ++k) r[k] = p[static_cast<std::size_t>(ctx.slot(ctx.states[ctx.positions[k]]))];
  const double n = std::sqrt(dot(r, r));
  for (auto& x : r) x /= n;
  return r;
}

Point set_sail(const Context& ctx, Point p, const Vec3& n) {
  for (std::size_t k = 0; k < 3; ++k) p[static_cast<std::size_t>(ctx.slot(ctx.sails[k]))] = n[k];
  return p;
}

Vec3 random_admissible(const Context& ctx, const Point& p, std::mt19937_64& rng) {
  const Vec3 rh = r_hat(ctx, p);
  const auto u = random_unit(rng, 3);
  Vec3 n{u[0], u[1], u[2]};
  const double c = dot(n, rh);
  if (c < 0)
    for (std::size_t k = 0; k < 3; ++k) n[k] -= 2 * c * rh[k];
  return n;
}

Vec3 optimal_sail(const Context& ctx, const Point& p) {
  const SailFrame f = sail_frame(ctx, p);
  const double half_pi = 1.5707963267948966, two_pi = 6.283185307179586;
  auto h = [&](double theta, double phi) {
    theta = std::clamp(theta, 0.0, half_pi);
    return ctx.hamiltonian_compiled(set_sail(ctx, p, f.at(theta, phi)));
  };
  // Grid rows: uniform in the cone angle, plus rows closing in on the rim geometrically (a
  // minimum next to the rim sits in a thin sliver a uniform grid can miss).
  std::vector<double> rows;
  for (int i = 1; i <= kSailCone; ++i) rows.push_back(half_pi * i / kSailCone);
  for (int k = 5; k <= 17; k += 3) rows.push_back(half_pi * (1 - std::ldexp(1.0, -k)));
  struct Start {
    double h, t, p;
  };
  std::vector<Start> grid{{h(0, 0), 0, 0}};
  for (double t : rows)
    for (int j = 0; j < kSailClock; ++j) grid.push_back({h(t, two_pi * j / kSailClock), t, two_pi * j / kSailClock});
  std::sort(grid.begin(), grid.end(), [](const Start& a, const Start& b) { return a.h < b.h; });
  Vec3 best{};
  double best_h = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < std::min<std::size_t>(3, grid.size()); ++s) {
    double bt = grid[s].t, bp = grid[s].p, bh = grid[s].h;
    double step_t = std::max(1e-4, std::min(half_pi / kSailCone, (half_pi - bt) / 2)), step_p = two_pi / kSailClock;
    while (step_t > 1e-9) {
      bool moved = false;
      for (const auto& [dt, dp] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}) {
        const double t = std::clamp(bt + dt * step_t, 0.0, half_pi), ph = bp + dp * step_p, v = h(t, ph);
        if (v < bh) {
          bh = v;
          bt = t;
          bp = ph;
          moved = true;
        }
      }
      if (!moved) {
        step_t /= 2;
        step_p /= 2;
      }
    }
    const Vec3 n = polish_sail(ctx, p, f.at(bt, bp));
    const double hn = ctx.hamiltonian_compiled(set_sail(ctx, p, n));
    if (hn < best_h) {
      best_h = hn;
      best = n;
    }
  }
  return best;
}

double sail_tangential(const Context& ctx, const Point& p, const Vec3& n) {
  const Point q = set_sail(ctx, p, n);
  const Vec3 g{ctx.dH_dn_compiled[0](q), ctx.dH_dn_compiled[1](q), ctx.dH_dn_compiled[2](q)};
  const double gn = dot(g, n);
  Vec3 t{};
  for (std::size_t k = 0; k < 3; ++k) t[k] = g[k] - gn * n[k];
  return std::isfinite(gn) ? std::sqrt(dot(t, t)) / (1 + std::sqrt(dot(g, g))) : 2.0;
}

std::string vec_text(const Vec3& v) {
  return "(" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + ")";
}

double cone_of(const Vec3& n, const Vec3& r) {
  const Vec3 x{n[1] * r[2] - n[2] * r[1], n[2] * r[0] - n[0] * r[2], n[0] * r[1] - n[1] * r[0]};
  return std::atan2(std::sqrt(dot(x, x)), dot(n, r));
}

}  // namespace helios::verify::detail

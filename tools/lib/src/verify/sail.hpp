#pragma once
// The geometry of the sail normal n (internal to tools/lib/src/verify): admissible means |n| = 1
// and n.r_hat >= 0; the verifier's own minimizer of H over that hemisphere, found numerically.
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "check.hpp"
#include "context.hpp"

namespace helios::verify::detail {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The unit vector along the position states at p.
Vec3 r_hat(const Context& ctx, const Point& p);
// p with the sail controls set to n.
Point set_sail(const Context& ctx, Point p, const Vec3& n);
// A random admissible normal at p.
Vec3 random_admissible(const Context& ctx, const Point& p, std::mt19937_64& rng);
// The verifier's own minimizer of H over the admissible hemisphere at p, found numerically (a grid
// in cone and clock angle, then a shrinking pattern search): it knows nothing of a closed form.
Vec3 optimal_sail(const Context& ctx, const Point& p);
// Relative norm of the part of dH/dn tangent to the unit sphere at n (0 at an interior optimum).
double sail_tangential(const Context& ctx, const Point& p, const Vec3& n);
// The angle between n and r.
double cone_of(const Vec3& n, const Vec3& r);
// "(x, y, z)" for feedback.
std::string vec_text(const Vec3& v);

}  // namespace helios::verify::detail

#pragma once
// Two-body (Kepler) utilities: Kepler's equation, classical elements <-> Cartesian state and
// universal-variable propagation. Standard library only: also compiled into the shooting runtime
// (templates/runtime/runtime.cpp).
#include "helios/astro/constants.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace helios::astro {

// Classical elements. a in the caller's length unit; angles in radians.
struct Elements {
  double a;
  double e;
  double i;
  double raan;
  double argp;
  double mean_anomaly;
};

namespace kepler_detail {

inline constexpr double EPS = 2.220446049250313080847e-16;  // DBL_EPSILON

inline double wrap_two_pi(double x) {
  double w = std::fmod(x, TWO_PI);
  if (w < 0.0) w += TWO_PI;
  return w >= TWO_PI ? 0.0 : w;
}

inline double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline std::array<double, 3> cross3(const double* a, const double* b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Universal functions U0..U3 of Goodyear/Battin for chi and alpha = 1/a:
// U0 = 1 - z*c2, U1 = chi*(1 - z*c3), U2 = chi^2*c2, U3 = chi^3*c3 with z = alpha*chi^2 and
// c2, c3 the Stumpff functions. Series near z = 0 avoid the cancellation of the closed forms.
struct Universal {
  double u0, u1, u2, u3;
};

inline Universal universal_functions(double chi, double alpha) {
  const double z = alpha * chi * chi;
  const double chi2 = chi * chi;
  Universal u{};
  if (std::fabs(z) < 4.0) {
    // c2 = sum (-z)^k/(2k+2)!, c3 = sum (-z)^k/(2k+3)!; |z| < 4 converges in < 20 terms.
    double c2 = 0.0, c3 = 0.0;
    double t2 = 0.5, t3 = 1.0 / 6.0;
    for (int k = 0; k < 40; ++k) {
      c2 += t2;
      c3 += t3;
      t2 *= -z / ((2.0 * k + 3.0) * (2.0 * k + 4.0));
      t3 *= -z / ((2.0 * k + 4.0) * (2.0 * k + 5.0));
      if (std::fabs(t2) <= 1e-18 * std::fabs(c2) && std::fabs(t3) <= 1e-18 * std::fabs(c3)) break;
    }
    u.u0 = 1.0 - z * c2;
    u.u1 = chi * (1.0 - z * c3);
    u.u2 = chi2 * c2;
    u.u3 = chi2 * chi * c3;
  } else if (z > 0.0) {
    const double x = std::sqrt(z);
    const double s = std::sin(x);
    const double sh = std::sin(0.5 * x);
    u.u0 = std::cos(x);
    u.u1 = chi * s / x;
    u.u2 = chi2 * 2.0 * sh * sh / z;
    u.u3 = chi2 * chi * (x - s) / (z * x);
  } else {
    const double x = std::sqrt(-z);
    const double s = std::sinh(x);
    const double sh = std::sinh(0.5 * x);
    u.u0 = std::cosh(x);
    u.u1 = chi * s / x;
    u.u2 = chi2 * 2.0 * sh * sh / (-z);
    u.u3 = chi2 * chi * (s - x) / (-z * x);
  }
  return u;
}

// Hyperbolic anomaly H with e*sinh(H) - H = M for e >= 1, safeguarded Newton.
inline double hyperbolic_anomaly(double M, double e) {
  if (M == 0.0) return 0.0;
  const double m = std::fabs(M);
  // e sinh H - H lies between (e-1) sinh H (also >= H^3/6 when e >= 1) and e sinh H for H >= 0.
  double lo = std::asinh(m / e);
  double hi = std::cbrt(6.0 * m);
  if (e > 1.0) hi = std::min(hi, std::asinh(m / (e - 1.0)));
  hi = std::max(hi, lo);
  double H = hi;  // g is convex for H > 0: Newton from above converges monotonically
  for (int it = 0; it < 200; ++it) {
    const double g = e * std::sinh(H) - H - m;
    if (g == 0.0) break;
    if (g < 0.0)
      lo = H;
    else
      hi = H;
    const double d = -g / (e * std::cosh(H) - 1.0);
    if (std::fabs(d) <= 2.0 * EPS * std::fabs(H)) {
      H += d;
      break;
    }
    double next = H + d;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 2.0 * EPS * hi) {
      H = next;
      break;
    }
    H = next;
  }
  return M < 0.0 ? -H : H;
}

// Root chi of the universal Kepler equation sqrt(mu)*dt = r0*U1 + sigma0*U2 + U3 (sigma0 = r0.v0 /
// sqrt(mu), alpha = 1/a), with target = sqrt(mu)*dt != 0.
inline double solve_universal_kepler(double r0, double sigma0, double alpha, double target, double dt, double mu) {
  const double smu = std::sqrt(mu);
  // F(chi) = sqrt(mu)*t(chi) - sqrt(mu)*dt is strictly increasing (F' = r > 0).
  auto eval = [&](double chi, double& F, double& Fp) {
    const auto u = universal_functions(chi, alpha);
    F = r0 * u.u1 + sigma0 * u.u2 + u.u3 - target;
    Fp = r0 * u.u0 + sigma0 * u.u1 + u.u2;
  };

  double guess = 0.0;
  if (alpha > 0.0) {
    guess = smu * dt * alpha;  // exact for circular orbits
  } else {
    const double sgn = dt > 0.0 ? 1.0 : -1.0;
    if (alpha < 0.0) {
      const double a = 1.0 / alpha;
      const double num = -2.0 * mu * alpha * dt;
      const double den = sigma0 * smu + sgn * std::sqrt(-mu * a) * (1.0 - r0 * alpha);
      const double arg = num / den;
      if (std::isfinite(arg) && arg > 0.0) guess = sgn * std::sqrt(-a) * std::log(arg);
    }
    if (!(guess * sgn > 0.0) || !std::isfinite(guess)) guess = target / r0;
  }

  // Bracket the root: F(0) = -target, then expand from the guess until F changes sign.
  double lo, hi, F, Fp;
  if (dt > 0.0) {
    lo = 0.0;
    hi = guess > 0.0 ? guess : target / r0;
    for (int k = 0; k < 200; ++k) {
      eval(hi, F, Fp);
      if (!std::isfinite(F) || F >= 0.0) break;
      lo = hi;
      hi *= 2.0;
    }
  } else {
    hi = 0.0;
    lo = guess < 0.0 ? guess : target / r0;
    for (int k = 0; k < 200; ++k) {
      eval(lo, F, Fp);
      if (!std::isfinite(F) || F <= 0.0) break;
      hi = lo;
      lo *= 2.0;
    }
  }

  // Newton safeguarded by bisection inside [lo, hi].
  double chi = (guess > lo && guess < hi) ? guess : 0.5 * (lo + hi);
  for (int it = 0; it < 300; ++it) {
    eval(chi, F, Fp);
    if (!std::isfinite(F) || !std::isfinite(Fp)) {
      // Overflow only happens far beyond the root.
      if (chi > 0.0)
        hi = chi;
      else
        lo = chi;
      chi = 0.5 * (lo + hi);
      continue;
    }
    if (F == 0.0) break;
    if (F < 0.0)
      lo = chi;
    else
      hi = chi;
    const double d = -F / Fp;
    if (std::fabs(d) <= 2.0 * EPS * std::fabs(chi)) {
      chi += d;
      break;
    }
    double next = chi + d;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 2.0 * EPS * std::max(std::fabs(lo), std::fabs(hi))) {
      chi = next;
      break;
    }
    chi = next;
  }

  return chi;
}

}  // namespace kepler_detail

// Eccentric anomaly E with E - e*sin(E) = M, for 0 <= e < 1 and any M. The revolution count of M
// is kept (E and M lie in the same 2*pi interval), so the residual is at rounding level.
inline double eccentric_anomaly(double M, double e) {
  if (!(e >= 0.0 && e < 1.0)) throw std::invalid_argument("eccentric_anomaly: need 0 <= e < 1");
  if (!std::isfinite(M)) throw std::invalid_argument("eccentric_anomaly: M is not finite");
  const double turns = std::round(M / TWO_PI);
  const double m = M - turns * TWO_PI;  // in [-pi, pi]
  // f(E) = E - e sin E - m is increasing with f(-pi) <= 0 <= f(pi): a bracket for safeguarding.
  double lo = -PI, hi = PI;
  double E = m + 0.85 * e * (m >= 0.0 ? 1.0 : -1.0);  // Danby's starter
  E = std::clamp(E, lo, hi);
  for (int it = 0; it < 100; ++it) {
    const double f = E - e * std::sin(E) - m;
    if (f == 0.0) break;
    if (f < 0.0)
      lo = E;
    else
      hi = E;
    const double fp = 1.0 - e * std::cos(E);
    const double fpp = e * std::sin(E);
    // Halley step: cubic convergence, still well defined where fp is small (e -> 1, E -> 0).
    const double d = -f / (fp - 0.5 * f * fpp / fp);
    double En = E + d;
    if (std::fabs(d) <= 2.0 * kepler_detail::EPS * std::max(1.0, std::fabs(E))) {
      E = En;
      break;
    }
    if (!(En > lo && En < hi)) En = 0.5 * (lo + hi);
    if (hi - lo <= 2.0 * kepler_detail::EPS * std::max(1.0, std::fabs(E))) {
      E = En;
      break;
    }
    E = En;
  }
  return E + turns * TWO_PI;
}

namespace kepler_detail {

// The state at eccentric anomaly E, on any scalar S with the arithmetic, sin, cos and sqrt: double
// for elements_to_state, Jet for its time derivative.
template <class S>
std::array<S, 6> state_at_anomaly(const S& a, const S& e, const S& i, const S& raan, const S& argp, const S& E,
                                  double mu) {
  using std::cos, std::sin, std::sqrt;
  const S cE = cos(E), sE = sin(E);
  const S b_over_a = sqrt((1.0 - e) * (1.0 + e));
  const S one_minus_ecosE = 1.0 - e * cE;
  // Perifocal frame (P towards periapsis, Q 90 deg ahead in the direction of motion).
  const S xp = a * (cE - e);
  const S yp = a * b_over_a * sE;
  const S vscale = sqrt(mu / a) / one_minus_ecosE;
  const S vxp = -vscale * sE;
  const S vyp = vscale * b_over_a * cE;

  const S cO = cos(raan), sO = sin(raan);
  const S cw = cos(argp), sw = sin(argp);
  const S ci = cos(i), si = sin(i);
  const S P[3] = {cO * cw - sO * sw * ci, sO * cw + cO * sw * ci, sw * si};
  const S Q[3] = {-cO * sw - sO * cw * ci, -sO * sw + cO * cw * ci, cw * si};
  return {xp * P[0] + yp * Q[0],   xp * P[1] + yp * Q[1],   xp * P[2] + yp * Q[2],
          vxp * P[0] + vyp * Q[0], vxp * P[1] + vyp * Q[1], vxp * P[2] + vyp * Q[2]};
}

// A value and its derivative in one variable (forward mode), for state_at_anomaly.
struct Jet {
  double v, d;
};
inline Jet operator+(Jet a, Jet b) {
  return {a.v + b.v, a.d + b.d};
}
inline Jet operator-(Jet a, Jet b) {
  return {a.v - b.v, a.d - b.d};
}
inline Jet operator*(Jet a, Jet b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d};
}
inline Jet operator/(Jet a, Jet b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
inline Jet operator-(Jet a) {
  return {-a.v, -a.d};
}
inline Jet operator+(double a, Jet b) {
  return {a + b.v, b.d};
}
inline Jet operator-(double a, Jet b) {
  return {a - b.v, -b.d};
}
inline Jet operator/(double a, Jet b) {
  return {a / b.v, -a * b.d / (b.v * b.v)};
}
inline Jet sin(Jet a) {
  return {std::sin(a.v), std::cos(a.v) * a.d};
}
inline Jet cos(Jet a) {
  return {std::cos(a.v), -std::sin(a.v) * a.d};
}
inline Jet sqrt(Jet a) {
  const double r = std::sqrt(a.v);
  return {r, 0.5 * a.d / r};
}

inline void check_elements(const Elements& el, double mu) {
  if (!(el.a > 0.0) || !(el.e >= 0.0 && el.e < 1.0) || !(mu > 0.0)) {
    throw std::invalid_argument("elements_to_state: need a > 0, 0 <= e < 1 and mu > 0");
  }
}

}  // namespace kepler_detail

// Cartesian state [x, y, z, vx, vy, vz] from elliptic elements; mu in length^3/time^2.
inline std::array<double, 6> elements_to_state(const Elements& el, double mu) {
  kepler_detail::check_elements(el, mu);
  const double E = eccentric_anomaly(el.mean_anomaly, el.e);
  return kepler_detail::state_at_anomaly(el.a, el.e, el.i, el.raan, el.argp, E, mu);
}

// The time derivative of elements_to_state(el(t), mu) where the elements move at `rate` (per unit
// time; the JPL model's drift), exact: Kepler's equation E - e sin E = M gives
// dE/dt = (dM/dt + de/dt sin E) / (1 - e cos E), and the rest is differentiated in forward mode.
inline std::array<double, 6> elements_to_state_rate(const Elements& el, const Elements& rate, double mu) {
  kepler_detail::check_elements(el, mu);
  using kepler_detail::Jet;
  const double E = eccentric_anomaly(el.mean_anomaly, el.e);
  const double E_rate = (rate.mean_anomaly + rate.e * std::sin(E)) / (1.0 - el.e * std::cos(E));
  const auto s = kepler_detail::state_at_anomaly(Jet{el.a, rate.a}, Jet{el.e, rate.e}, Jet{el.i, rate.i},
                                                 Jet{el.raan, rate.raan}, Jet{el.argp, rate.argp}, Jet{E, E_rate}, mu);
  return {s[0].d, s[1].d, s[2].d, s[3].d, s[4].d, s[5].d};
}

// Elliptic elements from a Cartesian state. Angles: i in [0, pi], the others in [0, 2*pi).
// Equatorial orbits (sin i ~ 0) get raan = 0 and argp measured from the x axis; circular orbits
// (e ~ 0) get argp = 0 and the anomaly measured from the node (or x axis), so the returned set
// always reproduces the state.
inline Elements state_to_elements(const std::array<double, 6>& s, double mu) {
  using kepler_detail::cross3;
  using kepler_detail::dot3;
  using kepler_detail::wrap_two_pi;
  if (!(mu > 0.0)) throw std::invalid_argument("state_to_elements: need mu > 0");
  const double* r = s.data();
  const double* v = s.data() + 3;
  const double rn = std::sqrt(dot3(r, r));
  const double v2 = dot3(v, v);
  const double rv = dot3(r, v);
  const auto h = cross3(r, v);
  const double hn = std::sqrt(dot3(h.data(), h.data()));
  if (!(rn > 0.0) || !(hn > 0.0)) throw std::invalid_argument("state_to_elements: degenerate (rectilinear) state");
  const double inv_a = 2.0 / rn - v2 / mu;
  if (!(inv_a > 0.0)) throw std::invalid_argument("state_to_elements: orbit is not elliptic");

  Elements el{};
  el.a = 1.0 / inv_a;
  const double hxy = std::hypot(h[0], h[1]);
  el.i = std::atan2(hxy, h[2]);
  const double tiny = 1e-13;
  el.raan = hxy > tiny * hn ? wrap_two_pi(std::atan2(h[0], -h[1])) : 0.0;

  // In-plane basis: N along the node line, Qn = W x N 90 deg ahead in the direction of motion.
  const double W[3] = {h[0] / hn, h[1] / hn, h[2] / hn};
  const double N[3] = {std::cos(el.raan), std::sin(el.raan), 0.0};
  const auto Qn = cross3(W, N);

  const double ecoef1 = v2 / mu - 1.0 / rn;
  const double ecoef2 = rv / mu;
  const double evec[3] = {ecoef1 * r[0] - ecoef2 * v[0], ecoef1 * r[1] - ecoef2 * v[1], ecoef1 * r[2] - ecoef2 * v[2]};
  el.e = std::sqrt(dot3(evec, evec));

  const double u = std::atan2(dot3(r, Qn.data()), dot3(r, N));  // argument of latitude
  el.argp = el.e > tiny ? wrap_two_pi(std::atan2(dot3(evec, Qn.data()), dot3(evec, N))) : 0.0;
  const double nu = u - el.argp;
  const double E =
      2.0 * std::atan2(std::sqrt(1.0 - el.e) * std::sin(0.5 * nu), std::sqrt(1.0 + el.e) * std::cos(0.5 * nu));
  el.mean_anomaly = wrap_two_pi(E - el.e * std::sin(E));
  return el;
}

// Two-body propagation of [r, v] by dt with universal variables (any conic, either sign of dt).
inline std::array<double, 6> propagate(const std::array<double, 6>& state, double dt, double mu) {
  using kepler_detail::dot3;
  if (!(mu > 0.0)) throw std::invalid_argument("propagate: need mu > 0");
  if (!std::isfinite(dt)) throw std::invalid_argument("propagate: dt is not finite");
  if (dt == 0.0) return state;
  const double* r0v = state.data();
  const double* v0v = state.data() + 3;
  const double r0 = std::sqrt(dot3(r0v, r0v));
  const double v02 = dot3(v0v, v0v);
  if (!(r0 > 0.0)) throw std::invalid_argument("propagate: zero position vector");
  const double smu = std::sqrt(mu);
  const double sigma0 = dot3(r0v, v0v) / smu;
  const double alpha = 2.0 / r0 - v02 / mu;  // 1/a; <= 0 for parabolic/hyperbolic
  const double target = smu * dt;

  double chi = 0.0, r = 0.0;
  bool solved = false;
  if (alpha < 0.0) {
    // Starting well out on a hyperbola and heading in, the universal Kepler equation is a
    // difference of terms that grow like exp|H0|; the hyperbolic-anomaly form stays exact there.
    const double A = -1.0 / alpha, sA = std::sqrt(A);
    const auto h = kepler_detail::cross3(r0v, v0v);
    const double e2m1 = dot3(h.data(), h.data()) / (mu * A);  // e^2 - 1 = p/|a|
    const double e = std::sqrt(1.0 + e2m1);
    const double H0 = std::asinh(sigma0 / (sA * e));  // e sinh H0 = sigma0/sqrt|a|
    if (std::fabs(H0) > 1.0) {
      const double M1 = (sigma0 / sA - H0) + smu / (A * sA) * dt;
      const double H1 = kepler_detail::hyperbolic_anomaly(M1, e);
      chi = sA * (H1 - H0);
      const double sh = std::sinh(0.5 * H1);
      r = A * (e2m1 / (1.0 + e) * std::cosh(H1) + 2.0 * sh * sh);  // |a|(e cosh H1 - 1), no cancellation
      solved = std::isfinite(chi) && r > 0.0;
    }
  }
  if (!solved) chi = kepler_detail::solve_universal_kepler(r0, sigma0, alpha, target, dt, mu);
  const auto u = kepler_detail::universal_functions(chi, alpha);
  if (!solved) r = r0 * u.u0 + sigma0 * u.u1 + u.u2;
  // Lagrange coefficients. sqrt(mu)*g = r0*U1 + sigma0*U2 = sqrt(mu)*dt - U3: the first form avoids
  // cancellation over many elliptic revolutions, the second when coming in from far along a
  // hyperbola; take the one whose terms are smaller.
  const double f = 1.0 - u.u2 / r0;
  const double ga = r0 * u.u1, gb = sigma0 * u.u2;
  const double g =
      (std::fabs(ga) + std::fabs(gb) <= std::fabs(target) + std::fabs(u.u3)) ? (ga + gb) / smu : dt - u.u3 / smu;
  const double fdot = -smu * u.u1 / (r * r0);
  const double gdot = 1.0 - u.u2 / r;
  std::array<double, 6> out{};
  for (std::size_t k = 0; k < 3; ++k) {
    out[k] = f * r0v[k] + g * v0v[k];
    out[k + 3] = fdot * r0v[k] + gdot * v0v[k];
  }
  return out;
}

}  // namespace helios::astro

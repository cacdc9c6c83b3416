// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, dual numbers (templates/runtime/dual.hpp): the operations of
// helios_runtime.hpp's Dual, out of line so that a generated expression on Dual compiles fast.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt::ad {

namespace {

// The derivatives of the thread's Duals, width() per row, since dual_jacobian began the Jacobian.
struct Tape {
  int width = 0;
  std::vector<double> rows;
  int add() {
    rows.resize(rows.size() + static_cast<std::size_t>(width));
    return static_cast<int>(rows.size() / static_cast<std::size_t>(width)) - 1;
  }
  double* row(int id) { return rows.data() + static_cast<std::size_t>(id) * static_cast<std::size_t>(width); }
};
Tape& tape() {
  thread_local Tape t;  // each search thread its own
  return t;
}

// A new Jacobian of n variables: the tape emptied.
void begin_jacobian(int n) {
  Tape& t = tape();
  t.width = n;
  t.rows.clear();
}

}  // namespace

int width() {
  return tape().width;
}

double derivative(const Dual& a, int j) {
  return a.id < 0 ? 0.0 : tape().row(a.id)[j];
}

Dual with_derivatives(double value, const double* d) {
  Dual r(value);
  if (!d) return r;
  Tape& t = tape();
  r.id = t.add();
  std::copy(d, d + t.width, t.row(r.id));
  return r;
}

Dual chain(Dual a, double value, double slope) noexcept {
  Dual r(value);
  if (a.id < 0) return r;
  Tape& t = tape();
  r.id = t.add();
  const double* x = t.row(a.id);
  double* y = t.row(r.id);
  for (int j = 0; j < t.width; ++j) y[j] = slope * x[j];
  return r;
}
Dual chain(Dual a, Dual b, double value, double da, double db) noexcept {
  if (a.id < 0) return chain(b, value, db);
  if (b.id < 0) return chain(a, value, da);
  Dual r(value);
  Tape& t = tape();
  r.id = t.add();
  const double *x = t.row(a.id), *z = t.row(b.id);
  double* y = t.row(r.id);
  for (int j = 0; j < t.width; ++j) y[j] = da * x[j] + db * z[j];
  return r;
}
Dual operator+(Dual a) noexcept {
  return a;
}
Dual operator-(Dual a) noexcept {
  return chain(a, -a.v, -1);
}
Dual operator+(Dual a, Dual b) noexcept {
  return chain(a, b, a.v + b.v, 1, 1);
}
Dual operator-(Dual a, Dual b) noexcept {
  return chain(a, b, a.v - b.v, 1, -1);
}
Dual operator*(Dual a, Dual b) noexcept {
  return chain(a, b, a.v * b.v, b.v, a.v);
}
Dual operator/(Dual a, Dual b) noexcept {
  return chain(a, b, a.v / b.v, 1 / b.v, -a.v / (b.v * b.v));
}
Dual operator+(Dual a, double b) noexcept {
  return chain(a, a.v + b, 1);
}
Dual operator+(double a, Dual b) noexcept {
  return chain(b, a + b.v, 1);
}
Dual operator-(Dual a, double b) noexcept {
  return chain(a, a.v - b, 1);
}
Dual operator-(double a, Dual b) noexcept {
  return chain(b, a - b.v, -1);
}
Dual operator*(Dual a, double b) noexcept {
  return chain(a, a.v * b, b);
}
Dual operator*(double a, Dual b) noexcept {
  return chain(b, a * b.v, a);
}
Dual operator/(Dual a, double b) noexcept {
  return chain(a, a.v / b, 1 / b);
}
Dual operator/(double a, Dual b) noexcept {
  return chain(b, a / b.v, -a / (b.v * b.v));
}
Dual sqrt(Dual a) noexcept {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r);
}
Dual pow(Dual a, double k) noexcept {
  return chain(a, std::pow(a.v, k), k * std::pow(a.v, k - 1));
}
Dual pow(Dual a, Dual b) noexcept {
  const double p = std::pow(a.v, b.v);
  return chain(a, b, p, b.v * std::pow(a.v, b.v - 1), p * std::log(a.v));
}
Dual pow(double a, Dual b) noexcept {
  const double p = std::pow(a, b.v);
  return chain(b, p, p * std::log(a));
}
Dual exp(Dual a) noexcept {
  const double e = std::exp(a.v);
  return chain(a, e, e);
}
Dual log(Dual a) noexcept {
  return chain(a, std::log(a.v), 1 / a.v);
}
Dual sin(Dual a) noexcept {
  return chain(a, std::sin(a.v), std::cos(a.v));
}
Dual cos(Dual a) noexcept {
  return chain(a, std::cos(a.v), -std::sin(a.v));
}
Dual tan(Dual a) noexcept {
  const double t = std::tan(a.v);
  return chain(a, t, 1 + t * t);
}
Dual asin(Dual a) noexcept {
  return chain(a, std::asin(a.v), 1 / std::sqrt(1 - a.v * a.v));
}
Dual acos(Dual a) noexcept {
  return chain(a, std::acos(a.v), -1 / std::sqrt(1 - a.v * a.v));
}
Dual atan(Dual a) noexcept {
  return chain(a, std::atan(a.v), 1 / (1 + a.v * a.v));
}
Dual atan2(Dual a, Dual b) noexcept {
  const double r2 = a.v * a.v + b.v * b.v;
  return chain(a, b, std::atan2(a.v, b.v), b.v / r2, -a.v / r2);
}
Dual abs(Dual a) noexcept {
  return chain(a, std::fabs(a.v), a.v < 0 ? -1.0 : 1.0);
}

}  // namespace helios_rt::ad

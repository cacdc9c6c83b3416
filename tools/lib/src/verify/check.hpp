#pragma once
// One check of the verify report (internal to tools/lib/src/verify), the expected side of an
// equality, and the text helpers of the checks' feedback.
#include <ginac/ginac.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/symbolic/evaluate.hpp"

namespace helios::verify::detail {

constexpr double kTol = 1e-9;  // |a - b| <= kTol (1 + max(|a|, |b|)) at every point

// A number in feedback: 3 significant digits.
inline std::string num(double v) {
  return io::significant(v, 3);
}

inline std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

// Relative difference in [0, 2]; 2 when a side is not finite.
inline double rel_diff(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return 2.0;
  return std::fabs(a - b) / (1.0 + std::max(std::fabs(a), std::fabs(b)));
}

// max_rel_error as reported: 3 significant digits, and 0 below 1e-13 (agreement to rounding).
// NOTE: GiNaC orders terms by hash values, which vary between runs, so evaluations of some forms
// differ in their last bits from run to run; the report must not.
inline double reported(double v) {
  if (!std::isfinite(v)) return 2.0;
  if (v < 1e-13) return 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return std::strtod(buf, nullptr);
}

// One check: its verdict, how it was reached, and the feedback of a failure (the first reason).
struct Check {
  std::string id, category, method;
  bool pass = true, exact = false;
  int points = 0;
  double max_rel = 0;
  std::string feedback;

  void fail(const std::string& why) {
    pass = false;
    exact = false;
    if (feedback.empty()) feedback = why;
  }
  io::json to_json() const {
    return {{"id", id},
            {"category", category},
            {"verdict", pass ? "pass" : "fail"},
            {"method", method},
            {"points", points},
            {"exact", exact},
            {"max_rel_error", reported(max_rel)},
            {"feedback", pass ? "" : feedback}};
  }
};

// The expected side of an equality: its symbolic form (printed in feedback, used by the exact
// check) and a compiled form evaluated at at(point) (the point itself if `at` is empty).
struct Expected {
  GiNaC::ex symbolic;
  symbolic::Compiled numeric;
  std::function<symbolic::Point(const symbolic::Point&)> at;
};

}  // namespace helios::verify::detail

#pragma once
// Shared helpers for unit tests: mixed absolute/relative floating-point comparison.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace helios::test {

// The wall-clock bounds of the tests are the normal build's; under ASan (make test-sanitized,
// __SANITIZE_ADDRESS__) the same code runs several times slower, so a bound is scaled by this.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kTimeScale = 10;
#else
inline constexpr double kTimeScale = 1;
#endif

// |a - b| <= atol + rtol * max(|a|, |b|); NaN never compares close.
inline bool close(double a, double b, double atol, double rtol) {
  return std::fabs(a - b) <= atol + rtol * std::max(std::fabs(a), std::fabs(b));
}

// Use as EXPECT_TRUE(IsClose(a, b, atol, rtol)); the failure message shows both values.
inline ::testing::AssertionResult IsClose(double a, double b, double atol, double rtol) {
  if (close(a, b, atol, rtol)) return ::testing::AssertionSuccess();
  std::ostringstream os;
  os.precision(17);
  os << a << " vs " << b << ": |diff| = " << std::fabs(a - b)
     << " > atol + rtol*max = " << atol + rtol * std::max(std::fabs(a), std::fabs(b)) << " (atol " << atol << ", rtol "
     << rtol << ")";
  return ::testing::AssertionFailure() << os.str();
}

}  // namespace helios::test

// Brings the helpers into unqualified scope for test files.
using helios::test::close;
using helios::test::IsClose;

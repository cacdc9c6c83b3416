// The HELIOS shooting runtime as one translation unit: libhelios-runtime.a, compiled once when
// the tools are built (CMake target helios-runtime). A generated program includes
// helios_runtime.hpp and links this library, which calls back into the program's modules.
#include <cminpack-1/cminpack.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

#include "helios/astro/constants.hpp"
#include "helios/astro/ephemeris.hpp"
#include "helios/astro/kepler.hpp"
#include "helios_runtime.hpp"

namespace helios_rt {
// The modules only some problems have: a throttle's slopes, a coasting target's dynamics, the
// shooting function by legs of a problem with events, the exact Jacobian and the JACOBIAN module
// it is built on. Weak, so a program without them links; the
// runtime calls them only for a problem that has them.
void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper)
    __attribute__((weak));
void coast_dynamics(const double* y, double* dy) __attribute__((weak));
void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs) __attribute__((weak));
void shooting_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J) __attribute__((weak));
void shooting_function_dual(const Dual* x, double eps, Propagator& prop, Dual* F) __attribute__((weak));
void shooting_legs_dual(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs)
    __attribute__((weak));
void dynamics_jacobian(double t, const double* y, const double* control, const Multipliers& mult, double* dfdz,
                       double* dfdu) __attribute__((weak));
void direction_jacobian(const double* y, double* dcontrol_dy) __attribute__((weak));
void throttle_slopes_jacobian(const double* y, const Multipliers& mult, double* d_lower, double* d_upper)
    __attribute__((weak));

double wall_seconds() {
  using clock = std::chrono::steady_clock;
  static const auto start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}
}  // namespace helios_rt

#include "runtime.hpp"

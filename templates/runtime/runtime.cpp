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
#include "helios/solve/verdict.hpp"
#include "helios_runtime.hpp"

namespace helios_rt {
double wall_seconds() {
  using clock = std::chrono::steady_clock;
  static const auto start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}
}  // namespace helios_rt

#include "runtime.hpp"

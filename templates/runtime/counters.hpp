// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, counters (templates/runtime/counters.hpp): what the solve's
// integrations cost, for solution.json's "integration" record and make bench: the integrations
// (Propagator::propagate calls) and their summed wall time, the shooting-function evaluations the
// solvers asked for, and how many of them served a finite-difference Jacobian (hybrd's fdjac1
// calls the function with iflag = 2, n calls per Jacobian).
// Process-wide and atomic: the global search's threads add to the same counters, so with several
// threads the summed integration time can exceed the wall time.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

struct Counters {
  std::atomic<long long> integrations{0};
  std::atomic<long long> integration_ns{0};
  std::atomic<long long> residual_evaluations{0};        // every call of a solver's function (iflag 1 and 2)
  std::atomic<long long> jacobian_evaluations{0};        // finite-difference Jacobians (one per n iflag-2 calls)
  std::atomic<long long> jacobian_residual_calls{0};     // the iflag-2 calls
  std::atomic<long long> exact_jacobian_evaluations{0};  // exact Jacobians (hybrj's iflag-2 calls)
};
inline Counters& counters() {
  static Counters c;
  return c;
}

// Adds the wall time of its scope to the integration counters.
class IntegrationTimer {
 public:
  IntegrationTimer() : start_(std::chrono::steady_clock::now()) {}
  ~IntegrationTimer() {
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
    Counters& c = counters();
    c.integrations.fetch_add(1, std::memory_order_relaxed);
    c.integration_ns.fetch_add(static_cast<long long>(ns), std::memory_order_relaxed);
  }
  IntegrationTimer(const IntegrationTimer&) = delete;
  IntegrationTimer& operator=(const IntegrationTimer&) = delete;

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

}  // namespace helios_rt

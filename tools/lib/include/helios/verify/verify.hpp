#pragma once
// The verifier behind helios-verify ("stricter than the paper's SymPy step"): it takes from a
// derivation only its problem statement (states, controls, parameters, dynamics state_rhs,
// running_cost, endpoint_cost, the constraints' psi and targets), checks psi against the targets
// (tools/lib/src/verify/README.md), recomputes H, the state and costate ODEs, the control law
// conditions, transversality and the shooting system's shape with GiNaC, and compares them with
// what the derivation claims. Every equality is tested at random points
// (|a - b| <= 1e-9 (1 + max(|a|, |b|))) and, as a bonus, exactly; the verdict is deterministic
// for a given seed.
#include "helios/io/json_io.hpp"

namespace helios::verify {

struct VerifyOptions {
  int points = 25;    // random sample points per check (>= 1)
  unsigned seed = 1;  // RNG seed of the sample points
};

// Verifies `derivation` (a derivation artifact, builtin or LLM-written) and returns the verify
// artifact (header included; validate/write it with io::write_artifact("verify", ...)).
// Throws std::invalid_argument / input_error naming the field when the problem statement itself
// (names, dynamics, costs, psi) is unusable; every flaw in the derived parts is a failed check.
io::json verify_derivation(const io::json& derivation, const VerifyOptions& options = {});

}  // namespace helios::verify

#pragma once
// The builtin symbolic PMP engine: from a problem to the Hamiltonian,
// state/costate ODEs, optimal control law, transversality conditions and the shooting system.
#include "helios/io/json_io.hpp"
#include "helios/pmp/derivation.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp {

// Derives the necessary conditions of `problem` and returns the derivation artifact
// (derivation_json of derive_conditions).
io::json derive(const Problem& problem);

// The derivation's "units" and "times" for `problem` (normalized scales; t0, tf or, when tf is
// free, its window and tf_expression in the shooting variable tf_frac).
io::json units_of(const Problem& problem);
io::json times_of(const Problem& problem);

// build_problem + derive for a spec artifact.
io::json derive_from_spec(const io::json& spec);

}  // namespace helios::pmp

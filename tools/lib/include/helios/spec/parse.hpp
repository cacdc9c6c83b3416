#pragma once
// The builtin backend of helios-parse: a controlled English read sentence by sentence.
// The grammar is documented in README.md ("Controlled English"); every sentence must match one
// of its forms, and one that does not is an error quoting it (never silently dropped).
#include <string>

#include "helios/io/json_io.hpp"

namespace helios::spec {

// Variables a user-written perturbing acceleration may use: position x, y, z and its norm r [km],
// velocity vx, vy, vz [km/s], mass m [kg], time t [s since departure].
inline constexpr const char* kAccelerationVariables[] = {"x", "y", "z", "r", "vx", "vy", "vz", "m", "t"};

// Reads a problem text into a spec artifact (header included). `source` names the file in errors:
// "<source>:<line>: cannot use sentence \"...\": <why>". Throws input_error.
io::json parse_problem_text(const std::string& text, const std::string& source);

}  // namespace helios::spec

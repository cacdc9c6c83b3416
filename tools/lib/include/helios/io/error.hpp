#pragma once
// Error types and the exit codes every helios tool documents in --help.
#include <stdexcept>
#include <string>

namespace helios {

enum ExitCode : int {
  kExitOk = 0,
  kExitOther = 1,         // solver breakdown, I/O failure, anything unexpected
  kExitUsage = 2,         // bad command line
  kExitInvalidInput = 3,  // unreadable, malformed or schema-violating input; impossible physics
  kExitCheckFailed = 4,   // a check the tool exists to make did not pass
  kExitInfeasible = 5,    // helios-solve: the artifact is written and says the problem is infeasible
};

// Bad command line (unknown option, missing argument).
struct usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Input that cannot be used: missing file, malformed JSON, schema violation, unusable sentence.
struct input_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A verification or gate that did not pass; the artifact describing why has been written.
struct check_failed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Integration or solver breakdown.
struct numerical_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace helios

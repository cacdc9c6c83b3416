// libFuzzer target: a derivation.json as helios-verify and helios-gen read it (JSON, header,
// schema), then the verifier and the code generator on it (each a tool of its own).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.hpp"
#include "helios/codegen/generate.hpp"
#include "helios/verify/verify.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  helios::io::json derivation;
  if (!helios::fuzz::clean_outcome("read derivation",
                                   [&] { derivation = helios::io::parse_artifact("derivation", text, "d.json"); }))
    return 0;
  helios::verify::VerifyOptions options;
  options.points = 2;  // the checks' code paths, not their statistics
  helios::io::json report;
  if (helios::fuzz::clean_outcome("verify", [&] { report = helios::verify::verify_derivation(derivation, options); }))
    helios::fuzz::expect_valid("verify", report);
  helios::fuzz::clean_outcome("gen", [&] { helios::codegen::generate(derivation, {}); });
  return 0;
}

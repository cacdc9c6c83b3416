// libFuzzer target: a spec.json as helios-derive reads it (JSON, header, schema), then the builtin
// derivation of it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.hpp"
#include "helios/pmp/derive.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  helios::io::json spec, derivation;
  if (!helios::fuzz::clean_outcome("read spec", [&] { spec = helios::io::parse_artifact("spec", text, "spec.json"); }))
    return 0;
  if (helios::fuzz::clean_outcome("derive", [&] { derivation = helios::pmp::derive_from_spec(spec); }))
    helios::fuzz::expect_valid("derivation", derivation);
  return 0;
}

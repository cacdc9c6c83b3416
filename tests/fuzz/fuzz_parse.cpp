// libFuzzer target: the builtin problem-text parser (helios-parse --backend builtin).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.hpp"
#include "helios/spec/parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  helios::io::json spec;
  if (helios::fuzz::clean_outcome("parse", [&] { spec = helios::spec::parse_problem_text(text, "fuzz.txt"); }))
    helios::fuzz::expect_valid("spec", spec);
  return 0;
}

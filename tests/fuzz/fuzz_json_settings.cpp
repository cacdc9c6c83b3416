// libFuzzer target: a solver settings file as helios-solve reads it (JSON, keys, schema).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.hpp"
#include "helios/solve/solve.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  helios::fuzz::clean_outcome("settings", [&] {
    helios::solve::check_settings(helios::io::parse_json_text(text, "settings.json"), "settings.json");
  });
  return 0;
}

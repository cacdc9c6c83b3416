// json-patch: a JSON document with an RFC 6902 JSON Patch applied, for the Bats walk of the
// verifier corpus (tests/verify-corpus/cases/*.patch.json against their seeds and bases).
//
// usage: json-patch BASE.json PATCH.json   (the patched document on stdout)
//
// Object keys keep their order (added keys last), as helios::io reads them.
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace {

nlohmann::ordered_json read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  return nlohmann::ordered_json::parse(in);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "json-patch: error: usage: json-patch BASE.json PATCH.json\n";
    return 2;
  }
  try {
    std::cout << read(argv[1]).patch(read(argv[2])).dump(2) << '\n';
  } catch (const std::exception& e) {
    std::cerr << "json-patch: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

#pragma once
// The prebuilt shooting runtime a generated program links against: libhelios-runtime.a and its
// header helios_runtime.hpp, built with the tools and found beside the running executable
// (<bin>/../lib and <bin>/../include/helios-runtime; a test executable in the build tree's root
// finds them in lib/ and include/helios-runtime beside it).
#include <string>
#include <vector>

namespace helios::solve {

struct RuntimeFiles {
  std::string library;      // absolute path of libhelios-runtime.a
  std::string include_dir;  // absolute folder of helios_runtime.hpp
  // What a program is built from: the public header, the three it includes, then the library.
  std::vector<std::string> files;
};

// Located once from /proc/self/exe; throws std::runtime_error naming the paths tried.
const RuntimeFiles& runtime_files();

// The SHA-256 of the runtime's files' bytes, in order (computed once).
const std::string& runtime_sha256();

}  // namespace helios::solve

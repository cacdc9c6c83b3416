// Where the prebuilt runtime is: beside the running executable, never in the source tree.
#include "helios/solve/runtime_files.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

#include "helios/io/json_io.hpp"
#include "helios/io/sha256.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;

RuntimeFiles locate() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot read /proc/self/exe to find the shooting runtime: " + ec.message());
  std::string tried;
  // The tools' bin/ has the build tree's lib/ and include/ beside it; a test in the tree's root has them inside.
  for (const fs::path& root : {exe.parent_path().parent_path(), exe.parent_path()}) {
    const fs::path library = root / "lib" / "libhelios-runtime.a";
    const fs::path include = root / "include" / "helios-runtime";
    if (fs::is_regular_file(library, ec) && fs::is_regular_file(include / "helios_runtime.hpp", ec)) {
      RuntimeFiles f;
      f.library = fs::canonical(library).string();
      f.include_dir = fs::canonical(include).string();
      for (const char* h : {"helios_runtime.hpp", "runtime_records.hpp", "runtime_calls.hpp", "module_interface.hpp"})
        f.files.push_back((fs::path(f.include_dir) / h).string());
      f.files.push_back(f.library);
      return f;
    }
    tried += (tried.empty() ? "" : ", ") + library.string();
  }
  throw std::runtime_error("the shooting runtime libhelios-runtime.a is not beside this executable (tried " + tried +
                           "): build it with the tools (make tools)");
}

}  // namespace

const RuntimeFiles& runtime_files() {
  static const RuntimeFiles files = locate();
  return files;
}

const std::string& runtime_sha256() {
  static const std::string sha256 = [] {
    std::string bytes;
    for (const std::string& f : runtime_files().files) bytes += io::read_text(f);
    return io::sha256_hex(bytes);
  }();
  return sha256;
}

}  // namespace helios::solve

// The compile step: g++ against the prebuilt runtime, into a cache keyed by the SHA-256 of the
// source's structure (its numbers masked), command, compiler and runtime.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/process.hpp"
#include "helios/io/schema.hpp"
#include "helios/io/sha256.hpp"
#include "helios/solve/runtime_files.hpp"
#include "helios/solve/solve.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;
using io::json;

// The cached compile.log holds a compile's diagnostics (at most 64 KiB of them); more is not ours.
constexpr std::size_t kMaxCompileLog = std::size_t{1} << 20;

// How often the compiler's diagnostics say `kind` ("warning:", "error:").
int count_of(const std::string& diagnostics, const std::string& kind) {
  int n = 0;
  for (std::size_t pos = diagnostics.find(kind); pos != std::string::npos; pos = diagnostics.find(kind, pos + 1)) ++n;
  return n;
}

// The folders a compiler outside /usr needs besides /usr (its installation prefix), else none.
std::vector<std::string> compiler_prefix(const std::string& compiler) {
  std::error_code ec;
  const fs::path real = fs::canonical(compiler, ec);
  if (ec || real.string().rfind("/usr/", 0) == 0) return {};
  return {real.parent_path().parent_path().string()};
}

// The flags the runtime's library and precompiled header were built with (CMakeLists.txt's
// HELIOS_PROGRAM_FLAGS): a program compiled otherwise would not use the precompiled header.
std::vector<std::string> program_flags() {
  std::vector<std::string> flags;
  std::istringstream words(HELIOS_PROGRAM_FLAGS);
  for (std::string w; words >> w;) flags.push_back(w);
  return flags;
}

// An exclusive lock on a cache folder's lock file, held for its lifetime (flock: released when the
// process ends, however it ends). A lock that cannot be taken is no error: the compile then runs
// unserialized, as two compiles of one structure are harmless (each renames its own binary).
class CacheLock {
 public:
  explicit CacheLock(const std::string& path)
      : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~CacheLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  CacheLock(const CacheLock&) = delete;
  CacheLock& operator=(const CacheLock&) = delete;

 private:
  int fd_;
};

}  // namespace

std::string compile_key(const std::string& source, const std::string& command, const std::string& compiler_version,
                        const std::string& runtime_sha256) {
  return io::sha256_hex(source + "\n" + command + "\n" + compiler_version + "\n" + runtime_sha256);
}

CompileResult compile_cached(const std::string& source, const SolveOptions& o) {
  const std::string& compiler = o.compiler;
  CompileResult c;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> flags = program_flags();
  std::string flag_text;
  for (const auto& f : flags) flag_text += " " + f;
  // The program includes the runtime's header and links its library (absolute paths, so the
  // recorded command rebuilds the program by hand).
  const RuntimeFiles& runtime = runtime_files();
  c.command =
      compiler + flag_text + " -I" + runtime.include_dir + " shoot.cpp -o shoot " + runtime.library + " -lcminpack";
  // The key covers the source, the command, the compiler's identity and the runtime's bytes; the
  // cache's is the same over the source's structure, its numbers masked, which the program reads
  // at run time from the parameters file.
  const std::string compiler_version = io::first_line(io::capture({compiler, "--version"}));
  c.parameters = program_parameters(source);
  c.sha256 = compile_key(source, c.command, compiler_version, runtime.sha256);
  c.structure_sha256 = compile_key(c.parameters.structure, c.command, compiler_version, runtime.sha256);
  // Absolute, as the sandbox binds the folder at its absolute path.
  const fs::path dir = fs::absolute(fs::path(o.cache_dir) / c.structure_sha256).lexically_normal();
  c.binary = (dir / "shoot").string();
  const auto from_cache = [&] {
    c.ok = c.cached = true;
    // The log holds at most the 64 KiB of diagnostics a compile keeps.
    c.diagnostics = io::read_text((dir / "compile.log").string(), kMaxCompileLog);
    c.warnings = count_of(c.diagnostics, "warning:");
    c.seconds = io::seconds_since(start);
    return c;
  };
  if (fs::exists(c.binary)) return from_cache();
  fs::create_directories(dir);
  // One compile per structure at a time: a second solve of the same structure (a sweep's next row
  // under make -j) waits for the first one's compile and takes it from the cache.
  const CacheLock lock((dir / "compile.lock").string());
  if (fs::exists(c.binary)) return from_cache();
  const std::string src = (dir / "shoot.cpp").string();
  io::write_text_atomic(src, source);
  const std::string tmp_bin = (dir / (".shoot.tmp." + std::to_string(::getpid()))).string();
  const io::TempFiles guard({tmp_bin});
  std::vector<std::string> argv = {io::on_path(compiler)};
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.insert(argv.end(), {"-I" + runtime.include_dir, src, "-o", tmp_bin, runtime.library, "-lcminpack"});
  // The compiler is sandboxed as the program is: a source that includes /etc/passwd or a project
  // file finds nothing to quote in its diagnostics (which a repair round sends to the model).
  // The runtime's folders are bound read-only, beside the compiler's prefix.
  std::vector<std::string> read_only = compiler_prefix(argv[0]);
  read_only.push_back(runtime.include_dir);
  read_only.push_back(fs::path(runtime.library).parent_path().string());
  const RunResult run =
      run_limited(o.sandbox ? sandboxed(argv, dir.string(), read_only) : argv, o.time_limit_s, o.memory_limit_mb);
  c.diagnostics = run.output_text;
  if (run.timed_out || run.signal != 0)
    c.diagnostics += "\nhelios-solve: the compiler was stopped: " +
                     (run.timed_out ? "killed after " + io::limit_text(o.time_limit_s) + " s wall clock"
                                    : "signal " + std::to_string(run.signal) + " (CPU, memory or file-size limit)") +
                     "\n";
  c.warnings = count_of(c.diagnostics, "warning:");
  c.ok = run.exit_code == 0 && !run.timed_out && fs::exists(tmp_bin);
  if (c.ok) {
    io::write_text_atomic((dir / "compile.log").string(), c.diagnostics);
    fs::rename(tmp_bin, c.binary);
  }
  c.seconds = io::seconds_since(start);
  return c;
}

json compile_report(const SolveOptions& o) {
  const std::string source = io::read_text(o.source_path);
  const CompileResult c = compile_cached(source, o);
  json doc = io::artifact_header("compile", "helios-solve", o.backend);
  doc["source"] = o.source_path == "-" ? "<stdin>" : o.source_path;
  doc["ok"] = c.ok;
  doc["cached"] = c.cached;
  doc["source_sha256"] = c.sha256;
  doc["structure_sha256"] = c.structure_sha256;
  doc["command"] = c.command;
  doc["warnings"] = c.warnings;
  doc["errors"] = count_of(c.diagnostics, "error:");
  doc["diagnostics"] = c.diagnostics.substr(0, 16000);
  doc["timings"] = {{"compile_s", c.seconds}};
  return doc;
}

}  // namespace helios::solve

// The compile step: g++ against the prebuilt runtime, into a cache keyed by the SHA-256 of the
// source's structure (its numbers masked) or of the whole source, command, compiler and runtime;
// an entry is used only when it is this user's alone and its program matches its stored hash.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <optional>
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
// A compiled program is a few MiB; a cached file above this is not one of ours.
constexpr std::size_t kMaxProgram = std::size_t{512} << 20;

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

// A cache entry's folder, made private (0700) when missing; a link, a file, another user's folder
// or one others may write is refused: what is in it is not this user's alone.
void private_folder(const fs::path& dir) {
  struct stat st;
  if (::lstat(dir.c_str(), &st) != 0 && errno == ENOENT && ::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw std::runtime_error(dir.string() + ": cannot create the compile cache entry: " + std::strerror(errno));
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid() || (st.st_mode & 022) != 0)
    throw std::runtime_error(dir.string() +
                             ": the compile cache entry is not a private folder of this user (a link, a file, another "
                             "user's or writable by others); remove it or use another --cache-dir");
}

// A file of a cache entry, read without following a link and only when it is a regular file of
// this user with one link that nobody else may write, of at most `limit` bytes; else nothing.
std::optional<std::string> private_file(const fs::path& path, std::size_t limit) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return std::nullopt;
  struct stat st;
  std::optional<std::string> out;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_nlink == 1 && st.st_uid == ::geteuid() &&
      (st.st_mode & 022) == 0 && static_cast<std::size_t>(st.st_size) <= limit) {
    out.emplace();
    out->reserve(static_cast<std::size_t>(st.st_size));
    char buf[65536];
    for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) != 0;) {
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 || out->size() + static_cast<std::size_t>(n) > limit) {
        out.reset();
        break;
      }
      out->append(buf, static_cast<std::size_t>(n));
    }
  }
  ::close(fd);
  return out;
}

// The entry in `dir` when it is whole: its program, the program's stored SHA-256 and its
// compile.log, each a private file, and the program matching the hash.
bool read_entry(const fs::path& dir, CompileResult& c) {
  const auto program = private_file(dir / "shoot", kMaxProgram);
  const auto stored = private_file(dir / "shoot.sha256", 65);
  const auto log = private_file(dir / "compile.log", kMaxCompileLog);
  if (!program || !stored || !log) return false;
  const std::string hash = io::sha256_hex(*program);
  if (*stored != hash + "\n") return false;
  c.program = *program;
  c.binary_sha256 = hash;
  c.diagnostics = *log;
  return true;
}

// The stamps of `files`, one line each: where the file is (device, inode), its size and its
// modification time in nanoseconds (a rebuilt or upgraded file gets another); "" when one cannot be
// read or was modified in the last kRacySeconds (the clock's coarse ticks could give a file changed
// again within one tick the same stamp, git's "racily clean" files): such a value is computed every
// time, never kept.
std::string stamps_of(const std::vector<std::string>& files) {
  constexpr std::time_t kRacySeconds = 2;
  std::string out;
  for (const std::string& f : files) {
    struct stat st;
    if (::stat(f.c_str(), &st) != 0 || std::time(nullptr) - st.st_mtim.tv_sec < kRacySeconds) return "";
    out += f + " " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + ":" + std::to_string(st.st_size) +
           ":" + std::to_string(st.st_mtim.tv_sec) + ":" + std::to_string(st.st_mtim.tv_nsec) + "\n";
  }
  return out;
}

}  // namespace

std::string memo_by_stamps(const std::string& memo_path, const std::vector<std::string>& files,
                           const std::function<std::string()>& compute) {
  const std::string before = stamps_of(files);
  if (!before.empty()) {
    if (const auto kept = private_file(memo_path, 1 << 16)) {
      try {
        const json memo = json::parse(*kept);
        if (memo.at("stamps").get<std::string>() == before) return memo.at("value").get<std::string>();
      } catch (const json::exception&) {
        // not one of ours, or torn: computed anew and replaced below
      }
    }
  }
  const std::string value = compute();
  // Kept only when no file changed while it was computed.
  if (!before.empty() && stamps_of(files) == before) {
    try {
      io::write_text_atomic(memo_path, json{{"stamps", before}, {"value", value}}.dump() + "\n");
    } catch (const std::exception&) {
      // a memo that cannot be written is computed again next time
    }
  }
  return value;
}

namespace {

const char* key_kind_name(KeyKind kind) {
  return kind == KeyKind::Structure ? "structure" : "source";
}

}  // namespace

std::string compile_key(KeyKind kind, const std::string& text, const std::string& command,
                        const std::string& compiler_version, const std::string& runtime_sha256) {
  // Each field after its length: no two lists of fields make the same bytes.
  std::string bytes = std::string("helios compile cache 2\n") + key_kind_name(kind) + "\n";
  for (const std::string* field : {&text, &command, &compiler_version, &runtime_sha256})
    bytes += std::to_string(field->size()) + ":" + *field + "\n";
  return io::sha256_hex(bytes);
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
  // at run time from the parameters file, or over the whole source when nothing is masked.
  fs::create_directories(o.cache_dir);
  // Both kept in the cache folder by the stamps of the files they come from (memo_by_stamps).
  const std::string compiler_path = io::on_path(compiler);
  const std::string compiler_version =
      memo_by_stamps((fs::path(o.cache_dir) / "compiler-identity.json").string(), {compiler_path}, [&] {
        return io::first_line(io::capture({compiler_path, "--version"}));
      });
  c.parameters = program_parameters(source);
  const std::string runtime_hash = memo_by_stamps((fs::path(o.cache_dir) / "runtime-identity.json").string(),
                                                  runtime.files, [] { return runtime_sha256(); });
  c.sha256 = compile_key(KeyKind::Source, source, c.command, compiler_version, runtime_hash);
  c.structure_sha256 = c.parameters.readable ? compile_key(KeyKind::Structure, c.parameters.structure, c.command,
                                                           compiler_version, runtime_hash)
                                             : c.sha256;
  // Absolute, as the sandbox binds the folder at its absolute path.
  const fs::path dir = fs::absolute(fs::path(o.cache_dir) / c.structure_sha256).lexically_normal();
  c.binary = (dir / "shoot").string();
  const auto from_cache = [&] {
    c.ok = c.cached = true;
    c.warnings = count_of(c.diagnostics, "warning:");
    c.seconds = io::seconds_since(start);
    return c;
  };
  private_folder(dir);
  if (read_entry(dir, c)) return from_cache();
  // One compile per structure at a time: a second solve of the same structure (a sweep's next row
  // under make -j) waits for the first one's compile and takes it from the cache.
  const CacheLock lock((dir / "compile.lock").string());
  if (read_entry(dir, c)) return from_cache();
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
  std::optional<std::string> program;
  if (run.exit_code == 0 && !run.timed_out && ::chmod(tmp_bin.c_str(), 0700) == 0)
    program = private_file(tmp_bin, kMaxProgram);
  c.ok = program.has_value();
  if (c.ok) {
    // The log and the hash first: a reader that meets the new hash beside the old program finds
    // them different and waits for this lock.
    c.program = std::move(*program);
    c.binary_sha256 = io::sha256_hex(c.program);
    io::write_text_atomic((dir / "compile.log").string(), c.diagnostics);
    io::write_text_atomic((dir / "shoot.sha256").string(), c.binary_sha256 + "\n");
    fs::rename(tmp_bin, c.binary);
  }
  c.seconds = io::seconds_since(start);
  return c;
}

void install_program(const CompileResult& c, const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0700);
  if (fd < 0) throw std::runtime_error(path + ": cannot create the program to run: " + std::strerror(errno));
  std::size_t done = 0;
  while (done < c.program.size()) {
    const ssize_t n = ::write(fd, c.program.data() + done, c.program.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      throw std::runtime_error(path + ": cannot write the program to run: " + std::strerror(error));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw std::runtime_error(path + ": cannot write the program to run: " + std::strerror(errno));
}

json cache_record(const CompileResult& c) {
  json record = {{"cache_key", c.parameters.readable ? "structure" : "source"}};
  if (!c.parameters.readable) record["cache_key_detail"] = c.parameters.whole_source_because;
  if (c.ok) record["binary_sha256"] = c.binary_sha256;
  return record;
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
  doc.update(cache_record(c));
  doc["command"] = c.command;
  doc["warnings"] = c.warnings;
  doc["errors"] = count_of(c.diagnostics, "error:");
  doc["diagnostics"] = c.diagnostics.substr(0, 16000);
  doc["timings"] = {{"compile_s", c.seconds}};
  return doc;
}

}  // namespace helios::solve

#pragma once
// Running other programs: fork/exec without a shell, their output captured, several at a time; and
// the text helpers for what they print. Used by helios-solve (the compiler, the sandboxed program,
// gnuplot) and by the sweep's cross-check (helios-solve, N at a time).
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace helios::io {

// Seconds since `start` on the steady clock.
double seconds_since(std::chrono::steady_clock::time_point start);

// A command's argv as exec wants it, built before fork: a forked child may not allocate. Another
// thread of the parent may hold the allocator's lock at the fork, and a child that lowered its
// RLIMIT_AS below the parent's mappings (the sandbox's memory limit) cannot map anything: under
// AddressSanitizer even a small malloc may map a new page of its allocation records there, and fails.
class ExecArgv {
 public:
  explicit ExecArgv(std::vector<std::string> argv);
  ExecArgv(const ExecArgv&) = delete;
  ExecArgv& operator=(const ExecArgv&) = delete;
  // In the forked child: replaces it with the command (argv[0] a path, or looked up on PATH when
  // `search_path`); exits 127 when that fails. Allocates nothing.
  [[noreturn]] void exec_or_exit(bool search_path) const;

 private:
  std::vector<std::string> strings_;
  std::vector<char*> pointers_;
};

// `name` itself when it holds a '/', else the first executable PATH entry of that name; `name`
// when none is (the exec then fails with its own error).
std::string on_path(const std::string& name);

// The combined stdout and stderr of a shell-free command (argv[0] looked up on PATH).
std::string capture(const std::vector<std::string>& argv);

// Runs shell-free commands (argv[0] looked up on PATH; their stdin, stdout and stderr the caller's),
// `jobs` at a time (at least one), each next one started as soon as one ends. Returns each one's
// exit code in the order of `commands`: 127 when it could not be executed, -1 when a signal ended
// it. Throws std::runtime_error when a process cannot be started (fork fails), after waiting for
// the ones already running. It waits for any child (waitpid(-1)): the caller must have no other
// child running, whose status it would take.
std::vector<int> run_all(const std::vector<std::vector<std::string>>& commands, int jobs);

// The text up to its first newline.
std::string first_line(const std::string& s);

// `text` fit for one line of a record: control bytes (a newline, an escape sequence) replaced by
// '?', cut at `max_bytes` with "..." after. For what a program wrote into a status_detail.
std::string printable_line(std::string text, std::size_t max_bytes = 500);

// A number of seconds as text ("%g").
std::string limit_text(double seconds);

}  // namespace helios::io

// The sandboxed run of a generated program: resource limits, its own process group, nothing left
// running, and its stderr forwarded line by line.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "helios/io/process.hpp"
#include "helios/solve/solve.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;

// Processes the program may add to the user's count (RLIMIT_NPROC): it needs none.
constexpr long kMaxChildProcesses = 16;

// From /proc: the processes whose parent is this process (the orphans a subreaper inherits), and
// whether a process of `group` still runs (a zombie does not).
struct ProcessScan {
  std::vector<pid_t> children;
  bool group_running = false;
};
ProcessScan scan_processes(pid_t group) {
  ProcessScan out;
  const std::string self = std::to_string(::getpid()), group_id = std::to_string(group);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // pid (comm) state ppid pgrp ...: comm may hold spaces, so read after the last ')'.
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 1));
    std::string state, ppid, pgrp;
    rest >> state >> ppid >> pgrp;
    if (ppid == self) out.children.push_back(static_cast<pid_t>(std::stol(name)));
    if (pgrp == group_id && state != "Z" && state != "X") out.group_running = true;
  }
  return out;
}

// Number of processes of the real user (RLIMIT_NPROC counts them all).
long processes_of_user() {
  long n = 0;
  const uid_t uid = ::getuid();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    struct stat st;
    if (::stat(entry.path().c_str(), &st) == 0 && st.st_uid == uid) ++n;
  }
  return n;
}

// A process's command name (/proc/<pid>/comm), "" when it cannot be read.
std::string command_name(pid_t p) {
  std::ifstream in("/proc/" + std::to_string(p) + "/comm");
  std::string name;
  std::getline(in, name);
  return name;
}

// Whether child `p` ends (and is reaped) within `grace`.
bool ends_within(pid_t p, std::chrono::milliseconds grace) {
  const auto until = std::chrono::steady_clock::now() + grace;
  do {
    if (::waitpid(p, nullptr, WNOHANG) == p) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  } while (std::chrono::steady_clock::now() < until);
  return false;
}

// Kills whatever the program left behind: its process group, then (as a child subreaper) every
// orphan reparented to us, including those that left the group with setsid(). Returns how many.
// Done when no process is our child and none of the group runs: a process that outlives the
// program is then nowhere (one whose parent died was reparented to us before that parent became a
// zombie, and a dying one is still in the group).
int kill_leftovers(pid_t group) {
  int killed = 0;
  ::kill(-group, SIGKILL);
  for (int round = 0; round < 1000; ++round) {
    const ProcessScan scan = scan_processes(group);
    if (scan.children.empty()) {
      if (!scan.group_running) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the group's processes are dying
      continue;
    }
    for (const pid_t p : scan.children) {
      // bubblewrap's own init, reparented to us as its program ends, is no leftover of the
      // program's: it gets a moment to end on its own, and is not counted.
      if (command_name(p) == "bwrap") {
        if (!ends_within(p, std::chrono::milliseconds(200))) {
          ::kill(p, SIGKILL);
          ::waitpid(p, nullptr, 0);
        }
        continue;
      }
      // Anything else the program started outlived it (killed here, or with its namespace).
      if (::waitpid(p, nullptr, WNOHANG) != p) {
        ::kill(p, SIGKILL);
        ::waitpid(p, nullptr, 0);
      }
      ++killed;
    }
  }
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
  return killed;
}

// Collects what a program prints (stderr and stdout alike): the first 64 KiB as text, each
// complete line, cleaned, to on_line as it arrives, and the line that says why it failed (the last
// one naming an error, else the last one).
class OutputLines {
 public:
  OutputLines(RunResult& result, const std::function<void(const std::string&)>& on_line)
      : result_(result), on_line_(on_line) {}
  void add(const char* data, std::size_t n) {
    std::string& text = result_.output_text;
    if (text.size() < kMaxText) text.append(data, std::min(n, kMaxText - text.size()));
    for (std::size_t i = 0; i < n; ++i) {
      if (data[i] == '\n') {
        flush();
        continue;
      }
      if (line_.size() < kMaxLine) line_ += std::isprint(static_cast<unsigned char>(data[i])) ? data[i] : '?';
    }
  }
  void flush() {
    if (line_.empty()) return;
    if (on_line_) on_line_(line_);
    const bool names_error = line_.find("error") != std::string::npos;
    if (names_error || !names_error_) result_.error_line = line_;
    names_error_ = names_error_ || names_error;
    line_.clear();
  }

 private:
  static constexpr std::size_t kMaxText = 65536, kMaxLine = 300;
  RunResult& result_;
  const std::function<void(const std::string&)>& on_line_;
  std::string line_;
  bool names_error_ = false;
};

}  // namespace

std::vector<std::string> sandboxed(const std::vector<std::string>& argv, const std::string& workdir,
                                   const std::vector<std::string>& read_only) {
  const std::string bwrap = io::on_path("bwrap");
  if (bwrap.find('/') == std::string::npos)
    throw std::runtime_error(
        "bubblewrap (bwrap) is not installed, so the program cannot run sandboxed: install it "
        "(tools/install-deps.sh, Debian package bubblewrap) or pass --no-sandbox");
  // The fresh /tmp comes before every bind: a bind under /tmp (a build tree, cache or run folder
  // there) mounted first would be hidden by it.
  std::vector<std::string> out = {bwrap,      "--unshare-all", "--die-with-parent", "--new-session", "--clearenv",
                                  "--setenv", "PATH",          "/usr/bin",          "--proc",        "/proc",
                                  "--dev",    "/dev",          "--tmpfs",           "/tmp",          "--ro-bind",
                                  "/usr",     "/usr"};
  // The top-level links into /usr of a merged-/usr system stay links; a real folder is bound.
  for (const char* top : {"/lib", "/lib64", "/lib32", "/bin", "/sbin"}) {
    std::error_code ec;
    if (fs::is_symlink(top, ec))
      out.insert(out.end(), {"--symlink", fs::read_symlink(top, ec).string(), top});
    else if (fs::is_directory(top, ec))
      out.insert(out.end(), {"--ro-bind", top, top});
  }
  for (const auto& folder : read_only) out.insert(out.end(), {"--ro-bind", folder, folder});
  out.insert(out.end(), {"--ro-bind", argv.at(0), argv.at(0), "--bind", workdir, workdir, "--chdir", workdir, "--"});
  out.insert(out.end(), argv.begin(), argv.end());
  return out;
}

RunResult run_limited(const std::vector<std::string>& argv, double wall_limit_s, double memory_limit_mb,
                      const std::string& workdir, const std::function<void(const std::string&)>& on_line) {
  RunResult r;
  const auto start = std::chrono::steady_clock::now();
  int err_pipe[2];
  if (::pipe2(err_pipe, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  // Orphans of the program (a daemonized or setsid() child) are reparented to us, so none escapes.
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  const rlim_t nproc = static_cast<rlim_t>(processes_of_user() + kMaxChildProcesses);
  // The CPU limit counts every thread's time, and the search runs one per core.
  const rlim_t cores = std::max(1u, std::thread::hardware_concurrency());
  const pid_t parent = ::getpid();
  const io::ExecArgv command(argv);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    // The child dies with helios-solve, so an interrupted run leaves no orphan writing files.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) _exit(126);
    // Its own process group, so a timeout kills everything it started.
    ::setpgid(0, 0);
    // stdout joins stderr in the collector: what the program prints never reaches helios-solve's
    // own output (with -o - that is the solution document).
    ::dup2(err_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    if (!workdir.empty() && ::chdir(workdir.c_str()) != 0) _exit(126);
    const rlim_t cpu = static_cast<rlim_t>(std::ceil(wall_limit_s)) * cores + 5;
    const rlim_t mem = static_cast<rlim_t>(memory_limit_mb * 1024 * 1024);
    const rlim_t fsize = 512ull * 1024 * 1024;
    const struct rlimit cpu_limit = {cpu, cpu}, mem_limit = {mem, mem}, file_limit = {fsize, fsize};
    const struct rlimit no_core = {0, 0}, proc_limit = {nproc, nproc};
    ::setrlimit(RLIMIT_CPU, &cpu_limit);
    ::setrlimit(RLIMIT_AS, &mem_limit);
    ::setrlimit(RLIMIT_FSIZE, &file_limit);
    ::setrlimit(RLIMIT_CORE, &no_core);
    // NOTE: the kernel does not apply RLIMIT_NPROC to root; kill_leftovers() is the bound there.
    ::setrlimit(RLIMIT_NPROC, &proc_limit);
    command.exec_or_exit(false);
  }
  ::close(err_pipe[1]);
  ::fcntl(err_pipe[0], F_SETFL, O_NONBLOCK);
  ::setpgid(pid, pid);  // also from the parent, so the group exists before any kill
  OutputLines lines(r, on_line);
  char buf[4096];
  const auto drain = [&] {
    ssize_t n;
    while ((n = ::read(err_pipe[0], buf, sizeof buf)) > 0) lines.add(buf, static_cast<std::size_t>(n));
  };
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (io::seconds_since(start) > wall_limit_s) {
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    struct pollfd p = {err_pipe[0], POLLIN, 0};
    ::poll(&p, 1, 20);
    drain();
  }
  r.leftover_processes = kill_leftovers(pid);
  r.seconds = io::seconds_since(start);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  drain();
  lines.flush();
  ::close(err_pipe[0]);
  return r;
}

}  // namespace helios::solve

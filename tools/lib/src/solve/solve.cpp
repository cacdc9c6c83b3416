#include "helios/solve/solve.hpp"

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
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/io/sha256.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;
using io::json;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Output of a shell-free command (for `g++ --version`).
std::string capture(const std::vector<std::string>& argv) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) return "";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(pipefd[1], 1);
    ::dup2(pipefd[1], 2);
    ::close(pipefd[0]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    _exit(127);
  }
  ::close(pipefd[1]);
  std::string out;
  char buf[4096];
  ssize_t n;
  while ((n = ::read(pipefd[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  ::close(pipefd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return out;
}

int count_warnings(const std::string& diagnostics) {
  int n = 0;
  for (std::size_t pos = diagnostics.find("warning:"); pos != std::string::npos;
       pos = diagnostics.find("warning:", pos + 1))
    ++n;
  return n;
}

std::string first_line(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

std::string limit_text(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", seconds);
  return buf;
}

// Processes the program may add to the user's count (RLIMIT_NPROC): it needs none.
constexpr long kMaxChildProcesses = 16;

// Processes whose parent is this process, from /proc (the orphans a subreaper inherits).
std::vector<pid_t> children_of_self() {
  std::vector<pid_t> out;
  const std::string self = std::to_string(::getpid());
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // pid (comm) state ppid ...: comm may hold spaces, so read after the last ')'.
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 1));
    std::string state, ppid;
    rest >> state >> ppid;
    if (ppid == self) out.push_back(static_cast<pid_t>(std::stol(name)));
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

// Kills whatever the program left behind: its process group, then (as a child subreaper) every
// orphan reparented to us, including those that left the group with setsid(). Returns how many.
int kill_leftovers(pid_t group) {
  int killed = 0;
  ::kill(-group, SIGKILL);
  for (int quiet = 0, round = 0; quiet < 3 && round < 200; ++round) {
    const auto stray = children_of_self();
    if (stray.empty()) {
      ++quiet;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    quiet = 0;
    for (const pid_t p : stray) {
      ::kill(p, SIGKILL);
      ::waitpid(p, nullptr, 0);
      ++killed;
    }
  }
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
  return killed;
}

}  // namespace

// Collects a program's stderr: the first 64 KiB as text, and each complete line, cleaned, to
// on_line as it arrives.
class StderrLines {
 public:
  StderrLines(std::string& text, const std::function<void(const std::string&)>& on_line)
      : text_(text), on_line_(on_line) {}
  void add(const char* data, std::size_t n) {
    if (text_.size() < 65536) text_.append(data, std::min(n, 65536 - text_.size()));
    if (!on_line_) return;
    for (std::size_t i = 0; i < n; ++i) {
      if (data[i] == '\n') {
        flush();
        continue;
      }
      if (line_.size() < 300) line_ += std::isprint(static_cast<unsigned char>(data[i])) ? data[i] : '?';
    }
  }
  void flush() {
    if (on_line_ && !line_.empty()) on_line_(line_);
    line_.clear();
  }

 private:
  std::string& text_;
  const std::function<void(const std::string&)>& on_line_;
  std::string line_;
};

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
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    // The child dies with helios-solve, so an interrupted run leaves no orphan writing files.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) _exit(126);
    // Its own process group, so a timeout kills everything it started.
    ::setpgid(0, 0);
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
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    _exit(127);
  }
  ::close(err_pipe[1]);
  ::fcntl(err_pipe[0], F_SETFL, O_NONBLOCK);
  ::setpgid(pid, pid);  // also from the parent, so the group exists before any kill
  StderrLines lines(r.stderr_text, on_line);
  char buf[4096];
  const auto drain = [&] {
    ssize_t n;
    while ((n = ::read(err_pipe[0], buf, sizeof buf)) > 0) lines.add(buf, static_cast<std::size_t>(n));
  };
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (seconds_since(start) > wall_limit_s) {
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
  r.seconds = seconds_since(start);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  drain();
  lines.flush();
  ::close(err_pipe[0]);
  return r;
}

CompileResult compile_cached(const std::string& source, const std::string& compiler, const std::string& cache_dir) {
  CompileResult c;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> flags = {"-std=c++17", "-O2", "-pthread", "-Wall", "-Wextra"};
  std::string flag_text;
  for (const auto& f : flags) flag_text += " " + f;
  c.command = compiler + flag_text + " shoot.cpp -o shoot -lcminpack";
  // The key covers the source, the command and the compiler's identity.
  c.sha256 = io::sha256_hex(source + "\n" + c.command + "\n" + first_line(capture({compiler, "--version"})));
  const fs::path dir = fs::path(cache_dir) / c.sha256;
  c.binary = (dir / "shoot").string();
  if (fs::exists(c.binary)) {
    c.ok = c.cached = true;
    std::ifstream log((dir / "compile.log").string());
    c.diagnostics.assign(std::istreambuf_iterator<char>(log), std::istreambuf_iterator<char>());
    c.warnings = count_warnings(c.diagnostics);
    c.seconds = seconds_since(start);
    return c;
  }
  fs::create_directories(dir);
  const std::string src = (dir / "shoot.cpp").string();
  io::write_text_atomic(src, source);
  const std::string tmp_bin = (dir / (".shoot.tmp." + std::to_string(::getpid()))).string();
  const io::TempFiles guard({tmp_bin});
  std::vector<std::string> argv = {compiler};
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.insert(argv.end(), {src, "-o", tmp_bin, "-lcminpack"});
  // Compilers live on PATH: resolve through a shell-free execvp in capture().
  c.diagnostics = capture(argv);
  c.warnings = count_warnings(c.diagnostics);
  c.ok = fs::exists(tmp_bin);
  if (c.ok) {
    io::write_text_atomic((dir / "compile.log").string(), c.diagnostics);
    fs::rename(tmp_bin, c.binary);
  }
  c.seconds = seconds_since(start);
  return c;
}

// The trajectory CSV's header and first data row, to pick the plots' units and panels.
std::pair<std::vector<std::string>, std::vector<double>> csv_head(const std::string& csv_path) {
  std::ifstream in(csv_path);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::vector<std::string> columns;
  std::vector<double> values;
  std::stringstream hs(header), rs(row);
  for (std::string c; std::getline(hs, c, ',');) columns.push_back(c);
  for (std::string v; std::getline(rs, v, ',');) values.push_back(std::atof(v.c_str()));
  return {columns, values};
}

json plot_trajectory(const std::string& csv_path, const std::string& prefix, const std::string& title) {
  const auto [columns, first] = csv_head(csv_path);
  const auto has = [&](const std::string& c) { return std::find(columns.begin(), columns.end(), c) != columns.end(); };
  const bool engine = has("u") && has("m_kg");
  const bool heliocentric = first.size() > 3 && std::hypot(first[1], first[2], first[3]) > 1e7;
  const std::string length = heliocentric ? "AU" : "km", scale = heliocentric ? "149597870.691" : "1.0";
  // Cone angle between the sail normal and the Sun line, in degrees.
  const std::string cone =
      "(acos((column('nx')*$2 + column('ny')*$3 + column('nz')*$4)/sqrt($2**2 + $3**2 + $4**2))*180/pi)";
  const std::string colour = engine ? "(column('u'))" : cone;
  const std::string panel = engine ? "throttle_mass" : "cone_angle";
  const std::string traj_png = prefix + "trajectory.png", panel_png = prefix + panel + ".png";
  const std::string tmp1 = prefix + ".trajectory.png.tmp", tmp2 = prefix + "." + panel + ".png.tmp";
  const io::TempFiles guard({tmp1, tmp2});
  std::string script = "set datafile separator ','\nset terminal pngcairo size 1000,800 noenhanced\n";
  script += "set output '" + tmp1 + "'\nset title '" + title +
            ": trajectory (colour = " + (engine ? "throttle" : "cone angle") + ")'\n";
  script += "set xlabel 'x [" + length + "]'\nset ylabel 'y [" + length + "]'\nset zlabel 'z [" + length + "]'\n";
  script += "set view equal xy\nset ticslevel 0\nset grid\nset palette defined (0 '#2b6cb0', 1 '#e53e3e')\n";
  script +=
      engine ? "set cbrange [0:1]\nset cblabel 'throttle u'\n" : "set cbrange [0:90]\nset cblabel 'cone angle [deg]'\n";
  script += "L = " + scale + "\nsplot '" + csv_path + "' every ::1 using ($2/L):($3/L):($4/L):" + colour +
            " with lines lw 2 palette title 'spacecraft', '< echo 0,0,0' using 1:2:3 with points pt 7 ps 2 lc rgb "
            "'#d69e2e' title 'central body'\n";
  script += "set output '" + tmp2 + "'\nset xlabel 'time [days]'\nunset zlabel\n";
  if (engine)
    script += "set title '" + title +
              ": throttle and mass'\nset ylabel 'throttle u'\nset y2label 'mass [kg]'\n"
              "set yrange [-0.05:1.05]\nset y2tics\nset ytics nomirror\nplot '" +
              csv_path +
              "' every ::1 using 1:(column('u')) with lines lw 2 lc rgb '#e53e3e' title 'throttle', "
              "'' every ::1 using 1:(column('m_kg')) axes x1y2 with lines lw 2 lc rgb '#2b6cb0' title 'mass'\n";
  else
    script += "set title '" + title + ": sail cone angle'\nset ylabel 'cone angle [deg]'\nset yrange [0:90]\nplot '" +
              csv_path + "' every ::1 using 1:" + cone + " with lines lw 2 lc rgb '#e53e3e' title 'cone angle'\n";
  char script_path[] = "/tmp/helios-plot-XXXXXX";
  const int fd = ::mkstemp(script_path);
  if (fd < 0) throw std::runtime_error("cannot create a gnuplot script file");
  if (::write(fd, script.data(), script.size()) != static_cast<ssize_t>(script.size())) {
    ::close(fd);
    throw std::runtime_error("cannot write the gnuplot script");
  }
  ::close(fd);
  const std::string out = capture({"gnuplot", script_path});
  ::unlink(script_path);
  if (!fs::exists(tmp1) || !fs::exists(tmp2))
    throw std::runtime_error("gnuplot did not draw the plots (is gnuplot installed?): " + first_line(out));
  fs::rename(tmp1, traj_png);
  fs::rename(tmp2, panel_png);
  return {{"trajectory_plot", fs::path(traj_png).filename().string()},
          {panel + "_plot", fs::path(panel_png).filename().string()}};
}

json compile_report(const SolveOptions& o) {
  const std::string source = io::read_text(o.source_path);
  const CompileResult c = compile_cached(source, o.compiler, o.cache_dir);
  json doc = io::artifact_header("compile", "helios-solve", o.backend);
  doc["source"] = o.source_path == "-" ? "<stdin>" : o.source_path;
  doc["ok"] = c.ok;
  doc["cached"] = c.cached;
  doc["source_sha256"] = c.sha256;
  doc["command"] = c.command;
  doc["warnings"] = c.warnings;
  int errors = 0;
  for (std::size_t pos = c.diagnostics.find("error:"); pos != std::string::npos;
       pos = c.diagnostics.find("error:", pos + 1))
    ++errors;
  doc["errors"] = errors;
  doc["diagnostics"] = c.diagnostics.substr(0, 16000);
  doc["timings"] = {{"compile_s", c.seconds}};
  return doc;
}

json solve(const SolveOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::string source = io::read_text(o.source_path);
  json settings = json::object();
  if (!o.settings_path.empty()) settings = io::read_json(o.settings_path);
  if (!settings.is_object()) throw input_error(o.settings_path + ": settings must be a JSON object");
  // schemas/settings.schema.json lists the keys the runtime reads (templates/runtime/main.hpp) with
  // their types and ranges; anything else is a typo, not a no-op.
  static const std::vector<std::string> known = io::schema_properties("settings");
  for (auto it = settings.begin(); it != settings.end(); ++it) {
    if (std::find(known.begin(), known.end(), it.key()) == known.end()) {
      std::string names;
      for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
      throw input_error(o.settings_path + ": field /" + it.key() + " is not a solver setting (known: " + names + ")");
    }
  }
  io::validate("settings", settings, o.settings_path);
  // The program stops itself a little before the wall-clock kill.
  const double own_limit = std::max(1.0, o.time_limit_s - 5);
  settings["time_limit_s"] = std::min(settings.value("time_limit_s", own_limit), own_limit);

  json doc = io::artifact_header("solution", "helios-solve", o.backend);
  doc["problem"] = {{"id", "unknown"}};
  doc["status"] = "compile_failed";
  const CompileResult c = compile_cached(source, o.compiler, o.cache_dir);
  doc["compile"] = {{"ok", c.ok},           {"cached", c.cached},     {"source_sha256", c.sha256},
                    {"command", c.command}, {"warnings", c.warnings}, {"diagnostics", c.diagnostics.substr(0, 8000)}};
  doc["seed"] = settings.value("seed", 1);
  doc["iterations"] = 0;
  doc["function_evaluations"] = 0;
  doc["settings"] = settings;
  doc["timings"] = {{"compile_s", c.seconds}, {"run_s", 0.0}, {"total_s", seconds_since(start)}};
  if (!c.ok) return doc;
  if (o.progress)
    o.progress(c.cached ? "compiled program from the cache" : "compiled in " + limit_text(c.seconds) + " s");

  const fs::path out_dir = fs::path(o.trajectory_path).parent_path();
  const std::string tag = std::to_string(::getpid());
  const std::string settings_tmp = (out_dir / (".settings." + tag + ".json")).string();
  const std::string result_tmp = (out_dir / (".result." + tag + ".json")).string();
  const std::string traj_tmp = (out_dir / (".trajectory." + tag + ".csv")).string();
  // The program writes RESULT.part / TRAJECTORY.part and renames them; all go when solve() returns.
  const io::TempFiles guard({settings_tmp, result_tmp, traj_tmp, result_tmp + ".part", traj_tmp + ".part"});
  io::write_json_atomic(settings_tmp, settings);
  const RunResult run =
      run_limited({fs::absolute(c.binary).string(), "--settings", fs::absolute(settings_tmp).string(), "--result",
                   fs::absolute(result_tmp).string(), "--trajectory", fs::absolute(traj_tmp).string()},
                  o.time_limit_s, o.memory_limit_mb, fs::absolute(out_dir.empty() ? fs::path(".") : out_dir).string(),
                  o.progress);
  doc["timings"]["run_s"] = run.seconds;
  if (run.timed_out || run.exit_code != 0 || !fs::exists(result_tmp)) {
    doc["status"] = run.timed_out ? "timeout" : "crashed";
    doc["status_detail"] = run.timed_out ? "killed after " + limit_text(o.time_limit_s) + " s wall clock"
                                         : "exit code " + std::to_string(run.exit_code) + ", signal " +
                                               std::to_string(run.signal) + ": " + first_line(run.stderr_text);
    if (run.leftover_processes > 0)
      doc["status_detail"] = doc["status_detail"].get<std::string>() + "; killed " +
                             std::to_string(run.leftover_processes) + " leftover processes";
    doc["timings"]["total_s"] = seconds_since(start);
    return doc;
  }
  const json r = io::read_json(result_tmp);
  doc["problem"]["id"] = r.value("problem", "unknown");
  doc["status"] = r.at("status");
  if (!r.value("detail", "").empty()) doc["status_detail"] = r.at("detail");
  doc["solver_info"] = {{"code", r.at("info")}, {"meaning", r.at("info_meaning")}};
  doc["seed"] = r.at("seed");
  doc["restarts"] = std::max(0, r.at("attempts").get<int>() - 1);
  doc["iterations"] = r.at("iterations");
  doc["function_evaluations"] = r.at("function_evaluations");
  json homotopy = json::array();
  for (const auto& h : r.at("homotopy")) {
    json step = {{"eps", h.at("eps")}, {"converged", h.at("converged")}, {"evaluations", h.at("evaluations")}};
    if (h.at("max_residual").get<double>() >= 0) step["max_residual"] = h.at("max_residual");
    homotopy.push_back(step);
  }
  doc["homotopy"] = homotopy;
  // How the solution was reached: the method, and for problems with interior events every leg
  // solved alone (its guesses, residual and evaluations) before the legs were joined, and every
  // solve of the continuation from the problem without its events onto them.
  doc["method"] = r.value("method", "single shooting");
  if (r.contains("legs")) doc["legs"] = r.at("legs");
  doc["passes"] = r.value("passes", 1);
  if (r.contains("bounds")) doc["bounds"] = r.at("bounds");
  if (r.contains("search")) doc["search"] = r.at("search");
  if (r.contains("continuation")) {
    json steps = json::array();
    for (const auto& c : r.at("continuation")) {
      json step = {{"stage", c.at("stage")}, {"value", c.at("value")}, {"converged", c.at("converged")},
                   {"evaluations", c.at("evaluations")}};
      if (c.at("max_residual").get<double>() >= 0) step["max_residual"] = c.at("max_residual");
      steps.push_back(step);
    }
    doc["continuation"] = steps;
  }
  if (r.at("status") == "converged") {
    doc["tof_days"] = r.at("tof_days");
    if (r.contains("departure_mjd2000")) doc["departure_mjd2000"] = r.at("departure_mjd2000");
    if (r.contains("final_mass_kg")) {  // a sail has no mass state
      doc["initial_mass_kg"] = r.at("initial_mass_kg");
      doc["final_mass_kg"] = r.at("final_mass_kg");
      doc["propellant_kg"] = r.at("propellant_kg");  // a mass drop is not propellant
      doc["delta_v_m_s"] = r.at("delta_v_m_s");
    }
    doc["epsilon"] = r.at("epsilon");
    doc["max_residual"] = r.at("max_residual");
    doc["residuals"] = r.at("residuals");
    doc["x"] = r.at("x");
    doc["switches"] = r.at("trajectory").at("switches");
    doc["hamiltonian_drift"] = r.at("trajectory").at("hamiltonian_drift");
    fs::rename(traj_tmp, o.trajectory_path);
    doc["files"] = {{"trajectory", fs::path(o.trajectory_path).filename().string()}};
    if (!o.plot_prefix.empty()) {
      doc["files"].update(plot_trajectory(o.trajectory_path, o.plot_prefix, doc["problem"]["id"].get<std::string>()));
    }
  }
  doc["timings"]["total_s"] = seconds_since(start);
  return doc;
}

}  // namespace helios::solve

// The solve stage: validated settings, the compile, the sandboxed run, and the solution record
// (solution.json): the program's outcome (solution.json's keys) with the compile, the settings, the
// timings and the files added.
#include "helios/solve/solve.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "helios/astro/calendar.hpp"
#include "helios/io/error.hpp"
#include "helios/io/process.hpp"
#include "helios/io/schema.hpp"

namespace helios::solve {

namespace fs = std::filesystem;
using io::json;

void check_settings(const json& settings, const std::string& source) {
  if (!settings.is_object()) throw input_error(source + ": settings must be a JSON object");
  static const std::vector<std::string> known = io::schema_properties("settings");
  for (auto it = settings.begin(); it != settings.end(); ++it) {
    if (std::find(known.begin(), known.end(), it.key()) == known.end()) {
      std::string names;
      for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
      throw input_error(source + ": field /" + it.key() + " is not a solver setting (known: " + names + ")");
    }
  }
  // The schema's own words for this one (an anyOf) would not say what is allowed.
  if (const auto it = settings.find("node_spacing_days");
      it != settings.end() && it->is_number() && it->get<double>() > 0 && it->get<double>() < 1)
    throw input_error(source + ": field /node_spacing_days: " + io::limit_text(it->get<double>()) +
                      " is below 1 day (0 turns the multiple-shooting polish off)");
  io::validate("settings", settings, source);
}

int scheduler_cpus_per_task() {
  const char* value = std::getenv("SLURM_CPUS_PER_TASK");
  if (value == nullptr || *value == '\0') return 0;
  const std::string text = value;
  const bool digits =
      text.size() <= 2 && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  const int cpus = digits ? std::stoi(text) : 0;
  if (cpus < 1 || cpus > 64)
    throw input_error("SLURM_CPUS_PER_TASK: '" + text + "' is not a CPU count (a whole number from 1 to 64)");
  return cpus;
}

// Each key of the settings file is one of schemas/settings.schema.json (which lists the keys the
// runtime reads, with their types and ranges: anything else is a typo, not a no-op).
json run_settings(const SolveOptions& o) {
  json settings = json::object();
  if (!o.settings_path.empty()) settings = io::read_json(o.settings_path);
  check_settings(settings, o.settings_path);
  const double own_limit = std::max(1.0, o.time_limit_s - 5);
  settings["time_limit_s"] = std::min(settings.value("time_limit_s", own_limit), own_limit);
  if (settings.value("threads", 0) == 0)
    if (const int cpus = scheduler_cpus_per_task(); cpus > 0) settings["threads"] = cpus;
  return settings;
}

namespace {

// The keys of solution.json that helios-solve alone knows: the artifact's header, the compile,
// the settings the program ran with, the timings and the files. The program's outcome
// (templates/runtime/main.hpp) carries every other key of schemas/solution.schema.json.
const std::vector<std::string> kSolveKeys = {"schema",   "schema_version", "producer", "compile",   "sandbox",
                                             "settings", "timings",        "files",    "warm_start"};
// And the user's units it adds beside the outcome's own keys (add_user_units).
const std::vector<std::string> kUserUnitKeys = {"tof_hours", "departure_date_tdb", "arrival_mjd2000",
                                                "arrival_date_tdb"};

// solution.json before the run: the compile, and the keys the program's outcome replaces (the
// problem, the status, the seed and the counts) as they are for a program that did not run.
json record_before_run(const SolveOptions& o, const json& settings, const CompileResult& c) {
  json doc = io::artifact_header("solution", "helios-solve", o.backend);
  doc["problem"] = {{"id", "unknown"}};
  doc["status"] = "compile_failed";
  doc["compile"] = {{"ok", c.ok},
                    {"cached", c.cached},
                    {"source_sha256", c.sha256},
                    {"structure_sha256", c.structure_sha256},
                    {"command", c.command},
                    {"warnings", c.warnings},
                    {"diagnostics", c.diagnostics.substr(0, 8000)}};
  doc["compile"].update(cache_record(c));
  doc["sandbox"] = o.sandbox ? "bubblewrap" : "none";
  doc["seed"] = settings.value("seed", 1);
  doc["iterations"] = 0;
  doc["function_evaluations"] = 0;
  doc["settings"] = settings;
  return doc;
}

// Why a run left no outcome: the wall-clock kill, or its exit code and signal, and the processes
// it left behind.
std::string run_failure(const RunResult& run, double time_limit_s) {
  std::string detail = run.timed_out ? "killed after " + io::limit_text(time_limit_s) + " s wall clock"
                                     : "exit code " + std::to_string(run.exit_code) + ", signal " +
                                           std::to_string(run.signal) + ": " + io::printable_line(run.error_line);
  if (run.leftover_processes > 0)
    detail += "; killed " + std::to_string(run.leftover_processes) + " leftover processes";
  return detail;
}

// The outcome the program wrote: an object of solution.json's keys, none of them helios-solve's.
json read_outcome(const std::string& path) {
  const json outcome = io::parse_json_text(io::read_program_file(path), path);
  if (!outcome.is_object()) throw std::runtime_error(path + ": the program's outcome is not a JSON object");
  static const std::vector<std::string> known = io::schema_properties("solution");
  for (auto it = outcome.begin(); it != outcome.end(); ++it)
    if (std::find(known.begin(), known.end(), it.key()) == known.end() ||
        std::find(kSolveKeys.begin(), kSolveKeys.end(), it.key()) != kSolveKeys.end() ||
        std::find(kUserUnitKeys.begin(), kUserUnitKeys.end(), it.key()) != kUserUnitKeys.end())
      throw std::runtime_error(path + ": field /" + it.key() + " is not a key of the program's outcome");
  return outcome;
}

// Whether process `pid` still runs. A zombie does not: a killed helios-solve whose parent died too
// stays one until an init that reaps slowly (some containers' never does) collects it, and kill(pid,
// 0) still finds it.
bool process_running(pid_t pid) {
  if (::kill(pid, 0) != 0 && errno == ESRCH) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return !fs::exists("/proc/self/stat");  // without /proc, kill's answer
  // "pid (comm) S ...": the state follows the last ')', as comm may hold one.
  const auto close = line.rfind(')');
  if (close == std::string::npos || close + 2 >= line.size()) return true;
  const char state = line[close + 2];
  return state != 'Z' && state != 'X';
}

// The outcome merged into `doc` and checked against solution.json's schema; "" when usable, else
// why not (the program's result is data: a malformed one makes the run crashed, not helios-solve).
std::string merge_outcome(json& doc, const std::string& outcome_path, const std::string& source_path) {
  try {
    json merged = doc;
    merged.update(read_outcome(outcome_path));
    io::validate("solution", merged, "the outcome of " + source_path);
    doc = std::move(merged);
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

// The private folder of one run, beside the trajectory, and the only folder the sandboxed program
// may write: it holds the settings and parameters the program reads and the outcome and trajectory
// it writes, so nothing the program leaves (a link, a FIFO) lands where helios-solve writes its own
// files. The folder goes, with whatever is in it, when this does.
struct RunFolder {
  explicit RunFolder(const fs::path& dir)
      : path(create(dir)),
        settings((fs::path(path) / "settings.json").string()),
        parameters((fs::path(path) / "parameters.json").string()),
        outcome((fs::path(path) / "outcome.json").string()),
        trajectory((fs::path(path) / "trajectory.csv").string()) {}
  ~RunFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;
  static std::string create(const fs::path& dir) {
    std::string name = fs::absolute(dir.empty() ? fs::path(".") : dir).lexically_normal().string();
    name += "/.run." + std::to_string(::getpid()) + ".XXXXXX";
    if (::mkdtemp(name.data()) == nullptr)
      throw std::runtime_error(name + ": cannot create the run's private folder: " + std::strerror(errno));
    return name;
  }
  const std::string path, settings, parameters, outcome, trajectory;
};

}  // namespace

// A SIGKILL, or a SIGTERM to helios-solve, leaves its folder with whatever the program wrote.
void remove_stale_run_folders(const std::string& dir) {
  static const std::regex run_folder(R"(\.run\.([0-9]{1,9})\.[A-Za-z0-9]{6})");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, m, run_folder) || !entry.is_directory(ec) || entry.is_symlink(ec)) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(m[1].str()));
    if (pid != ::getpid() && !process_running(pid)) fs::remove_all(entry.path(), ec);
  }
}

json warm_start_of(const std::string& path, json& record) {
  const json neighbour = io::read_json(path);
  const std::string status = neighbour.is_object() ? neighbour.value("status", "") : "";
  if (status.empty()) throw input_error(path + ": field /status: missing (not a solution.json)");
  record = {{"from", path}, {"neighbour_status", status}, {"used", false}};
  if (status != "converged") return nullptr;
  const json* x = neighbour.contains("x") ? &neighbour.at("x") : nullptr;
  if (x == nullptr || !x->is_array() || x->empty())
    throw input_error(path + ": field /x: a converged solution without its shooting variables");
  json names = json::array(), values = json::array();
  for (std::size_t i = 0; i < x->size(); ++i) {
    const json& v = (*x)[i];
    if (!v.is_object() || !v.contains("name") || !v.at("name").is_string() || !v.contains("value") ||
        !v.at("value").is_number())
      throw input_error(path + ": field /x/" + std::to_string(i) + ": not a {name, value} pair");
    names.push_back(v.at("name"));
    values.push_back(v.at("value"));
  }
  record["used"] = true;
  return {{"variables", names}, {"x", values}};
}

std::string add_user_units(json& doc) {
  std::string line;
  if (const auto tof = doc.find("tof_days"); tof != doc.end() && tof->is_number()) {
    const double days = tof->get<double>();
    if (std::fabs(days) < astro::kHoursBelowDays) doc["tof_hours"] = days * 24;
    line = "time of flight " + astro::duration_text(days, 4);
    if (const auto dep = doc.find("departure_mjd2000"); dep != doc.end() && dep->is_number()) {
      const double departure = dep->get<double>(), arrival = departure + days;
      doc["departure_date_tdb"] = astro::iso_date_tdb(departure);
      doc["arrival_mjd2000"] = arrival;
      doc["arrival_date_tdb"] = astro::iso_date_tdb(arrival);
      line += ", departure " + doc["departure_date_tdb"].get<std::string>() + " TDB (MJD2000 " +
              io::short_number(departure) + "), arrival " + doc["arrival_date_tdb"].get<std::string>() +
              " TDB (MJD2000 " + io::short_number(arrival) + ")";
    }
  }
  // What the flight cost: the final mass and the propellant, or at a constant mass the delta-v.
  const auto number = [&](const char* key) {
    const auto it = doc.find(key);
    return it != doc.end() && it->is_number() ? std::optional<double>(it->get<double>()) : std::nullopt;
  };
  const auto sig = [](double v) { return io::significant(v, 6); };
  const auto final_mass = number("final_mass_kg"), initial_mass = number("initial_mass_kg");
  const auto propellant = number("propellant_kg"), delta_v = number("delta_v_m_s");
  std::string cost;
  if (final_mass && propellant)
    cost = "final mass " + sig(*final_mass) + " kg (propellant " + sig(*propellant) + " kg)";
  else if (delta_v && final_mass && initial_mass && *final_mass == *initial_mass)
    cost = "delta-v " + sig(*delta_v) + " m/s at a constant mass of " + sig(*final_mass) + " kg";
  if (!cost.empty()) line += (line.empty() ? "" : ", ") + cost;
  return line;
}

namespace {

// What the problem asks, in its own units: the departure (or its window) as calendar dates and the
// flight's bounds in hours or days; "" without a spec.
std::string problem_line(const json& spec) {
  const json& t = spec.value("time", json::object());
  if (!t.is_object()) return "";
  std::string line = "problem " + spec.value("problem", json::object()).value("id", std::string("?")) + ":";
  const bool has_epoch = t.contains("epoch_mjd2000") && t.at("epoch_mjd2000").is_number();
  const double epoch = has_epoch ? t.at("epoch_mjd2000").get<double>() : 0;
  const json& window = t.value("t0_window_days", json());
  if (has_epoch && window.is_array() && window.size() == 2 && window[0].is_number() && window[1].is_number())
    line += " departure free between " + astro::iso_date_tdb(epoch + window[0].get<double>()) + " and " +
            astro::iso_date_tdb(epoch + window[1].get<double>()) + " TDB;";
  else if (has_epoch)
    line += " departure " + astro::iso_date_tdb(epoch + t.value("t0_days", 0.0)) + " TDB;";
  if (t.contains("tof_days") && t.at("tof_days").is_number())
    line += " time of flight " + astro::duration_text(t.at("tof_days").get<double>());
  else if (t.contains("tof_max_days") && t.at("tof_max_days").is_number())
    line += " time of flight free, at most " + astro::duration_text(t.at("tof_max_days").get<double>());
  else
    line += " time of flight free";
  return line;
}

// The folder of the run's private folder when no trajectory is kept: the system's temporary one.
fs::path scratch_dir() {
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  return ec ? fs::path("/tmp") : tmp;
}

}  // namespace

json solve(const SolveOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::string source = io::read_text(o.source_path);
  std::optional<json> spec;
  if (!o.spec_path.empty()) spec = io::read_artifact("spec", o.spec_path);
  if (o.progress && spec)
    if (const std::string line = problem_line(*spec); !line.empty()) o.progress(line);
  const json settings = run_settings(o);
  json warm_record;
  const json warm = o.warm_start_path.empty() ? json(nullptr) : warm_start_of(o.warm_start_path, warm_record);
  if (o.warm_only && warm.is_null())
    throw input_error(
        o.warm_start_path + ": field /status: " +
        (warm_record.is_null() ? std::string("no warm start") : warm_record.value("neighbour_status", "")) +
        ": --warm-only needs a converged neighbour");
  const CompileResult c = compile_cached(source, o);
  json doc = record_before_run(o, settings, c);
  if (!warm_record.is_null()) doc["warm_start"] = warm_record;
  doc["timings"] = {{"compile_s", c.seconds}, {"run_s", 0.0}, {"total_s", io::seconds_since(start)}};
  if (!c.ok) return doc;
  if (o.progress)
    o.progress(c.cached ? "compiled program from the cache" : "compiled in " + io::limit_text(c.seconds) + " s");

  // The private folder beside the trajectory (its rename into place stays on one file system), or
  // in the temporary folder when none is kept: never in the working directory unless told.
  const bool keep_trajectory = !o.trajectory_path.empty();
  const fs::path out_dir = keep_trajectory ? fs::path(o.trajectory_path).parent_path() : scratch_dir();
  if (keep_trajectory) remove_stale_run_folders(out_dir.string());
  const RunFolder files(out_dir);
  // The program reads the warm start beside its settings; solution.json's settings stay the user's.
  json program_settings = settings;
  if (!warm.is_null()) {
    program_settings["warm_start"] = warm;
    if (o.warm_only) program_settings["warm_start"]["only"] = true;
  }
  io::write_json_atomic(files.settings, program_settings);
  // The program checked against its stored hash, copied where only this run can change it.
  const std::string binary = (fs::path(files.path) / "shoot").string();
  install_program(c, binary);
  std::vector<std::string> program = {binary,        "--settings",   files.settings,  "--outcome",
                                      files.outcome, "--trajectory", files.trajectory};
  // This source's numbers: the cached program may have been compiled from another problem's.
  if (c.parameters.readable) {
    io::write_json_atomic(files.parameters, parameters_document(c.parameters.values));
    program.insert(program.end(), {"--parameters", files.parameters});
  }
  const RunResult run = run_limited(o.sandbox ? sandboxed(program, files.path) : program, o.time_limit_s,
                                    o.memory_limit_mb, files.path, o.progress);
  doc["timings"]["run_s"] = run.seconds;
  if (run.timed_out || run.exit_code != 0 || !fs::exists(files.outcome)) {
    doc["status"] = run.timed_out ? "timeout" : "crashed";
    doc["status_detail"] = run_failure(run, o.time_limit_s);
    doc["timings"]["total_s"] = io::seconds_since(start);
    return doc;
  }
  if (const std::string why = merge_outcome(doc, files.outcome, o.source_path); !why.empty()) {
    doc["status"] = "crashed";
    doc["status_detail"] = "the program's outcome is unusable: " + io::printable_line(why);
    doc["timings"]["total_s"] = io::seconds_since(start);
    return doc;
  }
  if (!warm_record.is_null() && !warm_record.at("used").get<bool>())
    doc["start_detail"] = "the neighbour " + o.warm_start_path + " did not converge (" +
                          warm_record.at("neighbour_status").get<std::string>() + "): the search started cold";
  if (doc.at("status") == "converged" && !io::is_program_file(files.trajectory)) {
    doc["status"] = "crashed";
    doc["status_detail"] = "the program's trajectory is missing or not a regular file";
  }
  if (doc.at("status") == "converged") {
    doc["files"] = json::object();
    if (keep_trajectory) doc["files"]["trajectory"] = fs::path(o.trajectory_path).filename().string();
    // Plotted from the run's own copy: the trajectory's path may be a stream (/dev/null, a FIFO).
    if (!o.plot_prefix.empty())
      doc["files"].update(plot_trajectory(files.trajectory, o.plot_prefix, doc["problem"]["id"].get<std::string>(),
                                          spec ? &*spec : nullptr));
    if (keep_trajectory) io::move_into_place(files.trajectory, o.trajectory_path);
  }
  if (doc.contains("tof_days")) {
    const std::string line = add_user_units(doc);
    if (o.progress && !line.empty()) o.progress(doc.at("status").get<std::string>() + ": " + line);
  }
  doc["timings"]["total_s"] = io::seconds_since(start);
  return doc;
}

}  // namespace helios::solve

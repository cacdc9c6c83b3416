// The solve stage: validated settings, the compile, the sandboxed run, and the solution record
// (solution.json) from the program's result.
#include "helios/solve/solve.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/solve/process.hpp"

namespace helios::solve {

namespace fs = std::filesystem;
using io::json;

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
  const RunResult run = run_limited(
      {fs::absolute(c.binary).string(), "--settings", fs::absolute(settings_tmp).string(), "--result",
       fs::absolute(result_tmp).string(), "--trajectory", fs::absolute(traj_tmp).string()},
      o.time_limit_s, o.memory_limit_mb, fs::absolute(out_dir.empty() ? fs::path(".") : out_dir).string(), o.progress);
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
      json step = {{"stage", c.at("stage")},
                   {"value", c.at("value")},
                   {"converged", c.at("converged")},
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

// A sweep's neighbour cross-check (helios/sweep/sweep.hpp): each cell re-solved warm from each
// converged neighbour's answer, the best kept, until no cell improves. A cell's first-pass answer
// comes from one chain (or one cold search); its neighbours' extremals are other candidates, and
// a sweep's answer should never be worse than a neighbour's continuation reaches.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/process.hpp"
#include "helios/sweep/sweep.hpp"

namespace helios::sweep {

namespace fs = std::filesystem;
using io::json;

namespace {

// Rounds of the cross-check at most (each round offers the cells improved by the one before).
constexpr int kMaxRounds = 20;
// Two objectives closer than this (relative) are one extremal; an answer must beat another by more.
constexpr double kSameObjective = 1e-9;

struct Answer {
  std::string file;  // relative to the sweep folder
  double objective = NAN;
  std::string from;  // "own" or the neighbour cell whose answer continued to this one
  std::vector<double> extremals;
  json tried = json::array();
};

bool same(double a, double b) {
  return std::fabs(a - b) <= kSameObjective * std::max(std::fabs(a), std::fabs(b));
}

// `a` beats `b` (NaN: none) for the plotted objective.
bool beats(const SweepGrid& grid, double a, double b) {
  if (!std::isfinite(a)) return false;
  if (!std::isfinite(b)) return true;
  if (same(a, b)) return false;
  return grid.plot == "final_mass_kg" ? a > b : a < b;
}

void note_extremal(Answer& a, double objective) {
  for (const double e : a.extremals)
    if (same(e, objective)) return;
  a.extremals.push_back(objective);
}

// The objective of a converged solution file, else NaN.
double objective_of(const SweepGrid& grid, const fs::path& path, std::string* status = nullptr) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (status) *status = "missing";
    return NAN;
  }
  const json s = io::read_json(path.string());
  if (status) *status = s.value("status", "unknown");
  if (s.value("status", "") != "converged") return NAN;
  if (!s.contains(grid.plot) || !s.at(grid.plot).is_number())
    throw input_error(path.string() + ": field /" + grid.plot + ": missing in a converged solution");
  return s.at(grid.plot).get<double>();
}

// A try's run on disk is reusable when it started from the same neighbour answer, after it was written.
bool reusable(const fs::path& candidate, const fs::path& warm_from) {
  std::error_code ec;
  if (!fs::exists(candidate, ec)) return false;
  const json s = io::read_json(candidate.string());
  if (!s.contains("warm_start") || s.at("warm_start").value("from", "") != warm_from.string()) return false;
  return fs::last_write_time(candidate, ec) >= fs::last_write_time(warm_from, ec);
}

}  // namespace

json crosscheck(const SweepGrid& grid, const std::string& dir, const CrosscheckOptions& o) {
  const std::size_t nd = grid.departures_mjd2000.size(), nt = grid.tofs_days.size();
  std::vector<std::string> names(nd * nt);
  std::vector<bool> solvable(nd * nt, false);
  std::vector<Answer> answers(nd * nt);
  std::set<std::size_t> offered;
  for (std::size_t i = 0; i < nd; ++i) {
    const Boundary b = read_boundary(grid, dir, grid.departures_mjd2000[i]);
    for (std::size_t j = 0; j < nt; ++j) {
      const std::size_t k = i * nt + j;
      names[k] = cell_name(grid.departures_mjd2000[i], grid.tofs_days[j]);
      std::error_code ec;
      solvable[k] = !below_boundary(b, grid.tofs_days[j]) && fs::exists(fs::path(dir) / names[k] / "shoot.cpp", ec);
      if (!solvable[k]) continue;
      Answer& a = answers[k];
      a.file = names[k] + "/solution.json";
      a.objective = objective_of(grid, fs::path(dir) / a.file);
      if (std::isfinite(a.objective)) {
        a.from = "own";
        note_extremal(a, a.objective);
        offered.insert(k);
      }
    }
  }
  int rounds = 0, runs = 0, reused = 0;
  double run_s = 0;
  std::set<std::string> improved_cells;
  while (!offered.empty() && rounds < kMaxRounds) {
    ++rounds;
    struct Try {
      std::size_t cell, from;
      fs::path warm_from, candidate;
    };
    std::vector<Try> tries;
    for (const std::size_t n : offered) {
      const std::size_t i = n / nt, j = n % nt;
      std::vector<std::size_t> around;
      if (i > 0) around.push_back(n - nt);
      if (i + 1 < nd) around.push_back(n + nt);
      if (j > 0) around.push_back(n - 1);
      if (j + 1 < nt) around.push_back(n + 1);
      for (const std::size_t k : around)
        if (solvable[k])
          tries.push_back({k, n, fs::path(dir) / answers[n].file,
                           fs::path(dir) / names[k] / "crosscheck" /
                               ("r" + std::to_string(rounds) + "_from_" + names[n]) / "solution.json"});
    }
    std::vector<std::vector<std::string>> commands;
    std::vector<std::size_t> commanded;
    for (std::size_t t = 0; t < tries.size(); ++t) {
      if (reusable(tries[t].candidate, tries[t].warm_from)) {
        ++reused;
        continue;
      }
      fs::create_directories(tries[t].candidate.parent_path());
      std::vector<std::string> argv = o.launch;
      for (const std::string& w :
           {o.solver, (fs::path(dir) / names[tries[t].cell] / "shoot.cpp").string(), std::string("--backend"),
            std::string("builtin"), std::string("--settings"), o.settings, std::string("--cache-dir"), o.cache_dir,
            std::string("--time-limit"), io::limit_text(o.time_limit_s), std::string("--quiet"),
            std::string("--warm-start"), tries[t].warm_from.string(), std::string("--warm-only"),
            std::string("--trajectory"), (tries[t].candidate.parent_path() / "trajectory.csv").string(),
            std::string("-o"), tries[t].candidate.string()})
        argv.push_back(w);
      commands.push_back(argv);
      commanded.push_back(t);
    }
    std::vector<int> codes;
    try {
      codes = io::run_all(commands, o.jobs);
    } catch (const std::runtime_error&) {
      throw std::runtime_error("cross-check: cannot start a solve (fork failed)");
    }
    for (std::size_t c = 0; c < codes.size(); ++c)
      if (codes[c] != 0)
        throw std::runtime_error("cross-check: helios-solve exited with " + std::to_string(codes[c]) + " on " +
                                 names[tries[commanded[c]].cell] + " from " + names[tries[commanded[c]].from]);
    runs += static_cast<int>(commands.size());
    std::set<std::size_t> improved;
    for (const Try& t : tries) {
      std::string status;
      const double objective = objective_of(grid, t.candidate, &status);
      const json s = io::read_json(t.candidate.string());
      if (s.contains("timings")) run_s += s.at("timings").value("run_s", 0.0);
      Answer& a = answers[t.cell];
      json tried = {{"from", names[t.from]}, {"round", rounds}, {"status", status}};
      if (std::isfinite(objective)) {
        tried[grid.plot] = objective;
        note_extremal(a, objective);
      }
      a.tried.push_back(tried);
      if (beats(grid, objective, a.objective)) {
        a.objective = objective;
        a.file = fs::relative(t.candidate, dir).string();
        a.from = names[t.from];
        improved.insert(t.cell);
        improved_cells.insert(names[t.cell]);
      }
    }
    offered = improved;
  }
  json cells = json::object();
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!solvable[k]) continue;
    const Answer& a = answers[k];
    cells[names[k]] = {{"answer", a.file},
                       {"answer_from", a.from},
                       {"extremals_compared", a.extremals.size()},
                       {"tried", a.tried}};
    if (std::isfinite(a.objective)) cells[names[k]][grid.plot] = a.objective;
  }
  return {{"schema", "helios/sweep-crosscheck"},
          {"rounds", rounds},
          {"saturated", offered.empty()},
          {"runs", runs},
          {"reused", reused},
          {"run_s", run_s},
          {"improved", json(std::vector<std::string>(improved_cells.begin(), improved_cells.end()))},
          {"cells", cells}};
}

}  // namespace helios::sweep

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

// One try: a cell re-solved warm from a neighbour's answer, into its candidate solution file.
struct Try {
  std::size_t cell, from;
  fs::path warm_from, candidate;
};

// The cross-check's state over the grid: each cell's name, whether it is solved at all, its best
// answer so far, and the figures of the runs.
class Crosscheck {
 public:
  Crosscheck(const SweepGrid& grid, const std::string& dir, const CrosscheckOptions& o)
      : grid_(grid),
        dir_(dir),
        o_(o),
        nd_(grid.departures_mjd2000.size()),
        nt_(grid.tofs_days.size()),
        names_(nd_ * nt_),
        solvable_(nd_ * nt_, false),
        answers_(nd_ * nt_) {}

  json run() {
    std::set<std::size_t> offered = first_answers();
    while (!offered.empty() && rounds_ < kMaxRounds) {
      ++rounds_;
      const std::vector<Try> tries = tries_from(offered);
      solve(tries);
      offered = take(tries);
    }
    return record(offered.empty());
  }

 private:
  // Every cell's name and first-pass answer; returns the cells with a converged one.
  std::set<std::size_t> first_answers() {
    std::set<std::size_t> offered;
    for (std::size_t i = 0; i < nd_; ++i) {
      const Boundary b = read_boundary(grid_, dir_, grid_.departures_mjd2000[i]);
      for (std::size_t j = 0; j < nt_; ++j) {
        const std::size_t k = i * nt_ + j;
        names_[k] = cell_name(grid_.departures_mjd2000[i], grid_.tofs_days[j]);
        std::error_code ec;
        solvable_[k] =
            !below_boundary(b, grid_.tofs_days[j]) && fs::exists(fs::path(dir_) / names_[k] / "shoot.cpp", ec);
        if (!solvable_[k]) continue;
        Answer& a = answers_[k];
        a.file = names_[k] + "/solution.json";
        a.objective = objective_of(grid_, fs::path(dir_) / a.file);
        if (std::isfinite(a.objective)) {
          a.from = "own";
          note_extremal(a, a.objective);
          offered.insert(k);
        }
      }
    }
    return offered;
  }

  // This round's tries: each offered cell's answer to each solvable 4-neighbour.
  std::vector<Try> tries_from(const std::set<std::size_t>& offered) const {
    std::vector<Try> tries;
    for (const std::size_t n : offered) {
      const std::size_t i = n / nt_, j = n % nt_;
      std::vector<std::size_t> around;
      if (i > 0) around.push_back(n - nt_);
      if (i + 1 < nd_) around.push_back(n + nt_);
      if (j > 0) around.push_back(n - 1);
      if (j + 1 < nt_) around.push_back(n + 1);
      for (const std::size_t k : around)
        if (solvable_[k])
          tries.push_back({k, n, fs::path(dir_) / answers_[n].file,
                           fs::path(dir_) / names_[k] / "crosscheck" /
                               ("r" + std::to_string(rounds_) + "_from_" + names_[n]) / "solution.json"});
    }
    return tries;
  }

  // helios-solve's command of a try: the warm solve alone, no search.
  std::vector<std::string> command(const Try& t) const {
    std::vector<std::string> argv = o_.launch;
    for (const std::string& w :
         {o_.solver, (fs::path(dir_) / names_[t.cell] / "shoot.cpp").string(), std::string("--backend"),
          std::string("builtin"), std::string("--settings"), o_.settings, std::string("--cache-dir"), o_.cache_dir,
          std::string("--time-limit"), io::limit_text(o_.time_limit_s), std::string("--quiet"),
          std::string("--warm-start"), t.warm_from.string(), std::string("--warm-only"), std::string("--trajectory"),
          (t.candidate.parent_path() / "trajectory.csv").string(), std::string("-o"), t.candidate.string()})
      argv.push_back(w);
    return argv;
  }

  // Runs the tries not already on disk, o.jobs at a time; throws when a solve fails to run.
  void solve(const std::vector<Try>& tries) {
    std::vector<std::vector<std::string>> commands;
    std::vector<std::size_t> commanded;
    for (std::size_t t = 0; t < tries.size(); ++t) {
      if (reusable(tries[t].candidate, tries[t].warm_from)) {
        ++reused_;
        continue;
      }
      fs::create_directories(tries[t].candidate.parent_path());
      commands.push_back(command(tries[t]));
      commanded.push_back(t);
    }
    std::vector<int> codes;
    try {
      codes = io::run_all(commands, o_.jobs);
    } catch (const std::runtime_error&) {
      throw std::runtime_error("cross-check: cannot start a solve (fork failed)");
    }
    for (std::size_t c = 0; c < codes.size(); ++c)
      if (codes[c] != kExitOk && codes[c] != kExitInfeasible)
        throw std::runtime_error("cross-check: helios-solve exited with " + std::to_string(codes[c]) + " on " +
                                 names_[tries[commanded[c]].cell] + " from " + names_[tries[commanded[c]].from]);
    runs_ += static_cast<int>(commands.size());
  }

  // Each try's result noted on its cell, the better answers kept; returns the cells improved.
  std::set<std::size_t> take(const std::vector<Try>& tries) {
    std::set<std::size_t> improved;
    for (const Try& t : tries) {
      std::string status;
      const double objective = objective_of(grid_, t.candidate, &status);
      const json s = io::read_json(t.candidate.string());
      if (s.contains("timings")) run_s_ += s.at("timings").value("run_s", 0.0);
      Answer& a = answers_[t.cell];
      json tried = {{"from", names_[t.from]}, {"round", rounds_}, {"status", status}};
      if (std::isfinite(objective)) {
        tried[grid_.plot] = objective;
        note_extremal(a, objective);
      }
      a.tried.push_back(tried);
      if (beats(grid_, objective, a.objective)) {
        a.objective = objective;
        a.file = fs::relative(t.candidate, dir_).string();
        a.from = names_[t.from];
        improved.insert(t.cell);
        improved_cells_.insert(names_[t.cell]);
      }
    }
    return improved;
  }

  json record(bool saturated) const {
    json cells = json::object();
    for (std::size_t k = 0; k < names_.size(); ++k) {
      if (!solvable_[k]) continue;
      const Answer& a = answers_[k];
      cells[names_[k]] = {
          {"answer", a.file}, {"answer_from", a.from}, {"extremals_compared", a.extremals.size()}, {"tried", a.tried}};
      if (std::isfinite(a.objective)) cells[names_[k]][grid_.plot] = a.objective;
    }
    return {{"schema", "helios/sweep-crosscheck"},
            {"rounds", rounds_},
            {"saturated", saturated},
            {"runs", runs_},
            {"reused", reused_},
            {"run_s", run_s_},
            {"improved", json(std::vector<std::string>(improved_cells_.begin(), improved_cells_.end()))},
            {"cells", cells}};
  }

  const SweepGrid& grid_;
  const std::string& dir_;
  const CrosscheckOptions& o_;
  const std::size_t nd_, nt_;
  std::vector<std::string> names_;
  std::vector<bool> solvable_;
  std::vector<Answer> answers_;
  std::set<std::string> improved_cells_;
  int rounds_ = 0, runs_ = 0, reused_ = 0;
  double run_s_ = 0;
};

}  // namespace

json crosscheck(const SweepGrid& grid, const std::string& dir, const CrosscheckOptions& o) {
  return Crosscheck(grid, dir, o).run();
}

}  // namespace helios::sweep

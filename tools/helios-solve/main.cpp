// helios-solve: shoot.cpp -> solution.json (+ trajectory.csv and plots).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/solve/solve.hpp"

namespace {

// trajectory.csv beside the solution: in -o's folder, or none when -o is stdout or a stream
// (/dev/null, a FIFO): the working directory only when it is -o's folder.
std::string default_trajectory(const std::string& output) {
  if (output.empty() || output == "-") return "";
  std::error_code ec;
  const auto status = std::filesystem::status(output, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return "";
  return (std::filesystem::path(output).parent_path() / "trajectory.csv").string();
}

// The user's cache folder (XDG), or one of this user's in the temporary folder without a home.
std::string default_cache_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && *xdg == '/') return std::string(xdg) + "/helios";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home == '/') return std::string(home) + "/.cache/helios";
  return "/tmp/helios-cache-" + std::to_string(::getuid());
}

}  // namespace

int main(int argc, char** argv) {
  const helios::cli::ToolInfo info{
      "helios-solve",
      "compile and run a shooting program, and collect its solution, trajectory and plots",
      "[options] SHOOT.cpp|-",
      {{"settings", "", "FILE", "solver settings JSON (seed, tolerances, homotopy, limits)", ""},
       {"trajectory", "", "FILE",
        "trajectory CSV to write (t, r, v, m, lambda, u, H, S); default: trajectory.csv in -o's folder (none for "
        "-o - or a stream)",
        ""},
       {"plots", "", "PREFIX", "write PREFIXtrajectory.png and PREFIXthrottle_mass.png; empty: no plots", ""},
       {"spec", "", "FILE",
        "the problem's spec.json: the plots' central body, orbits and thrust, and the progress lines' dates", ""},
       {"cache-dir", "", "DIR",
        "compiled programs by content hash (default: $XDG_CACHE_HOME/helios or ~/.cache/helios)", ""},
       {"time-limit", "", "SECONDS", "wall-clock limit of the run, a safety net (the search stops on its own rules)",
        "3600"},
       {"memory-limit", "", "MB", "address-space limit of the run", "4096"},
       {"warm-start", "", "FILE",
        "a neighbour's solution.json: its shooting variables are the first guess (a sweep's cell)", ""},
       {"warm-only", "", "", "with --warm-start: no search when the warm solve fails (a sweep's cross-check)", ""},
       {"backend", "", "NAME", "backend label recorded in the solution (builtin or llm)", "builtin"},
       {"compile-only", "", "", "only compile (into the cache) and write a compile report instead", ""},
       {"quiet", "", "", "no progress lines on stderr", ""},
       {"no-sandbox", "", "", "compile and run the program without bubblewrap (recorded in solution.json)", ""}},
      {"SHOOT"},
      "Compiles with g++ -O2 against the prebuilt runtime beside this tool (../lib, ../include;\n"
      "skipped when the cache holds the same source, compiler and runtime), runs the\n"
      "program in a child with CPU, memory, file-size and wall-clock limits, both inside bubblewrap\n"
      "(no network, read-only /usr; the only writable place is a private folder beside the\n"
      "trajectory, or in the temporary folder when none is kept, removed after the run), and writes\n"
      "solution.json. It writes nothing else than -o, --trajectory (by default beside -o), --plots and\n"
      "the cache: never into the working directory unless that is -o's folder. What the program prints\n"
      "goes to stderr as progress, never to stdout.\n"
      "A failed compile or run is recorded in the artifact's status; the tool still exits 0. A problem\n"
      "shown infeasible (its bound below the minimum time the search found) exits 5, the artifact written.\n"
      "The run is a global search (many starts, the distinct extremals compared, the best kept); its\n"
      "progress goes to stderr, one line per stage or every few seconds (--quiet: none).\n"
      "With --compile-only it writes a compile report (schemas/compile.schema.json: ok, errors,\n"
      "diagnostics) for a gen <-> compile repair round; a failed compile still exits 0.",
      "helios-solve runs/builtin/S01/shoot.cpp --settings scenarios/S01/settings.json "
      "--spec runs/builtin/S01/spec.json --plots runs/builtin/S01/ -o runs/builtin/S01/solution.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    helios::solve::SolveOptions o;
    o.source_path = args.positionals[0];
    o.settings_path = args.get("settings");
    o.trajectory_path = args.has("trajectory") ? args.get("trajectory") : default_trajectory(args.output);
    o.plot_prefix = args.get("plots");
    o.spec_path = args.get("spec");
    o.cache_dir = args.has("cache-dir") ? helios::cli::folder_option(args, "cache-dir") : default_cache_dir();
    o.warm_start_path = args.get("warm-start");
    o.warm_only = args.has("warm-only");
    if (o.warm_only && o.warm_start_path.empty()) throw helios::input_error("--warm-only: needs --warm-start");
    o.backend = helios::cli::backend_option(args, {"builtin", "llm"});
    o.time_limit_s = helios::cli::positive_option(args, "time-limit");
    o.memory_limit_mb = helios::cli::positive_option(args, "memory-limit");
    o.sandbox = !args.has("no-sandbox");
    if (!args.has("quiet"))
      o.progress = [](const std::string& line) { std::fprintf(stderr, "helios-solve: %s\n", line.c_str()); };
    if (args.has("compile-only")) {
      helios::io::write_artifact("compile", helios::solve::compile_report(o), args.output);
      return 0;
    }
    const helios::io::json solution = helios::solve::solve(o);
    helios::io::write_artifact("solution", solution, args.output);
    return solution.value("status", "") == "infeasible" ? int{helios::kExitInfeasible} : int{helios::kExitOk};
  });
}

// helios-score: a run's artifacts + scenarios/SNN/reference.json -> score.json, or a folder of
// score.json files -> scoreboard.md, or a run -> report.md, or a converged run's trajectory ->
// trajectory.oem, or a launch-window sweep's cells and outcome. Each job is a helios::cli::Mode
// here; its work is in its library room: score, report, oem, sweep (tools/lib/src/<room>).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/oem/oem.hpp"
#include "helios/report/report.hpp"
#include "helios/score/score.hpp"
#include "helios/spec/parse.hpp"
#include "helios/sweep/sweep.hpp"
#include "helios/symbolic/expr.hpp"

namespace {

using helios::cli::Args;
namespace score = helios::score;

// The stage artifact of option `kind` (spec, verify, ...), if it was given.
std::optional<helios::io::json> optional_artifact(const Args& args, const char* kind) {
  if (!args.has(kind)) return std::nullopt;
  return helios::io::read_artifact(kind, args.get(kind));
}

// Scores `in` with the run's artifacts the arguments name, into -o's file.
int score_artifacts(const Args& args, score::ScoreInputs& in) {
  in.spec = optional_artifact(args, "spec");
  in.derivation = optional_artifact(args, "derivation");
  in.verify = optional_artifact(args, "verify");
  in.solution = optional_artifact(args, "solution");
  helios::io::write_artifact("score", score::score_run(in), args.output);
  return 0;
}

int score_run(const Args& args) {
  score::ScoreInputs in;
  in.reference_source = args.get("reference") == "-" ? "<stdin>" : args.get("reference");
  in.reference = helios::io::read_json(args.get("reference"));
  return score_artifacts(args, in);
}

// A run of a problem without a reference (a user's own folder): scored on what needs none.
int score_unreferenced(const Args& args) {
  score::ScoreInputs in;
  in.reference = nullptr;
  in.scenario = args.get("no-reference");
  static const std::regex name("[A-Za-z0-9_-]{1,64}");
  if (!std::regex_match(in.scenario, name))
    throw helios::usage_error("--no-reference " + in.scenario + ": a scenario name is A-Z a-z 0-9 _ - only");
  return score_artifacts(args, in);
}

int report(const Args& args) {
  helios::report::ReportInputs in;
  in.problem_text = helios::io::read_text(args.get("problem"));
  helios::spec::check_problem_text(in.problem_text, args.get("problem"));
  in.spec = helios::io::read_artifact("spec", args.get("spec"));
  in.derivation = helios::io::read_artifact("derivation", args.get("derivation"));
  in.derivation_source = args.get("derivation");
  in.verify = optional_artifact(args, "verify");
  in.solution = optional_artifact(args, "solution");
  std::string text;
  helios::cli::naming_input(args.get("derivation"), [&] { text = helios::report::report_markdown(in); });
  helios::io::write_text_atomic(args.output, text);
  return 0;
}

int oem(const Args& args) {
  const helios::io::json spec = helios::io::read_artifact("spec", args.get("spec"));
  const helios::io::json solution = helios::io::read_artifact("solution", args.get("solution"));
  if (solution.at("status") != "converged") {
    if (args.output != "-") std::remove(args.output.c_str());
    std::cerr << "helios-score: " << args.get("solution") << " is " << solution.at("status").get<std::string>()
              << ": no trajectory, no OEM written\n";
    return 0;
  }
  const helios::oem::OemSources sources{args.get("spec"), args.get("solution"), args.get("trajectory")};
  const auto text = helios::oem::oem_from_run(spec, solution, helios::io::read_text(args.get("trajectory")), sources);
  helios::io::write_text_atomic(args.output, *text);
  return 0;
}

helios::sweep::SweepGrid sweep_grid(const Args& args, const std::string& sweep_path) {
  return helios::sweep::read_sweep(helios::io::read_json(sweep_path), sweep_path, args.get("grid"));
}

int sweep_cells(const Args& args) {
  const std::string sweep_path = args.get("sweep-cells");
  const helios::sweep::SweepGrid grid = sweep_grid(args, sweep_path);
  const std::string template_path = (std::filesystem::path(sweep_path).parent_path() / grid.template_file).string();
  const std::string fragment =
      helios::sweep::write_sweep_cells(grid, helios::io::read_text(template_path), template_path, args.get("cells"));
  helios::io::write_text_atomic(args.output, fragment);
  return 0;
}

int sweep_boundary(const Args& args) {
  const std::string sweep_path = args.get("sweep-boundary");
  const helios::sweep::SweepGrid grid = sweep_grid(args, sweep_path);
  const std::string template_path = (std::filesystem::path(sweep_path).parent_path() / grid.template_file).string();
  const std::string fragment =
      helios::sweep::write_sweep_boundary(grid, helios::io::read_text(template_path), template_path,
                                          helios::io::read_json(args.get("settings")), args.get("cells"));
  helios::io::write_text_atomic(args.output, fragment);
  return 0;
}

int sweep_crosscheck(const Args& args) {
  const std::string sweep_path = args.get("sweep-crosscheck");
  helios::sweep::CrosscheckOptions o;
  o.solver = args.get("solver");
  o.settings = args.get("settings");
  o.cache_dir = helios::cli::folder_option(args, "cache-dir");
  std::istringstream launch(args.get("launch"));
  for (std::string word; launch >> word;) o.launch.push_back(word);
  o.time_limit_s = helios::cli::positive_option(args, "time-limit");
  o.jobs = static_cast<int>(helios::cli::positive_option(args, "jobs"));
  const auto doc = helios::sweep::crosscheck(sweep_grid(args, sweep_path), args.get("cells"), o);
  helios::io::write_text_atomic(args.output, doc.dump(2) + "\n");
  return 0;
}

int sweep(const Args& args) {
  const std::string sweep_path = args.get("sweep");
  const helios::sweep::SweepGrid grid = sweep_grid(args, sweep_path);
  const std::vector<helios::sweep::SweepRow> rows = helios::sweep::sweep_rows(
      grid, args.get("cells"),
      args.has("crosscheck") ? helios::io::read_json(args.get("crosscheck")) : helios::io::json(nullptr));
  if (args.has("porkchop"))
    helios::sweep::porkchop_png(grid, rows, args.get("porkchop"),
                                std::filesystem::path(sweep_path).parent_path().filename().string());
  helios::io::write_text_atomic(args.output, helios::sweep::sweep_csv(grid, rows));
  return 0;
}

// The tool's jobs: each names the options it needs and may take; any other is refused.
const std::vector<helios::cli::Mode>& jobs() {
  static const std::vector<helios::cli::Mode> modes = {
      {"", {"reference"}, {"spec", "derivation", "verify", "solution"}, score_run},
      {"no-reference", {}, {"spec", "derivation", "verify", "solution"}, score_unreferenced},
      {"report", {"problem", "spec", "derivation"}, {"verify", "solution"}, report},
      {"oem", {"spec", "solution", "trajectory"}, {}, oem},
      {"scoreboard",
       {},
       {},
       [](const Args& args) {
         helios::io::write_text_atomic(args.output, score::scoreboard_from_dir(args.get("scoreboard")));
         return 0;
       }},
      {"tables",
       {},
       {},
       [](const Args& args) {
         helios::io::write_text_atomic(args.output, score::tables_from_runs(args.get("tables")));
         return 0;
       }},
      {"sweep-cells", {"cells"}, {"grid"}, sweep_cells},
      {"sweep-boundary", {"cells", "settings"}, {"grid"}, sweep_boundary},
      {"sweep-crosscheck",
       {"cells", "settings", "cache-dir", "solver"},
       {"grid", "launch", "jobs", "time-limit"},
       sweep_crosscheck},
      {"sweep", {"cells"}, {"grid", "porkchop", "crosscheck"}, sweep},
  };
  return modes;
}

}  // namespace

int main(int argc, char** argv) {
  helios::symbolic::fix_expression_order(argv);
  const helios::cli::ToolInfo info{
      "helios-score",
      "score a run against its scenario reference, render a scoreboard, or export a trajectory as a CCSDS OEM",
      "--reference REF.json|--no-reference NAME [--spec F] [--derivation F] [--verify F] [--solution F] [options]\n"
      "       helios-score --scoreboard DIR [options]\n"
      "       helios-score --oem --spec F --solution F --trajectory F.csv [options]\n"
      "       helios-score --report --problem F.txt --spec F --derivation F [--verify F] [--solution F] [options]\n"
      "       helios-score --sweep-boundary SWEEP.json --cells DIR --settings F [--grid bench] -o DIR/boundary.mk\n"
      "       helios-score --sweep-cells SWEEP.json --cells DIR [--grid bench] -o DIR/cells.mk\n"
      "       helios-score --sweep-crosscheck SWEEP.json --cells DIR --settings F --cache-dir D --solver BIN\n"
      "                    [--launch WORDS] [--jobs N] [--time-limit S] [--grid bench] -o DIR/crosscheck.json\n"
      "       helios-score --sweep SWEEP.json --cells DIR [--crosscheck F] [--grid bench] [--porkchop F.png]\n"
      "                    -o DIR/sweep.csv",
      {{"reference", "", "FILE", "scenarios/SNN/reference.json to score against", ""},
       {"no-reference", "", "NAME",
        "score the run of scenario NAME without a reference: d1's facts and d5 say \"no reference\" (max 0)", ""},
       {"spec", "", "FILE", "spec.json of the run (omitted: d1 scores 0)", ""},
       {"derivation", "", "FILE", "derivation.json of the run (omitted: no shooting-variable points)", ""},
       {"verify", "", "FILE", "verify.json of the run (omitted: no verification points)", ""},
       {"solution", "", "FILE", "solution.json of the run (omitted: d3-d5 score 0)", ""},
       {"scoreboard", "", "DIR", "render DIR/*/score.json as a Markdown table instead", ""},
       {"tables", "", "ROOT", "render the paper's three tables from a runs tree ROOT/<backend>/<scenario>/", ""},
       {"oem", "", "", "write the run's trajectory as a CCSDS OEM 2.0 (KVN) instead", ""},
       {"trajectory", "", "FILE", "trajectory.csv of the run (with --oem)", ""},
       {"report", "", "", "write the run as report.md (the derivation as LaTeX mathematics) instead", ""},
       {"problem", "", "FILE", "problem.txt of the run (with --report)", ""},
       {"sweep-boundary", "", "FILE", "write each departure's minimum-time problem under --cells and its make fragment",
        ""},
       {"sweep-cells", "", "FILE",
        "write a sweep's feasible cells' problem texts under --cells and their make fragment", ""},
       {"sweep-crosscheck", "", "FILE", "re-solve each cell warm from its converged neighbours, keep the best", ""},
       {"settings", "", "FILE", "the sweep's solver settings (with --sweep-boundary, --sweep-crosscheck)", ""},
       {"cache-dir", "", "DIR", "compiled programs (with --sweep-crosscheck)", ""},
       {"solver", "", "FILE", "helios-solve (with --sweep-crosscheck)", ""},
       {"launch", "", "WORDS", "a prefix of each cross-check solve, e.g. \"srun -n1 -c1\"", ""},
       {"jobs", "", "N", "cross-check solves at a time", "2"},
       {"time-limit", "", "SECONDS", "wall-clock limit of one cross-check solve", "900"},
       {"crosscheck", "", "FILE", "crosscheck.json: each cell's best answer (with --sweep)", ""},
       {"sweep", "", "FILE", "write a sweep's sweep.csv (and --porkchop) from its cells' solution.json", ""},
       {"cells", "", "DIR", "the sweep's run folder, one sub-folder per cell (with the --sweep options)", ""},
       {"grid", "", "NAME", "a named grid of sweep.json (bench) instead of its top level", ""},
       {"porkchop", "", "FILE", "porkchop.png to draw with --sweep (gnuplot)", ""}},
      {},
      "Scores the paper's five-dimension rubric: d1 parse 30 (facts of the reference found in the\n"
      "spec within tolerance), d2 derive 20 (14 x fraction of verify checks passed, 6 for the\n"
      "expected shooting-variable count), d3 compile 20, d4 converge 20 (10 for status converged,\n"
      "10 for max_residual below the reference's), d5 accuracy 10 (full within tolerance_kg of the\n"
      "reference m_f, linearly down to 0 at 100 x tolerance_kg; converged runs only). Any stage\n"
      "input may be omitted; its dimensions then score 0. With --no-reference NAME (a problem of\n"
      "one's own), d1's facts, d2's variable count, d4's residual and d5 need a reference and say\n"
      "\"no reference\" with a maximum of 0: max_total is what was scored (44). With --scoreboard, writes one table "
      "row\n"
      "per scenario folder plus a totals row. With --tables, writes the per-scenario comparison of\n"
      "backends and models, the token consumption (from *.transcript.json) and the compile-repair\n"
      "loop effect (compile.r1.json before, the final compile after) over every run folder of ROOT.\n"
      "With --oem, writes the converged trajectory as a CCSDS OEM 2.0 in KVN form: one segment per\n"
      "arc between interior events, km and km/s, TDB epochs from the spec's epoch (or J2000.0 when it\n"
      "has none, said in a COMMENT), mass and throttle in COMMENT lines. A solution that did not\n"
      "converge has no trajectory: nothing is written (a stale -o FILE is removed) and the exit is 0.\n"
      "With --report, writes the run as Markdown: the problem, the spec with units, the derivation as\n"
      "LaTeX mathematics in a compact exact form, verify's verdict beside each condition, the solution\n"
      "and its plots (verify and solution may be omitted: a report before verifying or solving).\n"
      "With --sweep-boundary, writes DIR/b<epoch>/problem.txt and settings.json for each departure:\n"
      "the template's problem with its time of flight free and minimized (the feasibility boundary).\n"
      "With --sweep-cells, writes DIR/<cell>/problem.txt for every cell d<epoch>_t<tof> of the sweep\n"
      "not below its departure's boundary (the template beside SWEEP.json with @DEPARTURE_MJD2000@\n"
      "and @TOF_DAYS@ replaced; an unchanged text is not rewritten) and the make fragment of the\n"
      "chains. With --sweep-crosscheck, re-solves each cell warm from its converged neighbours' answers\n"
      "until no cell improves (tools/lib/src/sweep/README.md). With --sweep, writes sweep.csv (one\n"
      "row per cell) and with --porkchop the contour plot of the objective.",
      "helios-score --reference scenarios/S01/reference.json --spec runs/builtin/S01/spec.json "
      "--derivation runs/builtin/S01/derivation.json --verify runs/builtin/S01/verify.json "
      "--solution runs/builtin/S01/solution.json -o runs/builtin/S01/score.json"};
  return helios::cli::run_tool(
      info, argc, argv, [&info](const Args& args) { return helios::cli::select_mode(info, args, jobs()).run(args); });
}

// helios-score: a run's artifacts + scenarios/SNN/reference.json -> score.json, or a folder of
// score.json files -> scoreboard.md.
#include <optional>
#include <string>

#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/score/score.hpp"

int main(int argc, char** argv) {
  const helios::cli::ToolInfo info{
      "helios-score",
      "score a run against its scenario reference, or render a scoreboard",
      "--reference REF.json [--spec F] [--derivation F] [--verify F] [--solution F] [options]\n"
      "       helios-score --scoreboard DIR [options]",
      {{"reference", "", "FILE", "scenarios/SNN/reference.json to score against", ""},
       {"spec", "", "FILE", "spec.json of the run (omitted: d1 scores 0)", ""},
       {"derivation", "", "FILE", "derivation.json of the run (omitted: no shooting-variable points)", ""},
       {"verify", "", "FILE", "verify.json of the run (omitted: no verification points)", ""},
       {"solution", "", "FILE", "solution.json of the run (omitted: d3-d5 score 0)", ""},
       {"scoreboard", "", "DIR", "render DIR/*/score.json as a Markdown table instead", ""},
       {"tables", "", "ROOT", "render the paper's three tables from a runs tree ROOT/<backend>/<scenario>/", ""}},
      {},
      "Scores the paper's five-dimension rubric: d1 parse 30 (facts of the reference found in the\n"
      "spec within tolerance), d2 derive 20 (14 x fraction of verify checks passed, 6 for the\n"
      "expected shooting-variable count), d3 compile 20, d4 converge 20 (10 for status converged,\n"
      "10 for max_residual below the reference's), d5 accuracy 10 (full within tolerance_kg of the\n"
      "reference m_f, linearly down to 0 at 100 x tolerance_kg; converged runs only). Any stage\n"
      "input may be omitted; its dimensions then score 0. With --scoreboard, writes one table row\n"
      "per scenario folder plus a totals row. With --tables, writes the per-scenario comparison of\n"
      "backends and models, the token consumption (from *.transcript.json) and the compile-repair\n"
      "loop effect (compile.r1.json before, the final compile after) over every run folder of ROOT.",
      "helios-score --reference scenarios/S01/reference.json --spec runs/builtin/S01/spec.json "
      "--derivation runs/builtin/S01/derivation.json --verify runs/builtin/S01/verify.json "
      "--solution runs/builtin/S01/solution.json -o runs/builtin/S01/score.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    if (args.has("tables")) {
      for (const char* other : {"scoreboard", "reference", "spec", "derivation", "verify", "solution"})
        if (args.has(other))
          throw helios::usage_error(std::string("--tables takes no --") + other + ", see helios-score --help");
      helios::io::write_text_atomic(args.output, helios::score::tables_from_runs(args.get("tables")));
      return 0;
    }
    if (args.has("scoreboard")) {
      for (const char* stage : {"reference", "spec", "derivation", "verify", "solution"})
        if (args.has(stage))
          throw helios::usage_error(std::string("--scoreboard takes no --") + stage + ", see helios-score --help");
      helios::io::write_text_atomic(args.output, helios::score::scoreboard_from_dir(args.get("scoreboard")));
      return 0;
    }
    if (!args.has("reference"))
      throw helios::usage_error("missing --reference FILE (or --scoreboard DIR), see helios-score --help");
    helios::score::ScoreInputs in;
    in.reference_source = args.get("reference") == "-" ? "<stdin>" : args.get("reference");
    in.reference = helios::io::read_json(args.get("reference"));
    const auto stage = [&](const char* kind) -> std::optional<helios::io::json> {
      if (!args.has(kind)) return std::nullopt;
      return helios::io::read_artifact(kind, args.get(kind));
    };
    in.spec = stage("spec");
    in.derivation = stage("derivation");
    in.verify = stage("verify");
    in.solution = stage("solution");
    helios::io::write_artifact("score", helios::score::score_run(in), args.output);
    return 0;
  });
}

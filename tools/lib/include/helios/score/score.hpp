#pragma once
// helios-score: a run's artifacts scored against scenarios/SNN/reference.json on the paper's
// five-dimension rubric. This is the only code that reads a reference.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::score {

// Points of each dimension of the rubric.
constexpr double kParseMax = 30.0;
constexpr double kDeriveMax = 20.0;
constexpr double kDeriveVerifyMax = 14.0;    // scaled by the fraction of verify checks passed
constexpr double kDeriveVariablesMax = 6.0;  // shooting-variable count equals the reference's
constexpr double kCompileMax = 20.0;
constexpr double kConvergeMax = 20.0;
constexpr double kConvergeStatusMax = 10.0;
constexpr double kConvergeResidualMax = 10.0;
constexpr double kAccuracyMax = 10.0;
// NOTE: d5 falls linearly from full points at tolerance_kg to 0 at this multiple of it.
constexpr double kAccuracyZeroAt = 100.0;

// The already-read documents of one run. A stage that did not run (or whose artifact is
// missing) is std::nullopt and scores 0 on the dimensions that need it.
struct ScoreInputs {
  io::json reference;    // null: no reference (d1's facts and d5 say "no reference", their maxima 0)
  std::string scenario;  // the scenario's name when there is no reference (a reference names its own)
  std::string reference_source = "reference.json";  // names the file in errors
  std::optional<io::json> spec;
  std::optional<io::json> derivation;
  std::optional<io::json> verify;
  std::optional<io::json> solution;
};

// Checks the shape of a reference (schemas/reference.schema.json, enforced here because
// references are not embedded artifacts). Throws input_error "<source>: field /x: <why>".
void check_reference(const io::json& reference, const std::string& source);

// Scores one run and returns the score artifact (header included, schema-valid).
io::json score_run(const ScoreInputs& inputs);

// Renders score artifacts as a Markdown table: one row per scenario, then a totals row.
std::string render_scoreboard(const std::vector<io::json>& scores);

// Reads every DIR/*/score.json (sorted by folder name) and renders them, followed by the table of
// solutions where a solution.json stands beside a score.json. Throws input_error if DIR is not a
// folder or holds no score.json; a malformed score or solution is an error naming it.
std::string scoreboard_from_dir(const std::string& dir);
// The second table of the scoreboard: per run with a solution (solutions[k] beside scores[k]), its
// status, time of flight, propellant, the extremals its search compared, whether the search
// saturated, its starts and the solve's wall time.
std::string render_search_table(const std::vector<io::json>& scores,
                                const std::vector<std::optional<io::json>>& solutions);

// The paper's three tables from a runs tree ROOT/<run folder>/<scenario>/ (run folders such as
// builtin, llm, llm-<tag>): per-scenario comparison of backends and models (mean score, compiled
// and converged counts), token consumption from the transcripts (input, output, total, per
// scenario), and the compile-repair loop (compiled before and after repair). Runs are grouped by
// backend and model. Throws input_error if ROOT holds no scored run or a file in it is malformed.
std::string tables_from_runs(const std::string& root);

}  // namespace helios::score

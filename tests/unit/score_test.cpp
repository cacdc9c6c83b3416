#include "helios/score/score.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;
using helios::score::ScoreInputs;

const std::string kSource = HELIOS_SOURCE_DIR;

// The S01 spec and derivation, built once in-process by the builtin backend.
const json& s01_spec() {
  static const json spec = helios::spec::parse_problem_text(
      helios::io::read_text(kSource + "/scenarios/S01/problem.txt"), "scenarios/S01/problem.txt");
  return spec;
}

const json& s01_derivation() {
  static const json derivation = helios::pmp::derive_from_spec(s01_spec());
  return derivation;
}

json s01_reference() {
  return helios::io::read_json(kSource + "/scenarios/S01/reference.json");
}

json verify_doc(int passed, int total) {
  json checks = json::array();
  for (int i = 0; i < total; ++i)
    checks.push_back({{"id", "check_" + std::to_string(i)},
                      {"category", "costate"},
                      {"verdict", i < passed ? "pass" : "fail"},
                      {"feedback", i < passed ? "" : "wrong sign"}});
  return {{"schema", "helios/verify"},
          {"schema_version", 1},
          {"producer", {{"tool", "helios-verify"}, {"version", "0.1.0"}, {"backend", "builtin"}}},
          {"verdict", passed == total ? "pass" : "fail"},
          {"checks", checks},
          {"summary", {{"passed", passed}, {"failed", total - passed}, {"total", total}}}};
}

json solution_doc(double final_mass_kg, double max_residual = 2.5e-12) {
  return {{"schema", "helios/solution"},
          {"schema_version", 1},
          {"producer", {{"tool", "helios-solve"}, {"version", "0.1.0"}, {"backend", "builtin"}}},
          {"problem", {{"id", "S01"}}},
          {"status", "converged"},
          {"compile", {{"ok", true}, {"cached", false}, {"source_sha256", "0"}, {"command", "g++ shoot.cpp"}}},
          {"final_mass_kg", final_mass_kg},
          {"delta_v_m_s", 9900.0},
          {"max_residual", max_residual},
          {"x", json::array()},
          {"residuals", json::array()},
          {"epsilon", 0.0},
          {"seed", 1},
          {"iterations", 12},
          {"function_evaluations", 140},
          {"timings", {{"compile_s", 1.0}, {"run_s", 0.5}, {"total_s", 1.5}}}};
}

ScoreInputs perfect_inputs() {
  ScoreInputs in;
  in.reference = s01_reference();
  in.spec = s01_spec();
  in.derivation = s01_derivation();
  in.verify = verify_doc(20, 20);
  in.solution = solution_doc(603.935);
  return in;
}

double points(const json& score, const char* dim) {
  return score["dimensions"][dim]["points"].get<double>();
}

const json& fact_detail(const json& score, const std::string& id) {
  for (const json& d : score["dimensions"]["d1_parse"]["details"])
    if (d["id"] == id) return d;
  throw std::runtime_error("no d1 detail " + id);
}

TEST(Score, PerfectRunScoresFullMarks) {
  const json s = helios::score::score_run(perfect_inputs());
  EXPECT_EQ(s["schema"], "helios/score");
  EXPECT_EQ(s["scenario"], "S01");
  EXPECT_EQ(s["producer"]["backend"], "builtin");
  EXPECT_EQ(s["reference"]["provenance"], "published");
  EXPECT_DOUBLE_EQ(points(s, "d1_parse"), 30.0);
  EXPECT_DOUBLE_EQ(points(s, "d2_derive"), 20.0);
  EXPECT_DOUBLE_EQ(points(s, "d3_compile"), 20.0);
  EXPECT_DOUBLE_EQ(points(s, "d4_converge"), 20.0);
  EXPECT_DOUBLE_EQ(points(s, "d5_accuracy"), 10.0);
  EXPECT_DOUBLE_EQ(s["total"].get<double>(), 100.0);
  EXPECT_EQ(s["max_total"], 100);
  EXPECT_EQ(s["measured"]["shooting_variables"], 8);
  EXPECT_FALSE(s.contains("warnings"));
  for (const json& d : s["dimensions"]["d1_parse"]["details"]) EXPECT_EQ(d["verdict"], "pass") << d.dump();
}

// A problem of one's own has no reference: what needs one says "no reference" with no points of
// none, the rest is scored, and nothing fails.
TEST(Score, WithoutAReferenceTheReferenceItemsSayNoReference) {
  ScoreInputs in = perfect_inputs();
  in.reference = nullptr;
  in.scenario = "P4";
  const json s = helios::score::score_run(in);
  EXPECT_EQ(s["scenario"], "P4");
  EXPECT_TRUE(s["reference"].is_null());
  EXPECT_EQ(s["max_total"], 44);
  EXPECT_DOUBLE_EQ(s["total"].get<double>(), 44.0);
  for (const char* dim : {"d1_parse", "d5_accuracy"}) {
    EXPECT_EQ(s["dimensions"][dim]["max"], 0) << dim;
    EXPECT_EQ(s["dimensions"][dim]["details"][0]["verdict"], "no_reference") << dim;
    EXPECT_NE(s["dimensions"][dim]["details"][0]["note"].get<std::string>().find("no reference"), std::string::npos);
  }
  EXPECT_DOUBLE_EQ(points(s, "d2_derive"), 14.0);
  EXPECT_DOUBLE_EQ(points(s, "d4_converge"), 10.0);
  EXPECT_EQ(s["measured"]["shooting_variables"], 8);
  EXPECT_TRUE(s["measured"]["reference_final_mass_kg"].is_null());
  EXPECT_FALSE(s.contains("warnings"));  // the spec's id S01 is no mismatch without a reference
  in.solution = solution_doc(603.935);
  (*in.solution)["status"] = "not_converged";
  EXPECT_DOUBLE_EQ(helios::score::score_run(in)["total"].get<double>(), 34.0);
  in.scenario = "";
  EXPECT_THROW(helios::score::score_run(in), std::exception);
}

TEST(Score, WrongThrustLosesOneFactShare) {
  ScoreInputs in = perfect_inputs();
  (*in.spec)["spacecraft"]["thrust_N"] = 0.6;
  const json s = helios::score::score_run(in);
  const double share = 30.0 / static_cast<double>(in.reference["expected_parse"].size());
  EXPECT_TRUE(IsClose(points(s, "d1_parse"), 30.0 - share, 1e-12, 0));
  EXPECT_TRUE(IsClose(s["total"].get<double>(), 100.0 - share, 1e-12, 0));
  const json& d = fact_detail(s, "thrust");
  EXPECT_EQ(d["verdict"], "fail");
  EXPECT_EQ(d["found"], 0.6);
  EXPECT_EQ(d["pointer"], "/spacecraft/thrust_N");
}

TEST(Score, TinyRoundingInAFactStillMatches) {
  ScoreInputs in = perfect_inputs();
  (*in.spec)["central_body"]["mu_km3_s2"] = 1.32712440018e11 * (1 + 1e-12);
  EXPECT_DOUBLE_EQ(points(helios::score::score_run(in), "d1_parse"), 30.0);
}

TEST(Score, WrongVectorComponentFailsTheFact) {
  ScoreInputs in = perfect_inputs();
  // The misprint some copies of the paper carry: vf_z = 9.21486e-4 instead of e-2.
  for (json& c : (*in.spec)["constraints"])
    if (c["kind"] == "rendezvous") c["target"]["velocity_km_s"][2] = 9.21486e-4;
  const json s = helios::score::score_run(in);
  const json& d = fact_detail(s, "arrival_velocity");
  EXPECT_EQ(d["verdict"], "fail");
  EXPECT_NE(d["note"].get<std::string>().find("component 2"), std::string::npos) << d["note"];
}

TEST(Score, MissingSolutionScoresZeroOnCompileConvergeAccuracy) {
  ScoreInputs in = perfect_inputs();
  in.solution.reset();
  const json s = helios::score::score_run(in);
  EXPECT_DOUBLE_EQ(points(s, "d1_parse"), 30.0);
  EXPECT_DOUBLE_EQ(points(s, "d2_derive"), 20.0);
  EXPECT_EQ(points(s, "d3_compile"), 0.0);
  EXPECT_EQ(points(s, "d4_converge"), 0.0);
  EXPECT_EQ(points(s, "d5_accuracy"), 0.0);
  EXPECT_DOUBLE_EQ(s["total"].get<double>(), 50.0);
  EXPECT_FALSE(s["inputs"]["solution"].get<bool>());
  EXPECT_TRUE(s["measured"]["final_mass_kg"].is_null());
  EXPECT_TRUE(s["measured"]["error_kg"].is_null());
  EXPECT_EQ(s["dimensions"]["d3_compile"]["details"][0]["verdict"], "missing");
}

TEST(Score, NothingButTheReferenceScoresZero) {
  ScoreInputs in;
  in.reference = s01_reference();
  const json s = helios::score::score_run(in);
  EXPECT_EQ(s["total"].get<double>(), 0.0);
  EXPECT_EQ(s["dimensions"]["d1_parse"]["details"].size(), in.reference["expected_parse"].size());
}

TEST(Score, FinalMassOffByHalfAKilogramGetsPartialAccuracy) {
  ScoreInputs in = perfect_inputs();
  in.solution = solution_doc(603.935 + 0.5);
  const json s = helios::score::score_run(in);
  // NOTE: linear from 10 at tol = 0.01 kg to 0 at 100 tol = 1 kg: 10 (1 - 0.5) / 0.99.
  const double expected = 10.0 * (100 * 0.01 - 0.5) / (99 * 0.01);
  EXPECT_TRUE(IsClose(points(s, "d5_accuracy"), expected, 1e-9, 0));
  EXPECT_TRUE(IsClose(expected, 5.050505050505, 1e-9, 0));
  EXPECT_EQ(s["dimensions"]["d5_accuracy"]["details"][0]["verdict"], "partial");
  EXPECT_TRUE(IsClose(s["measured"]["error_kg"].get<double>(), 0.5, 1e-9, 0));
  EXPECT_DOUBLE_EQ(points(s, "d4_converge"), 20.0);
}

TEST(Score, AccuracyEdges) {
  ScoreInputs in = perfect_inputs();
  in.solution = solution_doc(603.935 - 0.009);
  EXPECT_DOUBLE_EQ(points(helios::score::score_run(in), "d5_accuracy"), 10.0);
  in.solution = solution_doc(603.935 + 1.5);
  EXPECT_EQ(points(helios::score::score_run(in), "d5_accuracy"), 0.0);
  // An unconverged run's m_f is not scored, and its residual is too large.
  json unconverged = solution_doc(603.935, 1e-3);
  unconverged["status"] = "not_converged";
  in.solution = unconverged;
  const json s = helios::score::score_run(in);
  EXPECT_EQ(points(s, "d5_accuracy"), 0.0);
  EXPECT_EQ(points(s, "d4_converge"), 0.0);
  EXPECT_DOUBLE_EQ(points(s, "d3_compile"), 20.0);
}

TEST(Score, CompileFailureScoresZeroOnD3) {
  ScoreInputs in = perfect_inputs();
  json failed = solution_doc(603.935);
  failed["compile"]["ok"] = false;
  failed["status"] = "compile_failed";
  for (const char* key : {"final_mass_kg", "delta_v_m_s", "max_residual", "x", "residuals", "epsilon"})
    failed.erase(key);
  in.solution = failed;
  const json s = helios::score::score_run(in);
  EXPECT_EQ(points(s, "d3_compile"), 0.0);
  EXPECT_EQ(points(s, "d4_converge"), 0.0);
  EXPECT_EQ(points(s, "d5_accuracy"), 0.0);
}

TEST(Score, ReorderedConstraintsStillScoreFullParse) {
  ScoreInputs in = perfect_inputs();
  json& constraints = (*in.spec)["constraints"];
  std::reverse(constraints.begin(), constraints.end());
  ASSERT_EQ(constraints[0]["kind"], "rendezvous");
  const json s = helios::score::score_run(in);
  EXPECT_DOUBLE_EQ(points(s, "d1_parse"), 30.0);
  EXPECT_EQ(fact_detail(s, "arrival_position")["pointer"], "/constraints/0/target/position_km");
  EXPECT_EQ(fact_detail(s, "departure_velocity")["pointer"], "/constraints/1/target/velocity_km_s");
}

TEST(Score, VerifyFractionAndShootingCount) {
  ScoreInputs in = perfect_inputs();
  in.verify = verify_doc(15, 20);
  json s = helios::score::score_run(in);
  EXPECT_DOUBLE_EQ(points(s, "d2_derive"), 14.0 * 15 / 20 + 6.0);
  in.verify.reset();
  (*in.derivation)["shooting"]["variables"].erase(0);
  s = helios::score::score_run(in);
  EXPECT_EQ(points(s, "d2_derive"), 0.0);
  EXPECT_EQ(s["measured"]["shooting_variables"], 7);
}

TEST(Score, MalformedReferenceIsAnInputErrorNamingTheField) {
  ScoreInputs in = perfect_inputs();
  in.reference["expected_parse"][1]["rel_tol"] = -1;
  in.reference_source = "ref.json";
  try {
    helios::score::score_run(in);
    FAIL() << "expected input_error";
  } catch (const helios::input_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "ref.json: reference schema violation at /expected_parse/1/rel_tol: Expected number greater than or "
              "equal to 0.000000");
  }
  in.reference = s01_reference();
  in.reference["result"].erase("tolerance_kg");
  EXPECT_THROW(helios::score::score_run(in), helios::input_error);
  in.reference = s01_reference();
  in.reference["expected_parse"][0]["pointr"] = "/x";
  EXPECT_THROW(helios::score::score_run(in), helios::input_error);
  in.reference = s01_reference();
  in.reference["expected_parse"][1]["id"] = in.reference["expected_parse"][0]["id"];
  EXPECT_THROW(helios::score::score_run(in), helios::input_error);
}

TEST(Score, ScoreboardHasARowPerScenarioAndTotals) {
  const json s = helios::score::score_run(perfect_inputs());
  const std::string md = helios::score::render_scoreboard({s});
  EXPECT_NE(md.find("| S01 | builtin | 30 | 20 | 20 | 20 | 10 | 100 | 603.935 | 603.935 | 0.000 | 2.5e-12 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| **total** | 1 scenario |"), std::string::npos) << md;

  // The same through a run folder: DIR/S01/score.json.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("helios_score_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "S01");
  helios::io::write_json_atomic((dir / "S01" / "score.json").string(), s);
  EXPECT_EQ(helios::score::scoreboard_from_dir(dir.string()), md);
  // With the run's solution beside it, the table of solutions and their search follows.
  json solution = solution_doc(603.935);
  solution["tof_days"] = 348.795;
  solution["propellant_kg"] = 396.065;
  solution["x"] = json::array();
  for (const char* name : {"lambda0", "l_x_t0", "l_y_t0", "l_z_t0", "l_vx_t0", "l_vy_t0", "l_vz_t0", "l_m_t0"})
    solution["x"].push_back({{"name", name}, {"value", 0.1}});
  solution["search"] = {{"method", "multi-start"},
                        {"threads", 2},
                        {"starts", 128},
                        {"converged_at_eps_start", 36},
                        {"continued", 1},
                        {"converged_at_eps_0", 1},
                        {"seconds", 0.8},
                        {"cut_by_time", false},
                        {"saturated", true},
                        {"extremals_at_eps_start", json::array()},
                        {"extremals", json::array()}};
  helios::io::write_json_atomic((dir / "S01" / "solution.json").string(), solution);
  const std::string with_solution = helios::score::scoreboard_from_dir(dir.string());
  EXPECT_EQ(with_solution.rfind(md, 0), 0u);
  EXPECT_NE(with_solution.find("| S01 | converged | 348.795 | 396.065 | 8 | 0 | yes | 128 | 1.5 |"), std::string::npos)
      << with_solution;
  fs::remove_all(dir / "S01");
  EXPECT_THROW(helios::score::scoreboard_from_dir(dir.string()), helios::input_error);
  fs::remove_all(dir);
}

// The model's name is the endpoint's text: in scoreboard.md and the tables it stays text in its
// cell (no new row or heading, no HTML, link, code or math), whatever it holds.
TEST(Score, AModelNameIsMarkdownTextInItsCell) {
  const std::string hostile = "m | S99 | 100 |\n# Pwned <img src=x onerror=alert(1)> [a](http://x) `c` $x$ *b*";
  json s = helios::score::score_run(perfect_inputs());
  s["producer"]["backend"] = "llm";
  s["producer"]["model"] = hostile;
  const std::string escaped =
      "m \\| S99 \\| 100 \\| \\# Pwned \\<img src=x onerror=alert(1)\\> \\[a\\](http://x) \\`c\\` \\$x\\$ \\*b\\*";
  const auto rows = [](const std::string& md) {
    std::size_t n = 0;
    for (std::size_t at = 0; (at = md.find("\n|", at)) != std::string::npos; ++at) ++n;
    return n;
  };
  const std::string md = helios::score::render_scoreboard({s});
  EXPECT_NE(md.find("| S01 | llm (" + escaped + ") | 30 |"), std::string::npos) << md;
  EXPECT_EQ(rows(md), 4u) << md;  // header, rule, the run, the totals
  EXPECT_EQ(md.find("\n#", md.find("| S01")), std::string::npos) << md;
  EXPECT_EQ(md.find(" <img"), std::string::npos) << md;

  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("helios_score_tables_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "llm" / "S01");
  helios::io::write_json_atomic((root / "llm" / "S01" / "score.json").string(), s);
  const std::string tables = helios::score::tables_from_runs(root.string());
  EXPECT_NE(tables.find("| S01 | llm (" + escaped + ") | 1 | 100.0 | 1/1 | 1/1 |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| llm (" + escaped + ") | 1 | 0 | 0 | 0 | 0 | 0 |"), std::string::npos) << tables;
  EXPECT_EQ(tables.find(" <img"), std::string::npos) << tables;
  EXPECT_EQ(tables.find("\n# Pwned"), std::string::npos) << tables;
  fs::remove_all(root);
}

}  // namespace

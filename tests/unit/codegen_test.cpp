#include "helios/codegen/generate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../../tools/lib/src/codegen/context.hpp"  // number(): how codegen prints a double
#include "helios/pmp/derive.hpp"
#include "helios/solve/solve.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"

namespace {

using helios::io::json;

const json& s01() {
  static const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
      helios::io::read_text(std::string(HELIOS_SOURCE_DIR) + "/scenarios/S01/problem.txt"), "S01"));
  return d;
}

TEST(Codegen, StandardModelUsesTemplateDynamicsAndGeneratesResidualAndSolve) {
  const auto g = helios::codegen::generate(s01(), {});
  EXPECT_EQ(g.template_modules, (std::vector<std::string>{"DYNAMICS", "SWITCH"}));
  EXPECT_EQ(g.generated_modules, (std::vector<std::string>{"JACOBIAN", "RESIDUAL", "SOLVE"}));
  EXPECT_NE(g.source.find("module RESIDUAL (generated)"), std::string::npos);
  // the shooting function on double and on dual numbers, its exact Jacobian
  EXPECT_NE(g.source.find("template <class T>\nvoid shooting_residual(const T* x,"), std::string::npos);
  EXPECT_NE(
      g.source.find("void shooting_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J)"),
      std::string::npos);
  EXPECT_NE(g.source.find("template default: two-body Cartesian low thrust"), std::string::npos);
  EXPECT_EQ(g.source.find("#pragma once"), std::string::npos);
  EXPECT_NE(g.source.find("F[6] = (l_m_tf);"), std::string::npos);
}

TEST(Codegen, DifferentHamiltonianGetsGeneratedDynamics) {
  json d = s01();
  // A derivation whose H differs from the template's (a different cost) must not use the template.
  d["hamiltonian"] = d["hamiltonian"].get<std::string>() + "+l_rx*rx";
  const auto g = helios::codegen::generate(d, {});
  EXPECT_EQ(g.generated_modules.size(), 5u);  // DYNAMICS, SWITCH, JACOBIAN, RESIDUAL, SOLVE
  EXPECT_NE(g.source.find("modules DYNAMICS + SWITCH (generated"), std::string::npos);
}

TEST(Codegen, FiniteDifferenceOptionLeavesOutTheJacobian) {
  helios::codegen::GenOptions o;
  o.jacobian = false;
  const auto g = helios::codegen::generate(s01(), o);
  EXPECT_EQ(g.generated_modules, (std::vector<std::string>{"RESIDUAL", "SOLVE"}));
  EXPECT_EQ(g.source.find("shooting_jacobian"), std::string::npos);
  EXPECT_EQ(g.source.find("pragma GCC"), std::string::npos);
}

TEST(Codegen, TimeDependentDynamicsGetNoExactJacobian) {
  json d = s01();
  // An explicitly time-dependent term: the variational equations here assume autonomous dynamics.
  d["hamiltonian"] = d["hamiltonian"].get<std::string>() + "+l_rx*t";
  d["state_odes"][0]["rhs"] = d["state_odes"][0]["rhs"].get<std::string>() + "+t";
  const auto g = helios::codegen::generate(d, {});
  EXPECT_EQ(g.source.find("shooting_jacobian"), std::string::npos);
  EXPECT_EQ(std::count(g.generated_modules.begin(), g.generated_modules.end(), "JACOBIAN"), 0);
}

// Integer and half-integer powers up to 9/2 are printed as products and one sqrt (pow is tens of
// multiplications); others stay pow. Both dialects, the same text but the namespace.
TEST(Codegen, SmallPowersArePrintedAsProductsAndOneSqrt) {
  using helios::symbolic::CppScalar;
  using helios::symbolic::to_csrc;
  const GiNaC::symbol x("x"), y("y");
  const GiNaC::ex s = x + y;
  EXPECT_EQ(to_csrc(GiNaC::pow(x, 3)), "x*x*x");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, -4)), "1.0/(x*x*x*x)");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, -1)), "1.0/x");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, GiNaC::numeric(-1, 2))), "1.0/sqrt(x)");
  EXPECT_EQ(to_csrc(GiNaC::pow(s, GiNaC::numeric(-7, 2))), "1.0/((x+y)*(x+y)*(x+y)*sqrt(x+y))");
  EXPECT_EQ(to_csrc(GiNaC::pow(s, GiNaC::numeric(5, 2))), "(x+y)*(x+y)*sqrt(x+y)");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, 5)), "std::pow(x, 5.0)");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, GiNaC::numeric(9, 2)), CppScalar::Generic), "x*x*x*x*sqrt(x)");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, GiNaC::numeric(11, 2)), CppScalar::Generic), "pow(x, 11.0/2.0)");
  EXPECT_EQ(to_csrc(GiNaC::pow(x, GiNaC::numeric(1, 3))), "std::pow(x, 1.0/3.0)");
}

// A swing-by's rows in the velocity relative to the planet: expanded in the heliocentric
// velocities (~24 km/s at Mars, against a v_inf of a few km/s) their terms are a thousand times
// their sum, and S10's r_p row had 1e-11 of round-off at its solution.
TEST(Codegen, SwingByRowsAreWrittenInTheVelocityRelativeToThePlanet) {
  const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
      helios::io::read_text(std::string(HELIOS_SOURCE_DIR) + "/scenarios/S10/problem.txt"), "S10"));
  const std::string source = helios::codegen::generate(d, {}).source;
  EXPECT_NE(source.find("  const T vx_mars_rel = vx_mars_m - mars_vx;\n"), std::string::npos);
  std::istringstream lines(source);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("// gravity_assist at mars: sin(delta/2)^2") == std::string::npos) continue;
    ++rows;
    EXPECT_NE(line.find("vx_mars_rel*vx_mars_rel"), std::string::npos) << line;
    EXPECT_EQ(line.find("mars_vx*"), std::string::npos) << line;
  }
  EXPECT_EQ(rows, 2);  // the shooting function's, and the leg alone's
}

TEST(Codegen, GeneratedPolicyIsDeterministic) {
  helios::codegen::GenOptions o;
  o.modules = helios::codegen::ModulePolicy::Generated;
  EXPECT_EQ(helios::codegen::generate(s01(), o).source, helios::codegen::generate(s01(), o).source);
}

TEST(Codegen, PlanetTargetsAreEvaluatedFromTheEphemerisAtTheEvent) {
  std::string text = helios::io::read_text(std::string(HELIOS_SOURCE_DIR) + "/scenarios/S01/problem.txt");
  const std::string from =
      "with position [-172682023, 176959469, 7948912] km and velocity [-16.427384, -14.860506, 9.21486e-2] km/s";
  text.replace(text.find(from), from.size(), "with Mars");
  text.replace(text.find("at t = 0 days"), 13, "at MJD2000 400");
  const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, "mars"));
  EXPECT_EQ(d["times"]["epoch_mjd2000"], 400.0);
  const auto g = helios::codegen::generate(d, {});
  EXPECT_NE(g.source.find("const auto ephemeris_0 = ephemeris_state(\"Mars\", tf);"), std::string::npos);
  EXPECT_NE(g.source.find("const T arrival_rx = ephemeris_0[0];"), std::string::npos);
  EXPECT_EQ(g.source.find("constexpr double arrival_rx"), std::string::npos);
}

// The lines of the module whose banner starts "// ----- module <name>" in `source`.
std::vector<std::string> module_lines(const std::string& source, const std::string& name) {
  std::istringstream in(source);
  std::vector<std::string> lines;
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("// ----- ", 0) == 0) inside = line.rfind("// ----- module " + name + " ", 0) == 0;
    if (inside) lines.push_back(line);
  }
  return lines;
}

TEST(Codegen, EveryResidualRowOfEveryScenarioSaysWhichConditionItIs) {
  std::vector<std::filesystem::path> scenarios;
  // The scored scenarios S<NN> (a sweep's P<NN> is a template whose values are placeholders).
  for (const auto& entry : std::filesystem::directory_iterator(std::string(HELIOS_SOURCE_DIR) + "/scenarios"))
    if (entry.path().filename().string().rfind('S', 0) == 0) scenarios.push_back(entry.path());
  ASSERT_GE(scenarios.size(), 13u);
  for (const auto& dir : scenarios) {
    const std::string id = dir.filename().string();
    const json d = helios::pmp::derive_from_spec(
        helios::spec::parse_problem_text(helios::io::read_text((dir / "problem.txt").string()), id));
    const std::string source = helios::codegen::generate(d, {}).source;
    // Its numbers are readable: it shares a compiled program with every problem of its structure.
    const auto parameters = helios::solve::program_parameters(source);
    EXPECT_TRUE(parameters.readable) << id << ": " << parameters.whole_source_because;
    const auto lines = module_lines(source, "RESIDUAL");
    ASSERT_FALSE(lines.empty()) << id;
    for (const auto& line : lines) {
      if (line.find("F[") == std::string::npos || line.find("] = ") == std::string::npos) continue;
      const auto comment = line.find(";  // ");
      EXPECT_TRUE(comment != std::string::npos && comment + 6 < line.size()) << id << ": " << line;
    }
  }
}

// The lines of `text`.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(Codegen, StringsFromTheDerivationCannotBecomeCode) {
  // A derivation (an llm one, say) that passed no schema: an id that closes its string literal and
  // its first-line comment, a meaning with a newline, a body name with a quote.
  json d = s01();
  const std::string payload = "S01\"; inline int pwn = std::system(\"touch marker\"); //\ninline int pwn2 = 1;";
  d["problem"]["id"] = payload;
  d["shooting"]["equations"][0]["meaning"] = "x\ninline int pwn3 = 1; //\\";
  d["parameters"][0]["meaning"] = "mu\rinline int pwn4 = 1;";
  d["bodies"] = json::array(
      {{{"name", "Ni\"kko\\"},
        {"model", "kepler"},
        {"epoch", 0.0},
        {"elements",
         {{"a", 1.0}, {"e", 0.1}, {"i_rad", 0.0}, {"raan_rad", 0.0}, {"argp_rad", 0.0}, {"mean_anomaly_rad", 0.0}}}}});
  const auto g = helios::codegen::generate(d, {});
  // The payloads stay inside string literals and comments: no line starts with them as code.
  for (const auto& line : lines_of(g.source))
    EXPECT_NE(line.substr(line.find_first_not_of(' ') == std::string::npos ? 0 : line.find_first_not_of(' '))
                  .rfind("inline int pwn", 0),
              0u)
        << line;
  EXPECT_NE(
      g.source.find("kProblemId = \"S01\\\"; inline int pwn = std::system(\\\"touch marker\\\"); //\\012inline int "
                    "pwn2 = 1;\";"),
      std::string::npos);
  EXPECT_NE(g.source.find("{\"Ni\\\"kko\\\\\", "), std::string::npos);  // the body name, escaped
  EXPECT_EQ(lines_of(g.source)[0].rfind("// Shooting program for problem S01\"; inline int pwn = ", 0), 0u);
}

TEST(Codegen, CountMismatchIsAnError) {
  json d = s01();
  d["shooting"]["equations"].erase(d["shooting"]["equations"].size() - 1);
  EXPECT_THROW(helios::codegen::generate(d, {}), std::invalid_argument);
}

// The program of a P01 cell (tools/lib/src/sweep/README.md), its template's text changed by `edits`
// (each a {from, to} replacement).
std::string p01_program(const std::string& departure, const std::string& tof,
                        const std::vector<std::pair<std::string, std::string>>& edits = {}) {
  std::string text = helios::io::read_text(std::string(HELIOS_SOURCE_DIR) + "/scenarios/P01/problem.txt");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"@DEPARTURE_MJD2000@", departure}, {"@TOF_DAYS@", tof}})
    for (std::size_t at; (at = text.find(from)) != std::string::npos;) text.replace(at, from.size(), to);
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return helios::codegen::generate(helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, "P01")), {})
      .source;
}

// Two cells of a sweep, with another thrust too, are one program: their sources differ (the
// numbers are in them) but their structure, the compile cache's key, is the same; the numbers
// helios-solve passes are each cell's own.
TEST(Codegen, CellsOfASweepDifferOnlyInTheirParameters) {
  const std::string a = p01_program("9700", "350");
  const std::string b = p01_program("9740", "400", {{"maximum thrust of 0.5 N", "maximum thrust of 0.6 N"}});
  EXPECT_NE(a, b);
  const auto pa = helios::solve::program_parameters(a), pb = helios::solve::program_parameters(b);
  ASSERT_TRUE(pa.readable);
  ASSERT_TRUE(pb.readable);
  EXPECT_EQ(pa.structure, pb.structure);
  EXPECT_EQ(pa.values["kEpochMjd2000"], 9700.0);
  EXPECT_EQ(pb.values["kEpochMjd2000"], 9740.0);
  EXPECT_NE(pa.values["kTf"], pb.values["kTf"]);
  EXPECT_NE(pa.values["Tmax"], pb.values["Tmax"]);
  EXPECT_EQ(pa.values["mu"], pb.values["mu"]);
  // Only the numbers of the parameter lines are masked: the structure is the source line for line.
  const auto la = lines_of(a), ls = lines_of(pa.structure);
  ASSERT_EQ(la.size(), ls.size());
  int masked = 0;
  for (std::size_t i = 0; i < la.size(); ++i) {
    if (la[i] == ls[i]) continue;
    ++masked;
    EXPECT_EQ(la[i].rfind("HELIOS_PARAMETER", 0), 0u) << la[i];
  }
  EXPECT_EQ(masked, static_cast<int>(pa.values.size()));
  EXPECT_NE(pa.structure.find("HELIOS_PARAMETER(kTf, #);"), std::string::npos);
  EXPECT_NE(pa.structure.find("HELIOS_PARAMETER(Tmax, #);  // maximum thrust ["), std::string::npos);
}

// A free final time is its window's map written with the window's parameters kTfMin and kTf, which
// the runtime's thrust continuation scales: two windows are one structure.
TEST(Codegen, AFreeFinalTimeIsWrittenWithItsWindowsParameters) {
  const std::string free = "The time of flight is free, between 50 days and 600 days.";
  const std::string a = p01_program("9700", "", {{"The time of flight is  days.", free}});
  const std::string b = p01_program(
      "9700", "", {{"The time of flight is  days.", "The time of flight is free, between 80 days and 700 days."}});
  EXPECT_NE(a.find("const T tf = problem::kTfMin + (problem::kTf - problem::kTfMin) * tf_frac;"), std::string::npos);
  EXPECT_EQ(helios::solve::program_parameters(a).structure, helios::solve::program_parameters(b).structure);
}

// Anything but the numbers is structure: another target body, another objective.
TEST(Codegen, AnotherTargetOrObjectiveIsAnotherStructure) {
  const std::string structure = helios::solve::program_parameters(p01_program("9700", "350")).structure;
  const auto other = [](const std::string& source) { return helios::solve::program_parameters(source).structure; };
  EXPECT_NE(other(p01_program("9700", "350", {{"rendezvouses with Mars", "rendezvouses with Venus"}})), structure);
  EXPECT_NE(other(p01_program("9700", "",
                              {{"The time of flight is  days.",
                                "The time of flight is free, between 50 "
                                "days and 600 days."},
                               {"Minimize the fuel consumption.", "Minimize the time of flight."}})),
            structure);
}

// A literal codegen prints (17 significant digits) and helios-solve reads back is the same double,
// through the parameters file's JSON too.
TEST(Codegen, ParameterValuesAreTheDerivationsDoublesBitForBit) {
  const json d = s01();
  const auto p = helios::solve::program_parameters(helios::codegen::generate(d, {}).source);
  ASSERT_TRUE(p.readable);
  const json file = json::parse(helios::solve::parameters_document(p.values).dump(2));
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  int checked = 0;
  for (const auto& q : d.at("parameters")) {
    if (q.contains("source")) continue;
    const std::string name = q.at("name");
    EXPECT_TRUE(same(file.at("values").at(name).get<double>(), q.at("value").get<double>())) << name;
    ++checked;
  }
  EXPECT_GT(checked, 3);
  EXPECT_TRUE(same(file.at("values").at("kTf").get<double>(), d.at("times").at("tf").get<double>()));
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::uint64_t> bits;
  for (int i = 0; i < 20000; ++i) {
    const std::uint64_t u = bits(rng);
    double v;
    std::memcpy(&v, &u, sizeof v);
    if (!std::isfinite(v)) continue;
    const std::string source = "HELIOS_PARAMETER(x, " + helios::codegen::detail::number(v) + ");\n";
    const auto r = helios::solve::program_parameters(source);
    ASSERT_TRUE(r.readable) << source;
    const double back = json::parse(helios::solve::parameters_document(r.values).dump()).at("values").at("x");
    ASSERT_TRUE(same(back, v)) << source;
  }
}

// A source whose numbers helios-solve cannot read for sure keys the cache on its whole text and
// runs on its literals: a parameter line of another form, a macro before the parameters, a
// HELIOS_PARAMETER elsewhere in code; a comment line may name it.
TEST(Codegen, ParameterLinesOfAnotherFormAreNotMasked) {
  const std::string good =
      "#include \"helios_runtime.hpp\"\n// HELIOS_PARAMETER lines:\nHELIOS_PARAMETER(a, 1.5);\n"
      "HELIOS_PARAMETER_ARRAY(b, -2.0, 3e-05);  // note\nint main() {}\n";
  const auto p = helios::solve::program_parameters(good);
  ASSERT_TRUE(p.readable);
  EXPECT_EQ(p.structure,
            "#include \"helios_runtime.hpp\"\n// HELIOS_PARAMETER lines:\nHELIOS_PARAMETER(a, #);\n"
            "HELIOS_PARAMETER_ARRAY(b, #, #);  // note\nint main() {}\n");
  EXPECT_EQ(p.values, (json{{"a", 1.5}, {"b", {-2.0, 3e-05}}}));
  for (const std::string bad :
       {"HELIOS_PARAMETER(a, 1.5 * 2);\n", "HELIOS_PARAMETER(a, 1.5f);\n", "HELIOS_PARAMETER(a, 1.5); int x;\n",
        "HELIOS_PARAMETER(a, 1.5);\nHELIOS_PARAMETER(a, 2.5);\n", "#define double float\nHELIOS_PARAMETER(a, 1.5);\n",
        "  HELIOS_PARAMETER(a, 1.5);\n", "HELIOS_PARAMETER(a, 1e999);\n", "HELIOS_PARAMETER(a, 1.5);\r\n",
        "HELIOS_PARAMETER_ARRAY(a);\n", "HELIOS_PARAMETER(a, 1.5, 2.5);\n", "int HELIOS_PARAMETER = 1;\n"}) {
    const auto q = helios::solve::program_parameters(bad);
    EXPECT_FALSE(q.readable) << bad;
    EXPECT_EQ(q.structure, bad);
    EXPECT_TRUE(q.values.empty()) << bad;
  }
}

// A parameter line inside a comment is text, not a parameter: not masked, not in the file.
TEST(Codegen, AParameterLineInACommentIsNotAParameter) {
  const std::string source =
      "#include \"helios_runtime.hpp\"\n/*\nHELIOS_PARAMETER(a, 1.5);\n*/\n"
      "HELIOS_PARAMETER(b, 2.5);\nconst char* const kText = \"HELIOS_PARAMETER(c, 3.5);\";\n"
      "int main() {}\n";
  const auto p = helios::solve::program_parameters(source);
  ASSERT_TRUE(p.readable) << p.whole_source_because;
  EXPECT_EQ(p.values, (json{{"b", 2.5}}));
  EXPECT_NE(p.structure.find("\nHELIOS_PARAMETER(a, 1.5);\n*/\nHELIOS_PARAMETER(b, #);\n"), std::string::npos);
}

// Code that runs before main (a namespace-scope initializer, a static member, a constructor
// attribute) could read a parameter before the parameters file replaces it: such a source keeps its
// numbers (compiled on its own, keyed on its whole text). Functions, types, constexpr and literal
// initializers run nothing then.
TEST(Codegen, CodeThatRunsBeforeMainKeysTheCacheOnTheWholeSource) {
  const std::string head = "#include \"helios_runtime.hpp\"\nnamespace problem {\nHELIOS_PARAMETER(Tmax, 0.5);\n}\n";
  for (const std::string bad : {"const double k = problem::Tmax;\n",
                                "namespace n {\ndouble k{problem::Tmax};\n}\n",
                                "double k(problem::Tmax);\n",
                                "double f();\nconst double k = f();\n",
                                "const double k = [] { return problem::Tmax; }();\n",
                                "struct S {\n  static inline double k = problem::Tmax;\n};\n",
                                "struct S {\n  double v = problem::Tmax;\n} s;\n",
                                "__attribute__((constructor)) void f() { problem::Tmax = 1; }\n",
                                "[[gnu::constructor]] void f() {}\n",
                                "#define K 1\n",
                                "double a = 1, b = problem::Tmax;\n",
                                "namespace {\nconst double k = 2 * problem::Tmax;\n}\n",
                                "extern \"C\" {\ndouble k = problem::Tmax;\n}\n",
                                "thread_local double t = 1;\n",
                                "const double k = problem::\\\nTmax;\n",
                                "double \\u0054max2 = 1;\n",
                                "template <class T> T k = T(problem::Tmax);\n",
                                "struct Shape {} kShape;\n",
                                "Foo foo;\n",
                                "const helios_rt::ProblemShape kProblem = {problem::Tmax * 2};\n",
                                "/* open\n"}) {
    const auto p = helios::solve::program_parameters(head + bad + "int main() {}\n");
    EXPECT_FALSE(p.readable) << bad;
    EXPECT_FALSE(p.whole_source_because.empty()) << bad;
    EXPECT_TRUE(p.values.empty()) << bad;
  }
  for (const std::string good :
       {"constexpr double k = 2.0;\n", "const double kTwoPi = 2 * 3.141592653589793;\n",
        "const char* const kNames[] = {\"a\", \"b\"};\n",
        "double f(double x) {\n  static const double k = problem::Tmax;\n  return k * x;\n}\n",
        "struct S {\n  double v = 1.0;\n  double f() const { return problem::Tmax * v; }\n};\n",
        "namespace n {\ninline double g() { return problem::Tmax; }\n}  // namespace n\n", "enum class E { A = 1 };\n",
        "using D = double;\n", "static_assert(sizeof(double) == 8, \"x\");\n",
        "template <class T>\nT sq(T x) {\n  return x * x;\n}\n", "#pragma GCC optimize(\"O2\")\n#include <cmath>\n",
        "// HELIOS_PARAMETER(b, 1.5); in a comment\n", "constexpr auto table = [] { return 1; }();\n"}) {
    const auto p = helios::solve::program_parameters(head + good + "int main() {}\n");
    EXPECT_TRUE(p.readable) << good << p.whole_source_because;
    EXPECT_EQ(p.values, (json{{"Tmax", 0.5}})) << good;
  }
}

}  // namespace

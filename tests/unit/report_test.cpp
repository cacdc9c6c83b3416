#include "helios/report/report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "helios/derivation/reader.hpp"
#include "helios/io/json_io.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/latex.hpp"

namespace {

using helios::io::json;
using helios::symbolic::latex_symbol;
using helios::symbolic::Typesetter;

const std::string kSource = HELIOS_SOURCE_DIR;

json spec_of(const std::string& scenario) {
  const std::string path = kSource + "/scenarios/" + scenario + "/problem.txt";
  return helios::spec::parse_problem_text(helios::io::read_text(path), path);
}

// ---- symbol names --------------------------------------------------------------------------

TEST(LatexSymbol, StatesCostatesGreekAndEventParts) {
  EXPECT_EQ(latex_symbol("rx"), "r_{x}");
  EXPECT_EQ(latex_symbol("m"), "m");
  EXPECT_EQ(latex_symbol("l_vx"), "\\lambda_{v_{x}}");
  EXPECT_EQ(latex_symbol("l_rx_t0"), "\\lambda_{r_{x}}(t_0)");
  EXPECT_EQ(latex_symbol("l_m_tf"), "\\lambda_{m}(t_f)");
  EXPECT_EQ(latex_symbol("eps"), "\\varepsilon");
  EXPECT_EQ(latex_symbol("lambda0"), "\\lambda_{0}");
  EXPECT_EQ(latex_symbol("Tmax"), "T_{\\max}");
  EXPECT_EQ(latex_symbol("vx_mars_m"), "v_{x}^{\\mathrm{mars}-}");
  EXPECT_EQ(latex_symbol("l_vx_mars_p"), "\\lambda_{v_{x}}^{\\mathrm{mars}+}");
  EXPECT_EQ(latex_symbol("mars_vx"), "v_{x}^{\\mathrm{mars}}");
  EXPECT_EQ(latex_symbol("nu_arrival_1"), "\\nu_{1}^{\\mathrm{arrival}}");
  EXPECT_EQ(latex_symbol("t_mars_frac"), "t^{\\mathrm{mars},\\mathrm{frac}}");
  EXPECT_EQ(latex_symbol("rref"), "\\mathrm{rref}");
}

TEST(Typesetter, AnIntermediateAndItsPartialsTakeItsQualifierAsASubscript) {
  Typesetter t({"P_in", "T_P", "dP_in_drx", "a_arrival"}, {"P_in", "T_P"});
  EXPECT_EQ(t.symbol("P_in"), "P_{\\mathrm{in}}");
  EXPECT_EQ(t.symbol("T_P"), "T_{P}");
  EXPECT_EQ(t.symbol("dP_in_drx"), "\\partial_{r_{x}} P_{\\mathrm{in}}");
  EXPECT_EQ(t.symbol("a_arrival"), "a^{\\mathrm{arrival}}");  // no intermediate: a qualifier's superscript
}

TEST(Typesetter, TwoNamesThatWouldPrintAlikeDoNot) {
  Typesetter t({"mars_vx", "vx_mars"});
  EXPECT_NE(t.symbol("mars_vx"), t.symbol("vx_mars"));
}

// ---- compact forms -----------------------------------------------------------------------

TEST(Typesetter, APowerOfASumOfSquaresIsANamedNorm) {
  helios::symbolic::SymbolTable table;
  for (const char* n : {"rx", "ry", "rz", "mu"}) table.get(n);
  Typesetter t({"rx", "ry", "rz", "mu"});
  const auto e = table.parse("-(rx^2+ry^2+rz^2)^(-3/2)*mu*rx", "test");
  t.learn(e);
  EXPECT_EQ(t.latex(e), "-\\frac{\\mu r_{x}}{r^{3}}");
  ASSERT_EQ(t.definitions().size(), 1u);
  EXPECT_EQ(t.definitions()[0].symbol, "r");
  EXPECT_EQ(t.definitions()[0].definition, "\\sqrt{r_{x}^{2} + r_{y}^{2} + r_{z}^{2}}");
}

TEST(Typesetter, AnExpandedSquaredDifferenceIsANamedDifference) {
  helios::symbolic::SymbolTable table;
  const std::vector<std::string> names = {"vx_mars_m", "vy_mars_m", "mars_vx", "mars_vy", "k"};
  for (const auto& n : names) table.get(n);
  Typesetter t(names);
  const std::string base = "(vx_mars_m^2-2*vx_mars_m*mars_vx+mars_vx^2+vy_mars_m^2-2*vy_mars_m*mars_vy+mars_vy^2)";
  const auto e = table.parse("k*" + base + "^(-1/2)", "test");
  t.learn(e);
  EXPECT_EQ(t.latex(e), "\\frac{k}{\\rho_{1}}");
  const auto defs = t.definitions();
  ASSERT_EQ(defs.size(), 3u);
  EXPECT_EQ(defs[0].symbol, "\\Delta_{1}");
  EXPECT_EQ(defs[0].definition, "v_{x}^{\\mathrm{mars}-} - v_{x}^{\\mathrm{mars}}");
  EXPECT_EQ(defs[2].definition, "\\sqrt{\\Delta_{1}^{2} + \\Delta_{2}^{2}}");
}

TEST(Typesetter, TheSameExpressionPrintsTheSameInTwoTypesetters) {
  // GiNaC orders terms by hash values that follow memory addresses; the printer sorts them.
  const json d = helios::pmp::derive_from_spec(spec_of("S10"));
  std::vector<std::string> first;
  for (int round = 0; round < 2; ++round) {
    helios::derivation::Reader reader(d, "S10", false);
    std::vector<std::string> names;
    for (const auto& entry : reader.symbols.symtab()) names.push_back(entry.first);
    Typesetter t(names);
    for (const auto& e : d.at("shooting").at("equations")) {
      const std::string tex = t.latex(reader.symbols.parse(e.at("expression"), "eq"));
      if (round == 0)
        first.push_back(tex);
      else
        EXPECT_EQ(tex, first[&e - &d.at("shooting").at("equations")[0]]);
    }
  }
}

// Every expression of every scenario's derivation: the compact form, its named quantities put
// back, equals the stored expression at random points (relative 1e-11; compact forms are exact
// rewrites, the difference is round-off of two evaluation orders).
class CompactIsExact : public ::testing::TestWithParam<std::string> {};

void expressions_of(const json& v, const std::string& key, std::vector<std::string>& out) {
  static const std::vector<std::string> keys = {"hamiltonian", "rhs", "law",       "switching_function",
                                                "interior",    "psi", "expression"};
  if (v.is_object()) {
    for (const auto& [k, x] : v.items()) expressions_of(x, k, out);
  } else if (v.is_array()) {
    for (const auto& x : v) expressions_of(x, key, out);
  } else if (v.is_string() && std::find(keys.begin(), keys.end(), key) != keys.end()) {
    out.push_back(v.get<std::string>());
  }
}

TEST_P(CompactIsExact, AtRandomPoints) {
  const json d = helios::pmp::derive_from_spec(spec_of(GetParam()));
  helios::derivation::Reader reader(d, GetParam(), false);
  std::vector<std::string> names;
  for (const auto& entry : reader.symbols.symtab()) names.push_back(entry.first);
  Typesetter t(names);
  std::vector<std::string> texts;
  expressions_of(d, "", texts);
  std::vector<GiNaC::ex> stored;
  for (const auto& text : texts) {
    try {
      stored.push_back(reader.symbols.parse(text, "x"));
    } catch (const std::exception&) {
      // Prose under an expression key (a law's sentence): not typeset as mathematics.
    }
  }
  for (const auto& e : stored) t.learn(e);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(0.3, 1.7);
  std::size_t checked = 0;
  for (const auto& e : stored) {
    const GiNaC::ex back = t.expanded_back(t.compact(e), reader.symbols.symtab());
    for (int point = 0; point < 3; ++point) {
      GiNaC::exmap at;
      for (const auto& entry : reader.symbols.symtab()) at[entry.second] = value(rng);
      const GiNaC::ex a = GiNaC::evalf(e.subs(at)), b = GiNaC::evalf(back.subs(at));
      ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(a) && GiNaC::is_a<GiNaC::numeric>(b)) << e;
      const double x = GiNaC::ex_to<GiNaC::numeric>(a).to_double(), y = GiNaC::ex_to<GiNaC::numeric>(b).to_double();
      EXPECT_LE(std::abs(x - y), 1e-11 * std::max(1.0, std::abs(x))) << GetParam() << ": " << e;
    }
    ++checked;
  }
  EXPECT_GT(checked, 20u);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CompactIsExact,
                         ::testing::Values("S01", "S02", "S03", "S04", "S05", "S06", "S07", "S08", "S09", "S10", "S11",
                                           "S12", "S13", "S14"));

TEST(Typesetter, S10PeriapsisRowIsAFifthOfItsStoredLength) {
  const json d = helios::pmp::derive_from_spec(spec_of("S10"));
  helios::derivation::Reader reader(d, "S10", false);
  std::vector<std::string> names;
  for (const auto& entry : reader.symbols.symtab()) names.push_back(entry.first);
  Typesetter t(names);
  // As the report does: every expression learned first (the norm of the relative velocity is a
  // power in other rows; here it stands expanded).
  std::vector<std::string> texts;
  expressions_of(d, "", texts);
  for (const auto& text : texts) {
    try {
      t.learn(reader.symbols.parse(text, "x"));
    } catch (const std::exception&) {
      // Prose under an expression key.
    }
  }
  const std::string stored = d.at("events")[0].at("psi")[5];
  ASSERT_GT(stored.size(), 5000u);
  const GiNaC::ex e = reader.symbols.parse(stored, "psi");
  EXPECT_LT(t.latex(e).size(), stored.size() / 5);
}

// ---- the report ----------------------------------------------------------------------------

TEST(Report, HasEverySectionAndEveryShootingEquation) {
  helios::report::ReportInputs in;
  in.problem_text = "The problem.\n";
  in.spec = spec_of("S04");
  in.derivation = helios::pmp::derive_from_spec(in.spec);
  const std::string md = helios::report::report_markdown(in);
  for (const char* section : {"## The problem", "## Specification", "### Hamiltonian", "### State equations",
                              "### Costate equations", "### Optimal control", "### Boundary conditions",
                              "### Interior events", "### Shooting variables and equations", "### Named quantities"})
    EXPECT_NE(md.find(section), std::string::npos) << section;
  const std::size_t equations = in.derivation.at("shooting").at("equations").size();
  EXPECT_NE(md.find("F_{" + std::to_string(equations) + "} = "), std::string::npos);
  EXPECT_EQ(md.find("F_{" + std::to_string(equations + 1) + "}"), std::string::npos);
  EXPECT_NE(md.find("not verified"), std::string::npos);
  EXPECT_NE(md.find("| `/spacecraft/thrust_N` | "), std::string::npos);
}

TEST(Report, AnExpressionItCannotReadIsShownAsText) {
  helios::report::ReportInputs in;
  in.spec = spec_of("S01");
  in.derivation = helios::pmp::derive_from_spec(in.spec);
  in.derivation["hamiltonian"] = "rx +* 2";
  const std::string md = helios::report::report_markdown(in);
  EXPECT_NE(md.find("`rx +* 2` (not an expression this report can typeset)"), std::string::npos);
}

// A target orbit's side condition (h.n > 0 for GEO: h_z) is typeset under its rows with its meaning.
TEST(Report, ATargetOrbitsSideConditionIsShownUnderItsRows) {
  helios::report::ReportInputs in;
  in.spec = spec_of("S14");
  in.derivation = helios::pmp::derive_from_spec(in.spec);
  const std::string md = helios::report::report_markdown(in);
  const std::size_t at = md.find("g_{1} = r_{x} v_{y} - r_{y} v_{x} > 0\n$$\n");
  ASSERT_NE(at, std::string::npos) << md;
  EXPECT_NE(md.find("(h.n\\_arrival \\> 0: the orbit runs the stated way", at), std::string::npos)
      << md.substr(at, 300);
}

// The search's extremals table gives each objective in the unit its record names: propellant,
// flight time or a final-state objective alike.
TEST(Report, TheExtremalsTableGivesTheObjectiveInItsUnit) {
  helios::report::ReportInputs in;
  in.spec = spec_of("S01");
  in.derivation = helios::pmp::derive_from_spec(in.spec);
  in.solution = json{{"status", "converged"},
                     {"search",
                      {{"returned", 1},
                       {"extremals", json::array({{{"id", 0}, {"objective", -1.52}, {"final_radius_km", 2.25e8}},
                                                  {{"id", 1}, {"objective", 0.1}, {"propellant_kg", 150.5}}})}}}};
  const std::string md = helios::report::report_markdown(in);
  EXPECT_NE(md.find("| extremal | objective | in named units |"), std::string::npos);
  EXPECT_NE(md.find("| 0 | -1.52 | 225000000 km |"), std::string::npos) << md.substr(md.find("| extremal |"), 400);
  EXPECT_NE(md.find("| 1 (returned) | 0.1 | 150.5 kg |"), std::string::npos);
}

// Strings of the artifacts are text wherever they land: escaped outside code, quoted inside it, and
// a key typed as a number prints only a number.
TEST(Report, HostileArtifactStringsAreTextAndNumbersAreNumbers) {
  const std::string evil = "3 $\\input{/etc/hostname}$ <script>x</script> `c` [a](http://e) |\n# h";
  helios::report::ReportInputs in;
  in.problem_text = "```\n$x$\n";
  in.spec = spec_of("S01");
  in.derivation = helios::pmp::derive_from_spec(in.spec);
  in.derivation_source = evil;
  in.solution = json{{"status", "converged"},
                     {"method", evil},
                     {"timings", {{evil, evil}}},
                     {"homotopy", json::array({{{"eps", evil}, {"converged", true}, {"evaluations", "7 $x$"}}})},
                     {"files", {{"plot", "../x.png"}, {evil, "t.png"}}}};
  const std::string md = helios::report::report_markdown(in);
  const std::string text =
      "3 \\$\\\\input{/etc/hostname}\\$ \\<script\\>x\\</script\\> \\`c\\` \\[a\\](http://e) \\| \\# h";
  EXPECT_NE(md.find("| " + text + " |"), std::string::npos);
  EXPECT_NE(
      md.find(
          "| `timings/3 $\\input{/etc/hostname}$ <script>x</script> 'c' [a](http://e) \\| # h` | *(not a number)* |"),
      std::string::npos);
  EXPECT_NE(md.find("| *(not a number)* | yes | *(not a number)* |  |"), std::string::npos);
  EXPECT_NE(md.find("plot: `../x.png`"), std::string::npos);
  EXPECT_NE(md.find("![" + text + "](t.png)"), std::string::npos);
  EXPECT_EQ(md.find("<script>x</script> `"), std::string::npos);
  // The problem text's own fence line cannot close the report's fence around it.
  EXPECT_NE(md.find("````text\n```\n$x$\n````"), std::string::npos);
}

}  // namespace

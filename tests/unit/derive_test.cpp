#include "helios/pmp/derive.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "helios/io/schema.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;
using helios::symbolic::SymbolTable;
using helios::symbolic::Values;

const std::string kSource = HELIOS_SOURCE_DIR;

const json& s01_spec() {
  static const json spec =
      helios::spec::parse_problem_text(helios::io::read_text(kSource + "/scenarios/S01/problem.txt"), "S01");
  return spec;
}

const json& s01() {
  static const json d = helios::pmp::derive_from_spec(s01_spec());
  return d;
}

// A symbol table with every name a derivation uses, and a random point in sensible ranges.
struct Point {
  SymbolTable table;
  Values values;
  explicit Point(unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(0.6, 1.6), sym(-1, 1), unit(0.2, 1);
    for (const auto& s : s01()["states"]) {
      const std::string x = s["name"], l = s["costate"];
      table.get(x);
      table.get(l);
      values[x] = x == "m" ? unit(rng) : (x[0] == 'r' ? pos(rng) * (sym(rng) < 0 ? -1 : 1) : sym(rng) * 6);
      values[l] = sym(rng);
    }
    for (const auto& p : s01()["parameters"]) {
      table.get(p["name"]);
      values[p["name"]] = p["value"];
    }
    for (const auto& c : s01()["controls"]) table.get(c["name"]);
    values["u"] = unit(rng);
    double n = 0;
    for (const char* a : {"ax", "ay", "az"}) n += (values[a] = sym(rng)) * values[a];
    for (const char* a : {"ax", "ay", "az"}) values[a] /= std::sqrt(n);
    table.get("lambda0");
    table.get("eps");
    values["lambda0"] = unit(rng);
    values["eps"] = unit(rng);
  }
  double eval(const std::string& text) const {
    return helios::symbolic::evaluate(table.parse(text, "test"), table, values);
  }
};

TEST(Derive, S01HasEightShootingVariablesAndEquations) {
  const json& d = s01();
  EXPECT_NO_THROW(helios::io::validate("derivation", d, "derivation"));
  ASSERT_EQ(d["shooting"]["variables"].size(), 8u);
  ASSERT_EQ(d["shooting"]["equations"].size(), 8u);
  EXPECT_EQ(d["shooting"]["variables"][0]["name"], "lambda0");
  bool mass_transversality = false;
  for (const auto& e : d["shooting"]["equations"]) mass_transversality |= e["expression"] == "l_m_tf";
  EXPECT_TRUE(mass_transversality);
  EXPECT_EQ(d["shooting"]["equations"][7]["name"], "normalization");
}

// NOTE: physics check: every costate equation equals -dH/dx by central finite differences of the
// stored Hamiltonian (step 1e-6, so truncation ~1e-12 and round-off ~1e-10 relative).
TEST(Derive, CostateOdesMatchFiniteDifferencesOfH) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    Point p(seed);
    for (std::size_t i = 0; i < s01()["states"].size(); ++i) {
      const std::string x = s01()["states"][i]["name"];
      const double h = 1e-6 * std::max(1.0, std::fabs(p.values[x]));
      Point plus = p, minus = p;
      plus.values[x] += h;
      minus.values[x] -= h;
      const double fd = -(plus.eval(s01()["hamiltonian"]) - minus.eval(s01()["hamiltonian"])) / (2 * h);
      const double stored = p.eval(s01()["costate_odes"][i]["rhs"]);
      EXPECT_TRUE(IsClose(stored, fd, 1e-7, 1e-7)) << "costate of " << x << " at seed " << seed;
    }
  }
}

TEST(Derive, StateOdesAreTheDynamics) {
  Point p(11);
  for (std::size_t i = 0; i < s01()["states"].size(); ++i)
    EXPECT_TRUE(
        IsClose(p.eval(s01()["state_odes"][i]["rhs"]), p.eval(s01()["dynamics"]["state_rhs"][i]), 1e-14, 1e-14));
}

TEST(Derive, ThrottleLawMinimizesH) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Point p(seed);
    const auto& law = s01()["control_law"];
    for (int j = 0; j < 3; ++j) p.values[std::string("a") + "xyz"[j]] = p.eval(law["direction"]["law"][j]);
    const double s0 = p.eval(law["throttle"]["dH_du_at_lower"]);
    const double s1 = p.eval(law["throttle"]["dH_du_at_upper"]);
    const double u_star = s0 >= 0 ? 0 : s1 <= 0 ? 1 : p.eval(law["throttle"]["interior"]);
    p.values["u"] = u_star;
    const double h_star = p.eval(s01()["hamiltonian"]);
    for (double u = 0; u <= 1.0; u += 0.05) {
      Point q = p;
      q.values["u"] = u;
      EXPECT_LE(h_star, q.eval(s01()["hamiltonian"]) + 1e-12) << "u* = " << u_star << " u = " << u;
    }
  }
}

TEST(Derive, OutputIsDeterministic) {
  EXPECT_EQ(helios::pmp::derive_from_spec(s01_spec()).dump(), s01().dump());
}

TEST(Derive, UnsupportedDynamicsNamesTheField) {
  json spec = s01_spec();
  spec["objective"]["kind"] = "minimum_time";
  EXPECT_THROW(helios::pmp::derive_from_spec(spec), std::invalid_argument);
}

}  // namespace

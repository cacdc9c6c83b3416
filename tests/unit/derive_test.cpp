#include "helios/pmp/derive.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

#include "helios/astro/kepler.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/pmp/derivation.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"
#include "helios/verify/verify.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;
using helios::symbolic::SymbolTable;
using helios::symbolic::Values;

const std::string kSource = HELIOS_SOURCE_DIR;

const json& derivation_of(const std::string& scenario) {
  static std::map<std::string, json> cache;
  auto it = cache.find(scenario);
  if (it == cache.end()) {
    const std::string path = kSource + "/scenarios/" + scenario + "/problem.txt";
    it =
        cache
            .emplace(scenario,
                     helios::pmp::derive_from_spec(helios::spec::parse_problem_text(helios::io::read_text(path), path)))
            .first;
  }
  return it->second;
}

const json& s01() {
  return derivation_of("S01");
}

// A symbol table with every name a derivation uses, and a random point in sensible ranges
// (normalized units: positions of order 1, admissible controls).
struct Point {
  SymbolTable table;
  Values values;
  Point(const json& d, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(0.6, 1.6), sym(-1, 1), unit(0.2, 1);
    for (const auto& s : d["states"]) {
      const std::string x = s["name"], l = s["costate"];
      table.get(x);
      table.get(l);
      values[x] = x == "m" ? unit(rng) : (x[0] == 'r' ? pos(rng) * (sym(rng) < 0 ? -1 : 1) : sym(rng) * 6);
      values[l] = sym(rng);
      // The same names at the final time, for endpoint conditions.
      table.get(x + "_tf");
      table.get(l + "_tf");
      values[x + "_tf"] = values[x] * unit(rng);
      values[l + "_tf"] = sym(rng);
    }
    for (const auto& p : d["parameters"]) {
      table.get(p["name"]);
      values[p["name"]] = p.contains("source") ? sym(rng) : p["value"].get<double>();
    }
    std::map<std::string, std::vector<std::string>> unit_vectors;
    for (const auto& c : d["controls"]) {
      table.get(c["name"]);
      if (c["kind"] == "throttle")
        values[c["name"]] = unit(rng);
      else
        unit_vectors[c["kind"]].push_back(c["name"]);
    }
    for (const auto& [kind, names] : unit_vectors) {
      double n = 0, radial = 0;
      for (const auto& a : names) n += (values[a] = sym(rng)) * values[a];
      for (std::size_t j = 0; j < names.size(); ++j) radial += values[names[j]] * values[std::string("r") + "xyz"[j]];
      // A sail normal must point away from the Sun (n.r >= 0).
      const double sign = kind == "sail_normal" && radial < 0 ? -1 : 1;
      for (const auto& a : names) values[a] *= sign / std::sqrt(n);
    }
    for (const char* s : {"lambda0", "eps", "t", "H_tf", "tf_frac"}) {
      table.get(s);
      values[s] = unit(rng);
    }
    for (const auto& v : d["shooting"]["variables"]) table.get(v["name"]);
  }
  double eval(const std::string& text) const {
    return helios::symbolic::evaluate(table.parse(text, "test"), table, values);
  }
};

class EveryScenario : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Derive, EveryScenario, ::testing::Values("S01", "S05", "S06", "S11", "S14"));

TEST_P(EveryScenario, IsValidDeterministicAndSquare) {
  const json& d = derivation_of(GetParam());
  EXPECT_NO_THROW(helios::io::validate("derivation", d, "derivation"));
  EXPECT_EQ(d["shooting"]["variables"].size(), d["shooting"]["equations"].size());
  const std::string path = kSource + "/scenarios/" + GetParam() + "/problem.txt";
  EXPECT_EQ(helios::pmp::derive_from_spec(helios::spec::parse_problem_text(helios::io::read_text(path), path)).dump(),
            d.dump());
}

// NOTE: physics check: every costate equation equals -dH/dx by central finite differences of the
// stored Hamiltonian (step 1e-6, so truncation ~1e-12 and round-off ~1e-10 relative). For J2 this
// is the full 3x3 Jacobian of the J2 acceleration (G6); for the sail the geometric terms of
// (n.rhat)^2/r^2 (G3).
TEST_P(EveryScenario, CostateOdesMatchFiniteDifferencesOfH) {
  const json& d = derivation_of(GetParam());
  for (unsigned seed = 1; seed <= 5; ++seed) {
    Point p(d, seed);
    for (std::size_t i = 0; i < d["states"].size(); ++i) {
      const std::string x = d["states"][i]["name"];
      const double h = 1e-6 * std::max(1.0, std::fabs(p.values[x]));
      Point plus = p, minus = p;
      plus.values[x] += h;
      minus.values[x] -= h;
      const double fd = -(plus.eval(d["hamiltonian"]) - minus.eval(d["hamiltonian"])) / (2 * h);
      const double stored = p.eval(d["costate_odes"][i]["rhs"]);
      EXPECT_TRUE(IsClose(stored, fd, 1e-7, 1e-7)) << "costate of " << x << " at seed " << seed;
    }
  }
}

TEST_P(EveryScenario, StateOdesAreTheDynamics) {
  const json& d = derivation_of(GetParam());
  Point p(d, 11);
  for (std::size_t i = 0; i < d["states"].size(); ++i)
    EXPECT_TRUE(IsClose(p.eval(d["state_odes"][i]["rhs"]), p.eval(d["dynamics"]["state_rhs"][i]), 1e-14, 1e-14));
}

TEST(Derive, J2AddsEveryJacobianEntryToTheCostates) {
  // With J2 the costate of each position depends on all three velocity costates and positions.
  const json& d = derivation_of("S05");
  for (int i = 0; i < 3; ++i) {
    const std::string rhs = d["costate_odes"][i]["rhs"];
    for (const char* lv : {"l_vx", "l_vy", "l_vz"}) EXPECT_NE(rhs.find(lv), std::string::npos) << i << " " << lv;
    EXPECT_NE(rhs.find("J2"), std::string::npos);
  }
  EXPECT_EQ(d["shooting"]["variables"].size(), 8u);
}

// The sail's optimal normal: unit, admissible, and no admissible normal gives a smaller H.
TEST(Derive, SailLawMinimizesHOverTheAdmissibleHemisphere) {
  const json& d = derivation_of("S11");
  const json& sail = d["control_law"]["sail"];
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> sym(-1, 1);
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Point p(d, seed);
    for (const auto& def : sail["definitions"]) {
      p.table.get(def["name"]);
      p.values[def["name"]] = p.eval(def["expression"]);
    }
    double n2 = 0, radial = 0;
    const double r =
        std::sqrt(p.values["rx"] * p.values["rx"] + p.values["ry"] * p.values["ry"] + p.values["rz"] * p.values["rz"]);
    for (int j = 0; j < 3; ++j) {
      const std::string n = sail["controls"][j];
      p.values[n] = p.eval(sail["law"][j]);
      n2 += p.values[n] * p.values[n];
      radial += p.values[n] * p.values[std::string("r") + "xyz"[j]] / r;
    }
    EXPECT_TRUE(IsClose(n2, 1.0, 1e-12, 1e-12));
    EXPECT_GE(radial, -1e-12);
    // H parsed once per point and evaluated at 200 other admissible sail normals.
    const auto hamiltonian = p.table.parse(d["hamiltonian"].get<std::string>(), "test");
    const double h_star = helios::symbolic::evaluate(hamiltonian, p.table, p.values);
    for (int trial = 0; trial < 200; ++trial) {
      Values other = p.values;
      double m2 = 0, dot = 0;
      for (int j = 0; j < 3; ++j) m2 += (other[sail["controls"][j]] = sym(rng)) * other[sail["controls"][j]];
      for (int j = 0; j < 3; ++j) dot += other[sail["controls"][j]] * p.values[std::string("r") + "xyz"[j]];
      for (int j = 0; j < 3; ++j) other[sail["controls"][j]] *= (dot < 0 ? -1 : 1) / std::sqrt(m2);
      EXPECT_LE(h_star, helios::symbolic::evaluate(hamiltonian, p.table, other) + 1e-12) << "seed " << seed;
    }
  }
  EXPECT_EQ(d["states"].size(), 6u);  // no mass (G4)
  EXPECT_EQ(d["shooting"]["variables"].size(), 8u);
}

// Free final time with a moving target: H(tf) = sum lambda_i(tf) * d target_i/dt (nu = lambda(tf)).
TEST(Derive, FreeFinalTimeConditionCarriesTheTargetsMotion) {
  const json& d = derivation_of("S11");
  EXPECT_EQ(d["times"]["final_time"], "free");
  std::string expression;
  for (const auto& e : d["shooting"]["equations"])
    if (e["name"] == "transversality_tf") expression = e["expression"];
  Point p(d, 3);
  double expected = p.values["H_tf"];
  for (const char* s : {"rx", "ry", "rz", "vx", "vy", "vz"})
    expected -= p.values[std::string("l_") + s + "_tf"] * p.values[std::string("arrival_") + s + "_rate"];
  EXPECT_TRUE(IsClose(p.eval(expression), expected, 1e-14, 1e-14)) << expression;
}

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
TEST(Derive, ThrottleLawMinimizesH) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    Point p(s01(), seed);
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

TEST(Derive, MinimumInitialMassFreesM0WithItsTransversality) {
  const json& d = derivation_of("S09");
  const auto& vars = d["shooting"]["variables"];
  int m0 = 0, lm0 = 0;
  for (const auto& v : vars) {
    m0 += v["name"] == "m_t0" && v.value("role", "") == "initial_state" && v["range"][0] == 1.0 ? 1 : 0;
    lm0 += v["name"] == "l_m_t0" ? 1 : 0;
  }
  EXPECT_EQ(m0, 1);
  EXPECT_EQ(lm0, 1);
  std::map<std::string, json> eqs;
  for (const auto& e : d["shooting"]["equations"]) eqs[e["name"]] = e;
  EXPECT_EQ(eqs.at("transversality_m_t0")["expression"], "l_m_t0");
  // m(tf) is fixed (no lambda_m(tf) = 0), except for the last leg alone, where m0 is held.
  EXPECT_EQ(eqs.count("transversality_m"), 0u);
  EXPECT_EQ(eqs.at("psi_arrival_5")["expression"], "-1.0+m_tf");
  EXPECT_EQ(eqs.at("psi_arrival_5")["alone_expression"], "l_m_tf");
}

TEST(Derive, BoundsAreRowsOfPsiWithTheirOwnMultipliers) {
  const json& d = derivation_of("S09");
  std::map<std::string, json> eqs;
  for (const auto& e : d["shooting"]["equations"]) eqs[e["name"]] = e;
  // |v - v_T|^2 - vmax^2 <= 0 at tf: lambda_v(tf) = 2 nu (v - v_T), nu a shooting variable.
  const json& speed = eqs.at("psi_arrival_4");
  EXPECT_EQ(speed["inequality"]["multiplier"], "nu_arrival_4");
  EXPECT_EQ(speed["inequality"]["inactive_expression"], "nu_arrival_4");
  SymbolTable t;
  for (const char* name : {"l_vx_tf", "vx_tf", "arrival_vx", "nu_arrival_4"}) t.get(name);
  const auto same = [&](const std::string& a, const std::string& b) {
    return (t.parse(a, "a") - t.parse(b, "b")).expand().is_zero();
  };
  EXPECT_TRUE(same(eqs.at("transversality_vx")["expression"], "l_vx_tf - 2*nu_arrival_4*(vx_tf - arrival_vx)"));
  // An epoch's window is two bounds on t (start - t <= 0, t - end <= 0); the free-epoch condition
  // carries their multipliers with d psi/dt = -1 and +1.
  const std::string start = eqs.at("psi_nikko_7")["expression"], end = eqs.at("psi_nikko_8")["expression"];
  EXPECT_EQ(start.rfind("-t_nikko+", 0), 0u) << start;
  EXPECT_NE(end.find("+t_nikko"), std::string::npos) << end;
  EXPECT_EQ(eqs.at("psi_nikko_8")["inequality"]["held_when_active"],
            json::parse(R"({"variable": "t_nikko_frac", "value": 1})"));
  const std::string time = eqs.at("time_nikko")["expression"];
  EXPECT_NE(time.find("-nu_nikko_7"), std::string::npos) << time;
  EXPECT_NE(time.find("+nu_nikko_8"), std::string::npos) << time;
}

// The rows of an orbit target, evaluated in km and km/s by the derivation's own parameters.
struct OrbitRowsOf {
  SymbolTable table;
  Values values;
  std::vector<GiNaC::ex> psi;
  double length_km = 1, speed_km_s = 1;
  explicit OrbitRowsOf(const std::string& final_sentence) {
    const std::string text = helios::io::read_text(kSource + "/scenarios/S14/problem.txt");
    const std::string from = "At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.";
    const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
        text.substr(0, text.find(from)) + final_sentence + text.substr(text.find(from) + from.size()), "t"));
    for (const auto& q : d["parameters"]) values[q["name"]] = q["value"].get<double>();
    for (const auto& q : d["parameters"]) table.get(q["name"]);
    for (const char* x : {"rx", "ry", "rz", "vx", "vy", "vz", "m"}) table.get(x);
    length_km = d["units"]["length_km"];
    speed_km_s = length_km / d["units"]["time_s"].get<double>();
    for (const auto& c : d["constraints"])
      if (c["kind"] == "orbit_insertion" || c["kind"] == "state_conditions")
        for (const auto& row : c["psi"]) psi.push_back(table.parse(row, "psi"));
  }
  std::vector<double> at(const std::array<double, 6>& state_km) {
    const char* names[] = {"rx", "ry", "rz", "vx", "vy", "vz"};
    for (int i = 0; i < 6; ++i) values[names[i]] = state_km[i] / (i < 3 ? length_km : speed_km_s);
    values["m"] = 1;
    std::vector<double> out;
    for (const auto& row : psi) out.push_back(helios::symbolic::evaluate(row, table, values));
    return out;
  }
  // The rank of dpsi/dx at a state, by central differences and Gram-Schmidt.
  std::size_t rank(const std::array<double, 6>& state_km) {
    std::vector<std::vector<double>> grad(psi.size(), std::vector<double>(6));
    for (int k = 0; k < 6; ++k) {
      auto plus = state_km, minus = state_km;
      const double h = 1e-6 * (k < 3 ? 42165.0 : 3.0);
      plus[k] += h;
      minus[k] -= h;
      const auto a = at(plus), b = at(minus);
      for (std::size_t j = 0; j < psi.size(); ++j) grad[j][k] = (a[j] - b[j]) / (2 * h);
    }
    std::size_t r = 0;
    std::vector<std::vector<double>> basis;
    for (auto g : grad) {
      double n0 = 0;
      for (double x : g) n0 += x * x;
      for (const auto& b : basis) {
        double d = 0;
        for (int k = 0; k < 6; ++k) d += g[k] * b[k];
        for (int k = 0; k < 6; ++k) g[k] -= d * b[k];
      }
      double n = 0;
      for (double x : g) n += x * x;
      if (n0 > 0 && n > 1e-12 * n0) {
        for (double& x : g) x /= std::sqrt(n);
        basis.push_back(g);
        ++r;
      }
    }
    return r;
  }
};

// A circular orbit of radius a in the plane of inclination i and node W, at argument of latitude u.
std::array<double, 6> circular_state(double a, double i_deg, double node_deg, double u) {
  const double mu = 398600.47, v = std::sqrt(mu / a), i = i_deg * M_PI / 180, W = node_deg * M_PI / 180;
  const double P[3] = {std::cos(W), std::sin(W), 0};
  const double Q[3] = {-std::cos(i) * std::sin(W), std::cos(i) * std::cos(W), std::sin(i)};
  std::array<double, 6> x{};
  for (int k = 0; k < 3; ++k) {
    x[k] = a * (std::cos(u) * P[k] + std::sin(u) * Q[k]);
    x[3 + k] = v * (-std::sin(u) * P[k] + std::cos(u) * Q[k]);
  }
  return x;
}

// An orbit target's psi vanishes along the whole orbit (the anomaly is free) and its rows are
// independent there, also on the circular equatorial orbit where the elements' angles are undefined;
// so do the same orbits written as equations of the final state.
TEST(Derive, AnOrbitTargetsRowsVanishAlongItAndAreIndependent) {
  struct Case {
    std::string sentence;
    double a, i, node;
    std::size_t rows;
  };
  for (const Case& c : std::vector<Case>{
           {"At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.", 42165, 0, 0, 5},
           {"At the final time the spacecraft is on a circular orbit of 7500 km radius inclined 28.5 deg.", 7500, 28.5,
            40, 4},
           {"At the final time the spacecraft is on a circular orbit of radius 26600 km with inclination 55 deg and "
            "node 120 deg.",
            26600, 55, 120, 5},
           // the same orbits written as equations of the state, in other units
           {"At the final time |r| = 42165000 m, r\xC2\xB7v = 0, |r|\xC2\xB7|v|\xC2\xB2 = mu, z = 0 and vz = 0 km/s.",
            42165, 0, 0, 5},
           {"At the final time r = 7500 km, dot(r, v) = 0 and v^2 = mu/r.", 7500, 28.5, 40, 3}}) {
    OrbitRowsOf o(c.sentence);
    ASSERT_EQ(o.psi.size(), c.rows) << c.sentence;
    for (double u : {0.0, 1.0, 2.5, 4.0}) {
      const auto x = circular_state(c.a, c.i, c.node, u);
      for (double r : o.at(x)) EXPECT_NEAR(r, 0, 1e-12) << c.sentence << " u=" << u;
      EXPECT_EQ(o.rank(x), c.rows) << c.sentence << " u=" << u;
    }
    // Off the orbit (a larger radius) some row is not 0.
    double off = 0;
    for (double r : o.at(circular_state(1.01 * c.a, c.i, c.node, 1.0))) off = std::max(off, std::abs(r));
    EXPECT_GT(off, 1e-3) << c.sentence;
  }
}

// With psi fixing no state, the multipliers are shooting variables and every state's
// transversality row an equation: 5 rows, 6 + 1 transversality rows, square with tf free.
TEST(Derive, AnOrbitTargetKeepsItsMultipliersAndEveryTransversalityRow) {
  const json& d = derivation_of("S14");
  std::set<std::string> variables, equations;
  for (const auto& v : d["shooting"]["variables"]) variables.insert(v["name"]);
  for (const auto& e : d["shooting"]["equations"]) equations.insert(e["name"]);
  for (int j = 1; j <= 5; ++j) {
    EXPECT_TRUE(variables.count("nu_arrival_" + std::to_string(j))) << j;
    EXPECT_TRUE(equations.count("psi_arrival_" + std::to_string(j))) << j;
  }
  for (const char* x : {"rx", "ry", "rz", "vx", "vy", "vz", "m"})
    EXPECT_TRUE(equations.count(std::string("transversality_") + x)) << x;
  EXPECT_EQ(variables.size(), 14u);
  EXPECT_EQ(equations.size(), 14u);
}

// A departure anywhere on an orbit given by all its elements: the derivation's x(t0) = X(theta)
// is the state at true anomaly theta (against the library's own elements_to_state, through the
// mean anomaly), and theta is an unknown with its stationarity row lambda(t0).dX/dtheta = 0.
TEST(Derive, ADepartureOrbitsInitialStateIsTheOrbitAtItsAnomaly) {
  const std::string path = kSource + "/tests/fixtures/problems/gto_anywhere_to_geo.txt";
  const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(helios::io::read_text(path), path));
  SymbolTable table;
  Values values;
  for (const auto& q : d["parameters"]) values[q["name"]] = q["value"].get<double>();
  for (const auto& q : d["parameters"]) table.get(q["name"]);
  for (const char* l : {"l_rx_t0", "l_ry_t0", "l_rz_t0", "l_vx_t0", "l_vy_t0", "l_vz_t0", "l_m_t0", "theta_departure"})
    table.get(l);
  const double length_km = d["units"]["length_km"], speed_km_s = length_km / d["units"]["time_s"].get<double>();
  const auto state_at = [&](double theta) {
    values["theta_departure"] = theta;
    std::array<double, 6> x{};
    for (const auto& v : d["initial_values"]) {
      const std::string s = v["state"];
      const char* names[] = {"rx", "ry", "rz", "vx", "vy", "vz"};
      for (int k = 0; k < 6; ++k)
        if (s == names[k])
          x[k] = helios::symbolic::evaluate(table.parse(v["value"], "x0"), table, values) *
                 (k < 3 ? length_km : speed_km_s);
    }
    return x;
  };
  const double a = 26571.428571428576, e = 0.75, i = 7.004267441546314 * M_PI / 180;
  for (double theta : {0.0, 1.0, 2.5, M_PI, 4.0, 5.5}) {
    const double E = 2 * std::atan(std::sqrt((1 - e) / (1 + e)) * std::tan(theta / 2));
    const auto expected = helios::astro::elements_to_state({a, e, i, 0, 0, E - e * std::sin(E)}, 398600.47);
    const auto x = state_at(theta);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(x[k], expected[k], 1e-9 * (k < 3 ? a : 10)) << theta << " " << k;
  }
  // The stationarity row is lambda(t0).dX/dtheta (nu = -lambda(t0)), dX/dtheta by differences.
  std::string row;
  for (const auto& q : d["shooting"]["equations"])
    if (q["name"] == "stationarity_departure_theta_departure") row = q["expression"];
  ASSERT_FALSE(row.empty());
  const double lambda[6] = {0.3, -0.2, 0.5, 0.7, -0.1, 0.4};
  const char* costates[] = {"l_rx_t0", "l_ry_t0", "l_rz_t0", "l_vx_t0", "l_vy_t0", "l_vz_t0"};
  for (int k = 0; k < 6; ++k) values[costates[k]] = lambda[k];
  values["l_m_t0"] = 0.9;
  const double theta = 2.0, step = 1e-6;
  const auto plus = state_at(theta + step), minus = state_at(theta - step);
  double expected = 0;
  for (int k = 0; k < 6; ++k)
    expected += lambda[k] * (plus[k] - minus[k]) / (2 * step) / (k < 3 ? length_km : speed_km_s);
  values["theta_departure"] = theta;
  EXPECT_NEAR(helios::symbolic::evaluate(table.parse(row, "row"), table, values), expected, 1e-7 * std::abs(expected));
}

// A departure orbit whose node or argument of periapsis is left free: x(t0) = X(theta, node, argp)
// is the state of the orbit with those elements (elements_to_state), each free angle an unknown
// with its stationarity row; a free node is refused where the problem does not change when turned
// about z, and an element that is undefined cannot be free.
TEST(Derive, ADepartureOrbitsFreeNodeAndPeriapsisAreUnknownsOfItsState) {
  const std::string text = helios::io::read_text(kSource + "/tests/fixtures/problems/gto_anywhere_to_geo.txt");
  const auto derive_with = [&](const std::string& elements, const std::string& target) {
    std::string t = text;
    const std::string from = "node 0 deg and argument of perigee 0 deg, with any true anomaly";
    t.replace(t.find(from), from.size(), elements);
    const std::string geo = "the circular equatorial orbit of radius 42165 km";
    t.replace(t.find(geo), geo.size(), target);
    return helios::pmp::derive_from_spec(helios::spec::parse_problem_text(t, "t"));
  };
  const json d = derive_with("with any node, any argument of perigee and any true anomaly",
                             "the circular orbit of radius 42165 km inclined 1 deg with node 20 deg");
  std::vector<std::string> unknowns, rows;
  for (const auto& v : d["shooting"]["variables"])
    if (v.value("role", "") == "initial_state") unknowns.push_back(v["name"]);
  for (const auto& q : d["shooting"]["equations"])
    if (q["name"].get<std::string>().rfind("stationarity_departure_", 0) == 0) rows.push_back(q["name"]);
  EXPECT_EQ(unknowns, (std::vector<std::string>{"theta_departure", "node_departure", "argp_departure"}));
  EXPECT_EQ(rows.size(), 3u);
  SymbolTable table;
  Values values;
  for (const auto& q : d["parameters"]) values[q["name"]] = q["value"].get<double>();
  for (const auto& q : d["parameters"]) table.get(q["name"]);
  for (const auto& u : unknowns) table.get(u);
  const double length_km = d["units"]["length_km"], speed_km_s = length_km / d["units"]["time_s"].get<double>();
  const double a = 26571.428571428576, e = 0.75, i = 7.004267441546314 * M_PI / 180;
  for (const auto& [theta, node, argp] :
       std::vector<std::array<double, 3>>{{0.5, 1.0, 2.0}, {2.5, 4.0, 0.3}, {5.0, 6.0, 3.5}}) {
    values["theta_departure"] = theta;
    values["node_departure"] = node;
    values["argp_departure"] = argp;
    const double E = 2 * std::atan(std::sqrt((1 - e) / (1 + e)) * std::tan(theta / 2));
    const auto expected = helios::astro::elements_to_state({a, e, i, node, argp, E - e * std::sin(E)}, 398600.47);
    for (const auto& v : d["initial_values"]) {
      const char* names[] = {"rx", "ry", "rz", "vx", "vy", "vz"};
      for (int k = 0; k < 6; ++k) {
        if (v["state"] != names[k]) continue;
        EXPECT_NEAR(
            helios::symbolic::evaluate(table.parse(v["value"], "x0"), table, values) * (k < 3 ? length_km : speed_km_s),
            expected[k], 1e-9 * (k < 3 ? a : 10))
            << theta << " " << node << " " << argp << " " << k;
      }
    }
  }
  const auto error_of = [&](const std::string& elements, const std::string& target) {
    try {
      derive_with(elements, target);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // GEO, equatorial, turns into itself about z: every node gives the same transfer
  EXPECT_NE(error_of("argument of perigee 0 deg, with any node", "the circular equatorial orbit of radius 42165 km")
                .find("every node gives the same transfer"),
            std::string::npos);
  EXPECT_EQ(error_of("argument of perigee 0 deg, with any node",
                     "the circular orbit of radius 42165 km inclined 1 deg "
                     "with node 20 deg"),
            "");
}

// A final-state objective needs a fixed final time; an engine at full throttle burns a fixed
// amount of fuel, so it cannot minimize it.
TEST(Derive, AFinalStateObjectiveNeedsAFixedTimeAndFullThrottleNoFuelObjective) {
  const std::string path = kSource + "/tests/fixtures/problems/maximum_radius.txt";
  const json spec = helios::spec::parse_problem_text(helios::io::read_text(path), path);
  json free_time = spec;
  free_time["time"] = {{"t0_days", 0.0}, {"final_time", "free"}, {"tof_min_days", 0.0}, {"tof_max_days", 300.0}};
  EXPECT_THROW(helios::pmp::derive_from_spec(free_time), std::invalid_argument);
  json fuel = spec;
  fuel["objective"]["kind"] = "minimum_fuel";
  EXPECT_THROW(helios::pmp::derive_from_spec(fuel), std::invalid_argument);
  // The Mayer term enters the transversality: lambda_r(tf) = -lambda0 r/|r| + nu^T dpsi/dr.
  const json d = helios::pmp::derive_from_spec(spec);
  for (const auto& e : d["shooting"]["equations"])
    if (e["name"] == "transversality_rx") {
      const std::string row = e["expression"];
      EXPECT_NE(row.find("(rx_tf^2+ry_tf^2+rz_tf^2)^(-1/2)*lambda0*rx_tf"), std::string::npos) << row;
    }
}

// Equations of the final state that do not fix independent directions, or more of them than there
// are states, are refused naming the condition; their rows are the problem's ψ with unknown
// multipliers, every state's transversality row an equation.
TEST(Derive, StateConditionsAreIndependentRowsWithUnknownMultipliers) {
  const std::string text = helios::io::read_text(kSource + "/scenarios/S14/problem.txt");
  const std::string from = "At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.";
  const auto spec_with = [&](const std::string& sentence) {
    return helios::spec::parse_problem_text(
        text.substr(0, text.find(from)) + sentence + text.substr(text.find(from) + from.size()), "t");
  };
  const auto error_of = [&](const std::string& sentence) {
    try {
      helios::pmp::derive_from_spec(spec_with(sentence));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("At the final time |r| = 42165 km and r = 42165000 m.")
                .find("target/conditions/1 ('r = 42165 km') is not independent of the conditions before it"),
            std::string::npos);
  EXPECT_NE(error_of("At the final time x = 42165 km, y = 0 km, z = 0 km, vx = 0, vy = 3 km/s, vz = 0, m = 1000 kg and "
                     "r = 42165 km.")
                .find("8 conditions on 7 states"),
            std::string::npos);
  const json d = helios::pmp::derive_from_spec(spec_with("At the final time r = 42165 km, r.v = 0 and v^2 = mu/r."));
  int multipliers = 0, transversality = 0;
  for (const auto& v : d["shooting"]["variables"])
    multipliers += v["name"].get<std::string>().rfind("nu_arrival_", 0) == 0;
  for (const auto& e : d["shooting"]["equations"])
    transversality += e["name"].get<std::string>().rfind("transversality_", 0) == 0;
  EXPECT_EQ(multipliers, 3);
  EXPECT_EQ(transversality, 8);  // seven states and the final time
}

// A condition's value must stay a number in the normalized units: r^40 = 1e300 km^40 about the
// Sun is 1e300 / AU^40, and AU^40 is beyond a double (the row became r^40 = 0, r = 0). Refused
// naming the row and the value; a power the units can hold is derived.
TEST(Derive, AStateConditionsValueBeyondADoubleInNormalizedUnitsIsRefused) {
  const std::string text = helios::io::read_text(kSource + "/scenarios/S01/problem.txt");
  const std::string from = text.substr(text.find("At the final time"));
  const auto derive_with = [&](const std::string& sentence) {
    return helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
        text.substr(0, text.find(from)) + sentence + "\nMinimize the fuel consumption.\n", "t"));
  };
  try {
    derive_with("At the final time r^40 = 1e300 km^40.");
    FAIL() << "derived";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "constraint 'arrival': target/conditions/0/equals: 1e+300 km^40 in the normalized units (length "
              "149597870.7 km, time 31557600 s, mass 1000 kg) is beyond the range of a double (magnitudes 2.2e-308 to "
              "1.8e308), state the condition with a lower power (e.g. 'r = Q' for 'r^40 = Q^40')");
  }
  EXPECT_NO_THROW(derive_with("At the final time r^2 = 5.6e16 km^2."));
}

// A target orbit's rows also hold on its mirrors: the plane run the other way (h along -n) and the
// periapsis opposite the stated one (e_vec along -P). The side conditions h.n > 0 and e_vec.P > 0
// tell them apart: at states on the stated orbit and on each mirror (built here from P and Q read
// off the orbit's own state at periapsis) every row vanishes, and only the mirror fails its side.
TEST(Derive, ATargetOrbitsSideConditionsRejectItsMirrorsThatMeetItsRows) {
  std::string text = helios::io::read_text(kSource + "/scenarios/S14/problem.txt");
  const std::string geo = "the circular equatorial orbit of radius 42165 km";
  text.replace(text.find(geo), geo.size(),
               "an orbit with semi-major axis 30000 km, eccentricity 0.3, inclination 20 deg, node 40 deg and "
               "argument of perigee 60 deg");
  const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, "t"));
  const json& arrival = d["constraints"][1];
  ASSERT_EQ(arrival["must_be_positive"].size(), 2u);
  SymbolTable table;
  Values values;
  for (const auto& q : d["parameters"]) values[q["name"]] = q["value"].get<double>(), table.get(q["name"]);
  for (const char* x : {"rx", "ry", "rz", "vx", "vy", "vz"}) table.get(x);
  const double length_km = d["units"]["length_km"], speed_km_s = length_km / d["units"]["time_s"].get<double>();
  const double mu = 398600.47, a = 30000, e = 0.3, p = a * (1 - e * e), deg = M_PI / 180;
  const auto periapsis = helios::astro::elements_to_state({a, e, 20 * deg, 40 * deg, 60 * deg, 0}, mu);
  std::array<double, 3> P{}, Q{};
  const double rp = std::hypot(periapsis[0], periapsis[1], periapsis[2]);
  const double vp = std::hypot(periapsis[3], periapsis[4], periapsis[5]);
  for (int k = 0; k < 3; ++k) P[k] = periapsis[k] / rp, Q[k] = periapsis[3 + k] / vp;
  const auto evaluate = [&](const json& list, double theta, double p_sign, double q_sign) {
    const double radius = p / (1 + e * std::cos(theta)), speed = std::sqrt(mu / p);
    const char* names[] = {"rx", "ry", "rz", "vx", "vy", "vz"};
    for (int k = 0; k < 3; ++k) {
      values[names[k]] = radius * (std::cos(theta) * p_sign * P[k] + std::sin(theta) * q_sign * Q[k]) / length_km;
      values[names[3 + k]] =
          speed * (-std::sin(theta) * p_sign * P[k] + (e + std::cos(theta)) * q_sign * Q[k]) / speed_km_s;
    }
    std::vector<double> out;
    for (const auto& row : list)
      out.push_back(
          helios::symbolic::evaluate(table.parse(row.is_string() ? row : row["expression"], "row"), table, values));
    return out;
  };
  for (const double theta : {0.3, 2.0, 4.5}) {
    // stated, the plane's mirror (Q reversed), the periapsis' (P and Q reversed)
    for (const auto& [p_sign, q_sign] : std::vector<std::pair<double, double>>{{1, 1}, {1, -1}, {-1, -1}}) {
      for (const double row : evaluate(arrival["psi"], theta, p_sign, q_sign)) EXPECT_NEAR(row, 0, 1e-12) << theta;
      const std::vector<double> sides = evaluate(arrival["must_be_positive"], theta, p_sign, q_sign);
      EXPECT_EQ(sides[0] > 0, q_sign * p_sign > 0) << "h.n at " << theta << " " << p_sign << q_sign;
      EXPECT_EQ(sides[1] > 0, p_sign > 0) << "e_vec.P at " << theta << " " << p_sign << q_sign;
    }
  }
}

// An orbit on the way: its rows in the state just before the event, its multipliers unknowns, the
// state carried over; the costates jump by nu^T dc/dx-. helios-verify recomputes it all,
// including H(tf) = 0 with an H before and after the event declared too.
TEST(Derive, AnOrbitOnTheWayIsAnEventWithTheOrbitsRowsAndAContinuousState) {
  std::string text = helios::io::read_text(kSource + "/scenarios/S14/problem.txt");
  const std::string tof = "The time of flight is free, at most 2 days.";
  text.replace(
      text.find(tof), tof.size(),
      tof + " The spacecraft passes through the circular orbit of radius 30000 km between day 0.05 and day 1.");
  const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, "t"));
  ASSERT_EQ(d["events"].size(), 1u);
  const json& e = d["events"][0];
  EXPECT_EQ(e["kind"], "orbit_insertion");
  EXPECT_EQ(e["psi"][0], "-a_orbit+sqrt(rx_orbit_m^2+ry_orbit_m^2+rz_orbit_m^2)");
  EXPECT_EQ(e["psi"][1], "rx_orbit_m*vx_orbit_m+ry_orbit_m*vy_orbit_m+rz_orbit_m*vz_orbit_m");
  for (const auto& entry : e["state_map"])
    EXPECT_EQ(entry["expression"], entry["state"].get<std::string>() + "_orbit_m");
  int multipliers = 0;
  for (const auto& v : d["shooting"]["variables"])
    multipliers += v["name"].get<std::string>().rfind("nu_orbit_", 0) == 0;
  EXPECT_EQ(multipliers, 5);  // three rows of the orbit, two of the window
  const json report = helios::verify::verify_derivation(d, {});
  EXPECT_EQ(report["verdict"], "pass") << report.dump(1);
}

TEST(Derive, SailWithFuelObjectiveIsRefused) {
  const std::string path = kSource + "/scenarios/S11/problem.txt";
  json spec = helios::spec::parse_problem_text(helios::io::read_text(path), path);
  spec["objective"]["kind"] = "minimum_fuel";
  EXPECT_THROW(helios::pmp::derive_from_spec(spec), std::invalid_argument);
}

helios::pmp::Problem problem_of(const std::string& scenario) {
  const std::string path = kSource + "/scenarios/" + scenario + "/problem.txt";
  return helios::pmp::build_problem(helios::spec::parse_problem_text(helios::io::read_text(path), path));
}

// The typed derivation's canonical system, exactly (not numerically): x' = dH/dlambda is the
// dynamics and lambda' = -dH/dx, with H = lambda0 L + lambda^T f.
TEST(Derivation, CanonicalSystemIsThePartialsOfH) {
  for (const char* scenario : {"S01", "S05", "S11"}) {
    const helios::pmp::Derivation d = helios::pmp::derive_conditions(problem_of(scenario));
    auto S = d.problem.symbols;
    GiNaC::ex H = S.get("lambda0") * d.problem.running_cost;
    for (std::size_t i = 0; i < d.problem.states.size(); ++i)
      H += S.get(helios::derivation::names::costate(d.problem.states[i].name)) * d.problem.f[i];
    EXPECT_TRUE((d.hamiltonian - H).expand().is_zero()) << scenario;
    ASSERT_EQ(d.costate_odes.size(), d.problem.states.size());
    for (std::size_t i = 0; i < d.problem.states.size(); ++i) {
      const std::string& x = d.problem.states[i].name;
      EXPECT_TRUE((d.state_odes[i] - d.problem.f[i]).expand().is_zero()) << scenario << " " << x;
      EXPECT_TRUE((d.costate_odes[i] + d.hamiltonian.diff(S.get(x))).expand().is_zero()) << scenario << " " << x;
    }
  }
}

// S01's control law: the primer vector for the direction, a smoothed throttle whose switching
// function is dH/du at u = 0 and eps = 0; a square shooting system; the artifact is its text.
TEST(Derivation, S01ControlLawAndShootingSystem) {
  const helios::pmp::Problem problem = problem_of("S01");
  const helios::pmp::Derivation d = helios::pmp::derive_conditions(problem);
  ASSERT_TRUE(d.control.direction.has_value());
  EXPECT_NE(d.control.direction->reason.find("dH/da = k*(l_vx, l_vy, l_vz)"), std::string::npos);
  EXPECT_FALSE(d.control.sail.has_value());
  ASSERT_TRUE(d.control.throttle.has_value());
  EXPECT_TRUE(d.smoothed);
  auto S = d.problem.symbols;
  const GiNaC::ex dHdu = d.hamiltonian.diff(S.get("u"));
  GiNaC::exmap on_law = {{S.get("u"), 0}, {S.get("eps"), 0}};
  for (std::size_t j = 0; j < 3; ++j) on_law[S.get(d.control.direction->controls[j])] = d.control.direction->law[j];
  const GiNaC::ex difference = dHdu.subs(on_law) - d.control.throttle->switching_function;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> value(0.2, 1.5);
  Values at;
  for (const auto& name : helios::symbolic::free_symbols(difference)) at[name] = value(rng);
  EXPECT_TRUE(IsClose(helios::symbolic::evaluate(difference, S, at), 0, 1e-14, 0));
  EXPECT_EQ(d.shooting.variables.size(), d.shooting.equations.size());
  EXPECT_EQ(d.shooting.variables.front().name, "lambda0");
  EXPECT_EQ(d.shooting.equations.back().name, "normalization");
  EXPECT_EQ(helios::pmp::derivation_json(d).dump(), helios::pmp::derive(problem).dump());
}

// A rendezvous with a 30-day stay (S07) leaves from the target's state: the position and
// velocity costates after it are shooting variables with jump rows, the mass's is explicit.
TEST(Derivation, CostatesAfterAStayAreShootingVariables) {
  const helios::pmp::Derivation d = helios::pmp::derive_conditions(problem_of("S07"));
  ASSERT_EQ(d.events.size(), 3u);
  for (const auto& e : d.events) {
    ASSERT_EQ(e.costate_map.size(), 7u);
    EXPECT_EQ(e.psi.size(), e.multipliers.size());
    for (std::size_t s = 0; s < 6; ++s) EXPECT_TRUE(e.costate_map[s].shooting_variable) << e.event.id << " " << s;
    EXPECT_FALSE(e.costate_map[6].shooting_variable) << e.event.id;
  }
  EXPECT_EQ(d.shooting.variables.size(), d.shooting.equations.size());
}

}  // namespace

namespace {

// The message of the std::invalid_argument parsing `text` throws, "" when it parses.
std::string parse_error(const std::string& text) {
  helios::symbolic::SymbolTable symbols;
  symbols.get("x");
  try {
    symbols.parse(text, "d.json: field /hamiltonian");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Found by the json_derivation fuzz target: GiNaC's reason quoted a lone byte of a character it
// does not know ("\xd3"), and the 200-byte cut could split one; helios-verify then failed to
// write its report (nlohmann's type_error 316, invalid UTF-8) with exit 1.
TEST(SymbolicParse, TheErrorOfATextWithAForeignCharacterIsValidUtf8) {
  const auto valid = [](const std::string& s) {
    return helios::io::parse_json_text(helios::io::json(s).dump(), "m").get<std::string>() == s;
  };
  const std::string foreign = parse_error("x+\xd3\x8dx");
  EXPECT_NE(foreign.find("cannot parse expression 'x+\xd3\x8dx'"), std::string::npos) << foreign;
  EXPECT_TRUE(valid(foreign)) << foreign;
  // 199 ASCII bytes, then a 2-byte character across the cut at 200.
  const std::string cut = parse_error(std::string(199, 'x') + "\xd3\x8d" + "+");
  EXPECT_NE(cut.find("'" + std::string(199, 'x') + "...'"), std::string::npos) << cut;
  EXPECT_TRUE(valid(cut)) << cut;
}

TEST(SymbolicParse, AnExpressionBeyondItsBoundsIsAnErrorNamingTheFieldNotACrash) {
  using helios::symbolic::kMaxExpressionDepth;
  // 7,800 nested parentheses overflowed GiNaC's recursive parser.
  const std::string deep = std::string(7800, '(') + "x" + std::string(7800, ')');
  const std::string err = parse_error(deep);
  EXPECT_EQ(err.rfind("d.json: field /hamiltonian: cannot parse expression '((((", 0), 0u) << err;
  EXPECT_NE(err.find("...': parentheses nested deeper than 256 levels"), std::string::npos) << err;
  EXPECT_LT(err.size(), 400u);
  const std::string at_limit =
      std::string(kMaxExpressionDepth, '(') + "x" + std::string(kMaxExpressionDepth, ')') + "+(x)*(x)";
  EXPECT_EQ(parse_error(at_limit), "");
  std::string wide = "x";
  while (wide.size() <= helios::symbolic::kMaxExpressionChars) wide += "+x";
  EXPECT_NE(parse_error(wide).find("characters; the limit is 1048576"), std::string::npos);
}

}  // namespace

namespace {

// The estimate of expand()'s work bounds the terms from above (like terms may combine), is exact
// for a power of a sum of distinct terms (the multinomial count), and counts what expand()
// multiplies out inside a function's argument.
TEST(SymbolicParse, ExpandedTermsBoundTheWorkOfExpand) {
  helios::symbolic::SymbolTable symbols;
  for (const char* name : {"x", "y", "z"}) symbols.get(name);
  const auto terms = [&](const std::string& text) {
    return helios::symbolic::expanded_terms(symbols.parse(text, "test"));
  };
  for (const char* text : {"(x+y+z)^7", "(x+y)*(y+z)*(x+z+1)", "x^3*y-z"})
    EXPECT_GE(terms(text) + 1e-9, static_cast<double>(symbols.parse(text, "test").expand().nops())) << text;
  EXPECT_NEAR(terms("(x+y)*(y+z)*(x+z+1)"), 12, 1e-9);
  EXPECT_NEAR(terms("(x+y+z)^7"), 36, 1e-9);  // C(9, 7)
  EXPECT_NEAR(terms("sin((x+y)^5)"), 6, 1e-9);
  EXPECT_NEAR(terms("1/(x+y+z)^3"), 3, 1e-9);
}

// (x+y+z+vx+vy+vz)^40 made helios-derive run past 240 s at 1.1 GB: it is refused at once, by
// its field, and an expression at the scenarios' size is accepted.
TEST(SymbolicParse, AnExpressionWhoseExpansionIsBeyondTheBudgetIsRefused) {
  helios::symbolic::SymbolTable symbols;
  for (const char* name : {"x", "y", "z", "vx", "vy", "vz"}) symbols.get(name);
  try {
    symbols.parse("(x+y+z+vx+vy+vz)^40", "s.json: field /dynamics/perturbations (a)/components/0");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "s.json: field /dynamics/perturbations (a)/components/0: expression '(x+y+z+vx+vy+vz)^40' (or a "
                 "first derivative of it) would expand to about 1.2e+06 terms; the limit of the symbolic work is "
                 "2e+04 terms");
  }
  // 6,188 terms (4,368 in a first derivative) pass; 20,349 do not.
  EXPECT_NO_THROW(symbols.parse("(x+y+z+vx+vy+vz)^12", "test"));
  EXPECT_THROW(symbols.parse("(x+y+z+vx+vy+vz)^16", "test"), std::invalid_argument);
}

// A spec magnitude beyond double precision was blamed on the output schema ("output derivation:
// ... /parameters/0/value: Value type not permitted"): it is refused by its meaning.
TEST(Derive, AMagnitudeBeyondDoublePrecisionIsRefusedByItsMeaning) {
  const std::string path = kSource + "/scenarios/S01/problem.txt";
  const json s01 = helios::spec::parse_problem_text(helios::io::read_text(path), path);
  const auto error = [&](const char* pointer, double value) {
    json spec = s01;
    spec[json::json_pointer(pointer)] = value;
    try {
      helios::pmp::build_problem(spec);
    } catch (const std::domain_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("/central_body/mu_km3_s2", 1e308)
                .rfind("the gravitational parameter of the central body "
                       "(parameter mu) is not finite in normalized units",
                       0),
            0u);
  EXPECT_EQ(error("/time/tof_days", 1e306).rfind("a time of the problem", 0), 0u);
  EXPECT_EQ(error("/spacecraft/initial_mass_kg", 1e308).rfind("field /spacecraft: the maximum thrust is 0", 0), 0u);
  EXPECT_EQ(error("/spacecraft/isp_s", 3000), "");
}

}  // namespace

// Found by the json_spec fuzz target: a body's name went into a parameter's source
// ("ephemeris:<body>:tf") as it was, and a name with a space made a derivation its own schema
// refuses. The spec's schema now asks of a body's name what the parser does (NAME).
TEST(Derive, ABodyNameThatIsNoNameIsRefusedWhereTheSpecIsRead) {
  const std::string path = kSource + "/scenarios/S02/problem.txt";
  json spec = helios::spec::parse_problem_text(helios::io::read_text(path), path);
  helios::io::validate("spec", spec, "spec.json");
  spec["constraints"][1]["target"]["body"] = "Ma rs";
  try {
    helios::io::validate("spec", spec, "spec.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_NE(std::string(e.what()).find("spec.json: spec schema violation at /constraints/1/target"),
              std::string::npos)
        << e.what();
  }
}

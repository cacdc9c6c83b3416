// helios-verify's engine on the builtin S01 derivation and on deliberately broken copies of it.
#include "helios/verify/verify.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>

#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;

// The derivation of a problem text, its path from the source tree.
json derive_text(const std::string& relative) {
  const std::string path = HELIOS_SOURCE_DIR "/" + relative;
  return helios::pmp::derive_from_spec(helios::spec::parse_problem_text(helios::io::read_text(path), path));
}

json derive(const std::string& scenario) {
  return derive_text("scenarios/" + scenario + "/problem.txt");
}

const json& s01() {
  static const json derivation = derive("S01");
  return derivation;
}

const json& s05() {
  static const json derivation = derive("S05");
  return derivation;
}

const json& s06() {
  static const json derivation = derive("S06");
  return derivation;
}

const json& s11() {
  static const json derivation = derive("S11");
  return derivation;
}

json verify(const json& derivation) {
  json report = helios::verify::verify_derivation(derivation, {});
  helios::io::validate("verify", report, "verify_test");  // every report must satisfy the schema
  return report;
}

std::set<std::string> failed_ids(const json& report) {
  std::set<std::string> ids;
  for (const auto& c : report["checks"])
    if (c["verdict"] == "fail") ids.insert(c["id"].get<std::string>());
  return ids;
}

const json& check(const json& report, const std::string& id) {
  for (const auto& c : report["checks"])
    if (c["id"] == id) return c;
  throw std::runtime_error("no check " + id);
}

json& costate_ode(json& d, const std::string& name) {
  for (auto& e : d["costate_odes"])
    if (e["costate"] == name) return e;
  throw std::runtime_error("no costate ODE " + name);
}

json& equation(json& d, const std::string& name) {
  for (auto& e : d["shooting"]["equations"])
    if (e["name"] == name) return e;
  throw std::runtime_error("no equation " + name);
}

TEST(Verify, BuiltinDerivationPassesEveryCheck) {
  const json r = verify(s01());
  EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  EXPECT_EQ(r["summary"]["failed"], 0);
  EXPECT_EQ(r["feedback"], "");
  EXPECT_EQ(r["problem"]["id"], "S01");
  EXPECT_EQ(r["derivation_producer"]["tool"], "helios-derive");
  for (const auto& c : r["checks"]) {
    EXPECT_EQ(c["verdict"], "pass") << c["id"] << ": " << c["feedback"];
    EXPECT_LE(c["max_rel_error"].get<double>(), 1e-9) << c["id"];
  }
  // The builtin derivation is also shown exactly, item by item.
  for (const std::string id :
       {"hamiltonian", "state_ode:vx", "costate_ode:l_rx", "costate_ode:l_m", "control_direction", "throttle_switching",
        "throttle_dH_du_at_lower", "throttle_interior", "transversality:m", "endpoint:arrival_1", "normalization"})
    EXPECT_TRUE(check(r, id)["exact"].get<bool>()) << id;
  // One check per state ODE and costate ODE, and the expected family of other checks.
  for (const std::string id : {"state_ode:m", "costate_ode:l_vz", "throttle_dH_du_at_upper", "throttle_convexity",
                               "throttle_law", "endpoint:arrival_6", "count", "shooting_variables", "state_usage"})
    EXPECT_NO_THROW(check(r, id)) << id;
}

TEST(Verify, IsDeterministicForASeed) {
  EXPECT_EQ(verify(s01()).dump(), verify(s01()).dump());
}

TEST(Verify, FlippedSignOfCostateEquationFailsOnlyThatEquation) {
  json d = s01();
  auto& e = costate_ode(d, "l_rx");
  e["rhs"] = "-(" + e["rhs"].get<std::string>() + ")";
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "fail");
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_ode:l_rx"});
  const std::string fb = check(r, "costate_ode:l_rx")["feedback"];
  EXPECT_NE(fb.find("costate_odes[l_rx]"), std::string::npos) << fb;
  EXPECT_NE(fb.find("expected -dH/drx = "), std::string::npos) << fb;
  EXPECT_NE(fb.find("flipped"), std::string::npos) << fb;
  EXPECT_NE(fb.find("relative difference"), std::string::npos) << fb;
  EXPECT_GT(check(r, "costate_ode:l_rx")["max_rel_error"].get<double>(), 1e-3);
  EXPECT_NE(r["feedback"].get<std::string>().find(fb), std::string::npos);
}

TEST(Verify, FlippedSignOfOneTermIsNamed) {
  json d = s01();
  std::string rhs = costate_ode(d, "l_rx")["rhs"];
  const std::string term = "-3*(rx^2+ry^2+rz^2)^(-5/2)*l_vy*mu*rx*ry";
  ASSERT_NE(rhs.find(term), std::string::npos) << rhs;
  rhs.replace(rhs.find(term), 1, "+");
  costate_ode(d, "l_rx")["rhs"] = rhs;
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_ode:l_rx"});
  const std::string fb = check(r, "costate_ode:l_rx")["feedback"];
  EXPECT_NE(fb.find("the sign of " + term + " is flipped"), std::string::npos) << fb;
}

TEST(Verify, EquivalentButDifferentlyWrittenCostateEquationPasses) {
  json d = s01();
  costate_ode(d, "l_rx")["rhs"] = "mu*(rx^2+ry^2+rz^2)^(-5/2)*(l_vx*(ry^2+rz^2-2*rx^2) - 3*rx*(l_vy*ry + l_vz*rz))";
  costate_ode(d, "l_ry")["rhs"] =
      "mu*l_vy/sqrt(rx^2+ry^2+rz^2)^3 - 3*mu*ry*(l_vx*rx+l_vy*ry+l_vz*rz)/(rx^2+ry^2+rz^2)^(5/2)";
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  EXPECT_TRUE(check(r, "costate_ode:l_rx")["exact"].get<bool>());
}

TEST(Verify, MissingGeometricTermFails) {
  json d = s01();
  costate_ode(d, "l_rx")["rhs"] = "(rx^2+ry^2+rz^2)^(-3/2)*l_vx*mu";  // the 3*... terms dropped
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_ode:l_rx"});
  const std::string fb = check(r, "costate_ode:l_rx")["feedback"];
  EXPECT_NE(fb.find("lacks the term(s)"), std::string::npos) << fb;
}

TEST(Verify, WrongSwitchingFunctionFails) {
  json d = s01();
  // Sign of the primer vector term flipped.
  d["control_law"]["throttle"]["switching_function"] =
      "-Tmax*c^(-1)*l_m+Tmax*m^(-1)*sqrt(l_vx^2+l_vy^2+l_vz^2)+Tmax*c^(-1)*lambda0";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"throttle_switching"});
  const std::string fb = check(r, "throttle_switching")["feedback"];
  EXPECT_NE(fb.find("switching_function"), std::string::npos) << fb;
  EXPECT_NE(fb.find("sqrt(l_vx^2+l_vy^2+l_vz^2)"), std::string::npos) << fb;
}

TEST(Verify, SwitchingFunctionStillInTheDirectionFails) {
  json d = s01();
  d["control_law"]["throttle"]["switching_function"] =
      "-Tmax*c^(-1)*l_m+Tmax*m^(-1)*(ax*l_vx+ay*l_vy+az*l_vz)+Tmax*c^(-1)*lambda0";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"throttle_switching"});
  EXPECT_NE(check(r, "throttle_switching")["feedback"].get<std::string>().find("must not depend on ax"),
            std::string::npos);
}

TEST(Verify, DirectionLawThatMaximizesHFails) {
  json d = s01();
  for (auto& l : d["control_law"]["direction"]["law"]) l = "-(" + l.get<std::string>() + ")";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"control_direction"});
  EXPECT_NE(check(r, "control_direction")["feedback"].get<std::string>().find("maximizes H"), std::string::npos);
}

TEST(Verify, ConcaveSmoothingFailsConvexity) {
  json d = s01();
  d["dynamics"]["running_cost"] = "Tmax*c^(-1)*eps*u-Tmax*c^(-1)*eps*u^2+Tmax*c^(-1)*u";
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "fail");
  EXPECT_TRUE(failed_ids(r).count("throttle_convexity"));
}

TEST(Verify, MissingMassTransversalityFailsCountAndTransversality) {
  json d = s01();
  auto& eqs = d["shooting"]["equations"];
  for (auto it = eqs.begin(); it != eqs.end(); ++it)
    if ((*it)["name"] == "transversality_m") {
      eqs.erase(it);
      break;
    }
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), (std::set<std::string>{"count", "transversality:m"}));
  const std::string fb = check(r, "transversality:m")["feedback"];
  EXPECT_NE(fb.find("missing transversality condition l_m_tf = 0: m(tf) is free"), std::string::npos) << fb;
  EXPECT_NE(check(r, "count")["feedback"].get<std::string>().find("8 variables but 7 equations"), std::string::npos);
}

TEST(Verify, EquivalentNormalizationPassesAndLambda0IsRequired) {
  json d = s01();
  auto& n = equation(d, "normalization");
  n["expression"] = "lambda0^2+l_rx_t0^2+l_ry_t0^2+l_rz_t0^2+l_vx_t0^2+l_vy_t0^2+l_vz_t0^2+l_m_t0^2-1";
  EXPECT_EQ(verify(d)["verdict"], "pass");

  n["expression"] = "-1+sqrt(l_m_t0^2+l_rx_t0^2+l_ry_t0^2+l_rz_t0^2+l_vx_t0^2+l_vy_t0^2+l_vz_t0^2)";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"normalization"});
  const std::string fb = check(r, "normalization")["feedback"];
  EXPECT_NE(fb.find("leaves out lambda0"), std::string::npos) << fb;
  EXPECT_NE(fb.find("G1"), std::string::npos) << fb;
}

TEST(Verify, Lambda0NotAShootingVariableFails) {
  json d = s01();
  auto& vars = d["shooting"]["variables"];
  vars.erase(vars.begin());  // lambda0
  const json r = verify(d);
  EXPECT_TRUE(failed_ids(r).count("shooting_variables"));
  EXPECT_TRUE(failed_ids(r).count("count"));
}

TEST(Verify, ExtraStateWithZeroDynamicsFailsG4) {
  json d = s01();
  d["states"].push_back({{"name", "w"}, {"meaning", "an unused quantity"}, {"unit", "1"}, {"costate", "l_w"}});
  d["dynamics"]["state_rhs"].push_back("0");
  d["state_odes"].push_back({{"state", "w"}, {"rhs", "0"}});
  d["costate_odes"].push_back({{"costate", "l_w"}, {"rhs", "0"}});
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "fail");
  EXPECT_TRUE(failed_ids(r).count("state_usage"));
  const std::string fb = check(r, "state_usage")["feedback"];
  EXPECT_NE(fb.find("w"), std::string::npos);
  EXPECT_NE(fb.find("G4"), std::string::npos);
}

TEST(Verify, UnparseableDerivedExpressionIsAFailedCheck) {
  json d = s01();
  costate_ode(d, "l_rz")["rhs"] = "foo+1";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_ode:l_rz"});
  EXPECT_NE(check(r, "costate_ode:l_rz")["feedback"].get<std::string>().find("foo"), std::string::npos);
}

TEST(Verify, UnusableProblemStatementThrows) {
  json d = s01();
  d["dynamics"]["state_rhs"][0] = "vx+bar";
  EXPECT_THROW(helios::verify::verify_derivation(d, {}), std::invalid_argument);
}

// ---- issue 4: J2, coasting targets, the sail, free final time

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Verify, BuiltinJ2CoastAndSailDerivationsPassEveryCheck) {
  for (const json* d : {&s05(), &s06(), &s11()}) {
    const json r = verify(*d);
    EXPECT_EQ(r["verdict"], "pass") << (*d)["problem"]["id"] << ": " << r["feedback"];
  }
  const json sail = verify(s11());
  for (const std::string id :
       {"control_sail", "control_sail_cone_angle", "transversality_tf", "tf_expression", "event_values", "state_usage"})
    EXPECT_EQ(check(sail, id)["verdict"], "pass") << id;
  EXPECT_EQ(check(verify(s06()), "coast_dynamics")["verdict"], "pass");
}

json& sail_alpha(json& d) {
  for (auto& def : d["control_law"]["sail"]["definitions"])
    if (def["name"] == "sail_alpha") return def["expression"];
  throw std::runtime_error("no sail_alpha");
}

TEST(Verify, SailLawWithTheOtherRootFailsNamingTheLaw) {
  json d = s11();
  sail_alpha(d) = "atan((3*sail_A-sqrt(8*sail_B^2+9*sail_A^2))/(4*sail_B))";  // minus sign before the root
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"control_sail"});
  const std::string fb = check(r, "control_sail")["feedback"];
  EXPECT_TRUE(contains(fb, "control_law.sail.law does not minimize H over the admissible hemisphere")) << fb;
  EXPECT_TRUE(contains(fb, "stationary point of H but not its minimum")) << fb;
}

TEST(Verify, SailLawOutsideTheHemisphereOrNotUnitFails) {
  json d = s11();
  auto& law = d["control_law"]["sail"]["law"];
  const json right = law;
  for (auto& l : law) l = "2*(" + l.get<std::string>() + ")";
  EXPECT_TRUE(contains(check(verify(d), "control_sail")["feedback"], "is not a unit vector"));
  const char* rhat[] = {"-rx/sqrt(rx^2+ry^2+rz^2)", "-ry/sqrt(rx^2+ry^2+rz^2)", "-rz/sqrt(rx^2+ry^2+rz^2)"};
  for (int k = 0; k < 3; ++k) law[k] = rhat[k];
  EXPECT_TRUE(contains(check(verify(d), "control_sail")["feedback"], "leaves the admissible set"));
}

TEST(Verify, SailConeAngleMustMatchTheLaw) {
  json d = s11();
  d["control_law"]["sail"]["cone_angle"] = "Pi/2-sail_alpha";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"control_sail_cone_angle"});
}

TEST(Verify, SailWithAMassStateFailsG4) {
  json d = s11();
  d["states"].push_back({{"name", "m"}, {"meaning", "mass"}, {"unit", "kg"}, {"costate", "l_m"}});
  d["dynamics"]["state_rhs"].push_back("0");
  d["state_odes"].push_back({{"state", "m"}, {"rhs", "0"}});
  d["costate_odes"].push_back({{"costate", "l_m"}, {"rhs", "0"}});
  const json r = verify(d);
  EXPECT_TRUE(failed_ids(r).count("state_usage"));
  EXPECT_TRUE(contains(check(r, "state_usage")["feedback"], "a sail has no mass state"));
}

TEST(Verify, FreeFinalTimeConditionIsRecomputedFromPsi) {
  json d = s11();
  auto& e = equation(d, "transversality_tf")["expression"];
  const std::string right = e;
  e = "-(" + right + ")";  // any constant multiple is the same equation
  EXPECT_EQ(verify(d)["verdict"], "pass");

  std::string dropped = right;
  const std::string term = "-arrival_vz_rate*l_vz_tf";
  ASSERT_TRUE(contains(dropped, term)) << dropped;
  dropped.erase(dropped.find(term), term.size());
  e = dropped;
  json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"transversality_tf"});
  std::string fb = check(r, "transversality_tf")["feedback"];
  EXPECT_TRUE(contains(fb, "shooting equation 'transversality_tf'")) << fb;
  EXPECT_TRUE(contains(fb, "it lacks the term(s) -arrival_vz_rate*l_vz_tf")) << fb;

  e = "H_tf";  // as if the target did not move
  r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"transversality_tf"});
}

TEST(Verify, FreeFinalTimeAddsOneVariableAndOneEquation) {
  json d = s11();
  auto& vars = d["shooting"]["variables"];
  for (auto it = vars.begin(); it != vars.end(); ++it)
    if ((*it)["name"] == "tf_frac") {
      vars.erase(it);
      break;
    }
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), (std::set<std::string>{"count", "tf_expression"}));
  EXPECT_TRUE(contains(check(r, "tf_expression")["feedback"], "Rule 0"));
}

TEST(Verify, MissingJ2JacobianEntryIsNamed) {
  json d = s05();
  // l_ry' without its l_vz terms from J2: the entry d(vz')/dry of the J2 acceleration.
  std::string rhs = costate_ode(d, "l_ry")["rhs"], kept;
  std::string term;
  int depth = 0;
  for (std::size_t i = 0; i <= rhs.size(); ++i) {
    const char ch = i < rhs.size() ? rhs[i] : '+';
    if ((ch == '+' || ch == '-') && depth == 0 && !term.empty() && term.back() != '^' && term.back() != '*') {
      if (!(contains(term, "J2") && contains(term, "l_vz"))) kept += term;
      term.clear();
    }
    depth += ch == '(' ? 1 : ch == ')' ? -1 : 0;
    if (i < rhs.size()) term += ch;
  }
  ASSERT_NE(kept, rhs);
  costate_ode(d, "l_ry")["rhs"] = kept;
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_ode:l_ry"});
  const std::string fb = check(r, "costate_ode:l_ry")["feedback"];
  EXPECT_TRUE(contains(fb, "coefficient of l_vz must be -d(dynamics.state_rhs[vz])/dry")) << fb;
  EXPECT_TRUE(contains(fb, "the Jacobian entry dvz'/dry")) << fb;
}

TEST(Verify, CoastingTargetMustObeyTheSameField) {
  json d = s06();
  auto& rhs = d["coast_dynamics"]["rhs"];
  rhs[5] = "-(rx^2+ry^2+rz^2)^(-3/2)*mu*rz";  // two-body only
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"coast_dynamics"});
  EXPECT_TRUE(contains(check(r, "coast_dynamics")["feedback"], "coast_dynamics.rhs[5]"));
}

// An orbit target (S14): psi fixes no state, so each state's row lambda(tf) = nu^T dpsi/dx is an
// equation of its own, recomputed from psi: dropped or with a term's sign flipped, it fails.
TEST(Verify, AnOrbitTargetsTransversalityIsRecomputedFromPsi) {
  json d = derive("S14");
  json r = verify(d);
  EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  for (const char* x : {"rx", "vz", "m"}) EXPECT_EQ(check(r, std::string("transversality:") + x)["verdict"], "pass");
  json dropped = d;
  auto& eqs = dropped["shooting"]["equations"];
  for (std::size_t i = 0; i < eqs.size(); ++i)
    if (eqs[i]["name"] == "transversality_vx") eqs.erase(i);
  EXPECT_TRUE(failed_ids(verify(dropped)).count("transversality:vx"));
  // lambda_vx(tf) - 2 nu_3 vx - ...: the sign of the nu_arrival_3 term flipped.
  auto& e = equation(d, "transversality_vx")["expression"];
  std::string text = e;
  const auto at = text.find("-2*nu_arrival_3*vx_tf");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 1, "+");
  e = text;
  r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"transversality:vx"});
  EXPECT_TRUE(contains(check(r, "transversality:vx")["feedback"], "nu_arrival_3")) << r["feedback"];
}

// A departure anywhere on an orbit: x(t0) = X(theta) with theta free, so dPhi/dtheta = -lambda(t0).
// dX/dtheta = 0 is recomputed from psi: dropped or with a term's sign flipped, it fails.
TEST(Verify, ADepartureOrbitsStationarityIsRecomputedFromPsi) {
  json d = derive_text("tests/fixtures/problems/gto_anywhere_to_geo.txt");
  const std::string id = "initial_stationarity:departure_theta_departure";
  json r = verify(d);
  EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  EXPECT_EQ(check(r, id)["verdict"], "pass");
  json dropped = d;
  auto& eqs = dropped["shooting"]["equations"];
  for (std::size_t i = 0; i < eqs.size(); ++i)
    if (eqs[i]["name"] == "stationarity_departure_theta_departure") eqs.erase(i);
  EXPECT_TRUE(failed_ids(verify(dropped)).count(id));
  auto& e = equation(d, "stationarity_departure_theta_departure")["expression"];
  std::string text = e;
  const auto at = text.find("*l_rz_t0");
  ASSERT_NE(at, std::string::npos) << text;
  const auto sign = text.find_last_of("+-", at);
  ASSERT_NE(sign, std::string::npos) << text;
  text[sign] = text[sign] == '+' ? '-' : '+';
  e = text;
  EXPECT_TRUE(failed_ids(verify(d)).count(id));
}

// A Mayer objective (the final radius) with the engine at full throttle: the endpoint cost and the
// throttle-free thrust are recomputed from their terms.
TEST(Verify, AFinalStateObjectiveAndAFullThrottleEngineAreRecomputed) {
  json d = derive_text("tests/fixtures/problems/maximum_radius.txt");
  EXPECT_EQ(verify(d)["verdict"], "pass");
  json maximized = d;
  maximized["dynamics"]["endpoint_cost"] = "sqrt(rx^2+ry^2+rz^2)";  // phi = +|r|: the radius minimized
  EXPECT_TRUE(failed_ids(verify(maximized)).count("cost_terms"));
  json throttled = d;
  throttled["dynamics"]["state_rhs"].back() = "-Tmax/c/2";  // m's rate: half a full throttle's mass flow
  EXPECT_TRUE(failed_ids(verify(throttled)).count("dynamics_terms"));
}

TEST(Verify, RightHandSideWithTheOptimalControlSubstitutedPasses) {
  json d = s01();
  costate_ode(d, "l_m")["rhs"] = "-Tmax*u*sqrt(l_vx^2+l_vy^2+l_vz^2)/m^2";  // a* = -l_v/|l_v| substituted
  EXPECT_EQ(verify(d)["verdict"], "pass");
  costate_ode(d, "l_m")["rhs"] = "Tmax*u*sqrt(l_vx^2+l_vy^2+l_vz^2)/m^2";  // with the maximizing direction
  EXPECT_EQ(failed_ids(verify(d)), std::set<std::string>{"costate_ode:l_m"});
}

// ---- interior events and a sliding departure (specs in tests/verify-corpus/base/E-*.spec.json)

json derive_spec(const std::string& name) {
  return helios::pmp::derive_from_spec(
      helios::io::read_json(HELIOS_SOURCE_DIR "/tests/verify-corpus/base/" + name + ".spec.json"));
}

const json& flyby() {
  static const json derivation = derive_spec("E-flyby");
  return derivation;
}

const json& stay() {
  static const json derivation = derive_spec("E-stay");
  return derivation;
}

const json& slide() {
  static const json derivation = derive_spec("E-slide");
  return derivation;
}

json& event_costate(json& d, const std::string& costate) {
  for (auto& c : d["events"][0]["costate_map"])
    if (c["costate"] == costate) return c;
  throw std::runtime_error("no costate_map entry " + costate);
}

void drop(json& list, const std::string& name) {
  for (auto it = list.begin(); it != list.end(); ++it)
    if ((*it)["name"] == name) {
      list.erase(it);
      return;
    }
  throw std::runtime_error("nothing named " + name);
}

TEST(VerifyEvents, BuiltinEventDerivationsPassEveryCheck) {
  for (const json* d : {&flyby(), &stay(), &slide()}) {
    const json r = verify(*d);
    EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
    for (const std::string id :
         {"event_psi:rock", "event_multipliers:rock", "event_constraint:rock_1", "costate_jump:rock_rx",
          "costate_jump:rock_m", "event_time:rock", "event_unknowns:rock", "equation_symbols", "shooting_variables"})
      EXPECT_EQ(check(r, id)["verdict"], "pass") << id;
  }
  // The flyby's psi and its jumps are shown exactly; the stay's r, v costates are shooting variables.
  const json f = verify(flyby());
  for (const std::string id : {"event_psi:rock", "costate_jump:rock_rx", "event_time:rock"})
    EXPECT_TRUE(check(f, id)["exact"].get<bool>()) << id;
  EXPECT_EQ(check(verify(stay()), "costate_jump:rock_vz")["verdict"], "pass");
  const json s = verify(slide());
  EXPECT_EQ(check(s, "transversality_t0")["verdict"], "pass");
  EXPECT_EQ(check(s, "t0_expression")["verdict"], "pass");
}

TEST(VerifyEvents, GravityAssistStationarityIsRecomputedFromPsi) {
  json d = derive_spec("E-ga");
  const auto t0 = std::chrono::steady_clock::now();
  json r = verify(d);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            1.0 * helios::test::kTimeScale);
  EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  EXPECT_EQ(check(r, "event_stationarity:rock_delta_rock")["verdict"], "pass");
  EXPECT_EQ(check(r, "costate_jump:rock_vx")["verdict"], "pass");  // a shooting variable with its jump row
  // One term of dPhi/ddelta with the wrong sign: l_vx(t+) -> -l_vx(t+) in that equation only.
  auto& e = equation(d, "stationarity_rock_delta_rock")["expression"];
  std::string text = e;
  for (std::size_t at = text.find("l_vx_rock_p"); at != std::string::npos; at = text.find("l_vx_rock_p", at + 14))
    text.replace(at, 11, "(-l_vx_rock_p)");
  e = text;
  r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"event_stationarity:rock_delta_rock"});
  EXPECT_TRUE(contains(check(r, "event_stationarity:rock_delta_rock")["feedback"],
                       "the term(s) in l_vx_rock_p have the wrong sign"));
}

TEST(VerifyEvents, JumpWithTheWrongSignFails) {
  json d = flyby();
  event_costate(d, "l_ry")["expression"] = "l_ry_rock_m+nu_rock_2";  // lambda+ = lambda- + nu
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_jump:rock_ry"});
  const std::string fb = check(r, "costate_jump:rock_ry")["feedback"];
  EXPECT_TRUE(contains(fb, "expected l_ry_rock_p = -nu_rock_2+l_ry_rock_m")) << fb;
  EXPECT_TRUE(contains(fb, "the term(s) in nu_rock_2 have the wrong sign")) << fb;
  // An equivalent form passes.
  event_costate(d, "l_ry")["expression"] = "-(nu_rock_2-l_ry_rock_m)";
  EXPECT_EQ(verify(d)["verdict"], "pass");
}

TEST(VerifyEvents, TimeConditionNeedsTheHJumpAndTheTargetsMotion) {
  json d = flyby();
  auto& e = equation(d, "time_rock")["expression"];
  const std::string right = e;
  e = "3*(" + right + ")";  // a multiple is the same condition
  EXPECT_EQ(verify(d)["verdict"], "pass");
  e = "-nu_rock_1*rock_rx_rate-nu_rock_2*rock_ry_rate-nu_rock_3*rock_rz_rate";  // no H jump
  json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"event_time:rock"});
  EXPECT_TRUE(contains(check(r, "event_time:rock")["feedback"], "the jump of the Hamiltonian")) << r["feedback"];
  e = "H_rock_p-H_rock_m-nu_rock_1*rock_rx_rate-nu_rock_2*rock_ry_rate-nu_rock_3*rock_rz_rate";  // H jump's sign
  r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"event_time:rock"});
  EXPECT_TRUE(contains(check(r, "event_time:rock")["feedback"], "the jump of the Hamiltonian has the wrong sign"));
  e = "H_rock_m-H_rock_p";  // no nu^T dpsi/dt
  r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"event_time:rock"});
  EXPECT_TRUE(contains(check(r, "event_time:rock")["feedback"], "nu^T dpsi/dt is missing")) << r["feedback"];
}

// A model may omit an event value's optional "at": the label is read from the name's grammar
// (H_rock_m is H at rock_m), so the time condition is still checked, and still passes.
TEST(VerifyEvents, AHamiltonianValueWithoutAtIsPlacedByItsName) {
  json d = flyby();
  for (auto& v : d["event_values"])
    if (v.value("kind", "") == "hamiltonian") v.erase("at");
  EXPECT_EQ(verify(d)["verdict"], "pass") << verify(d)["feedback"];
  equation(d, "time_rock")["expression"] = "H_rock_p-H_rock_m";  // the H jump's sign, caught as with "at"
  EXPECT_EQ(failed_ids(verify(d)), std::set<std::string>{"event_time:rock"});
}

TEST(VerifyEvents, MappedCostateTreatedAsContinuousFails) {
  json d = stay();
  auto& c = event_costate(d, "l_vy");
  c.erase("variable");
  c["expression"] = "l_vy_rock_m";
  drop(d["shooting"]["variables"], "l_vy_rock_p");
  drop(d["shooting"]["equations"], "jump_rock_vy");
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), (std::set<std::string>{"costate_jump:rock_vy", "event_unknowns:rock"}));
  const std::string fb = check(r, "costate_jump:rock_vy")["feedback"];
  EXPECT_TRUE(contains(fb, "does not carry vy over")) << fb;
  EXPECT_TRUE(contains(fb, "jump_rock_vy")) << fb;
}

TEST(VerifyEvents, CarriedCostateMustBeExplicit) {
  json d = flyby();
  auto& c = event_costate(d, "l_vx");
  c.erase("expression");
  c["variable"] = "l_vx_rock_p";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_jump:rock_vx"});
  EXPECT_TRUE(contains(check(r, "costate_jump:rock_vx")["feedback"], "the map carries vx"));
}

TEST(VerifyEvents, LambdaMassDoesNotJumpAtAMassDrop) {
  json d = stay();
  event_costate(d, "l_m")["expression"] = "l_m_rock_m*m_rock_m/(m_rock_m-drop_rock)";
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"costate_jump:rock_m"});
  EXPECT_TRUE(contains(check(r, "costate_jump:rock_m")["feedback"], "lambda_m does not jump"));
}

TEST(VerifyEvents, PsiStateMapAndMultipliersMustAgree) {
  json d = stay();
  for (auto& m : d["events"][0]["state_map"])
    if (m["state"] == "m") m["expression"] = "m_rock_m";
  EXPECT_EQ(failed_ids(verify(d)), std::set<std::string>{"event_psi:rock"});
  d = flyby();
  // The state map's multipliers follow c's (position and the window's two bounds): -lambda(t+).
  auto& multipliers = d["events"][0]["multipliers"];
  multipliers[multipliers.size() - d["states"].size()] = "l_rx_rock_p";
  EXPECT_EQ(failed_ids(verify(d)), std::set<std::string>{"event_multipliers:rock"});
  d = flyby();
  drop(d["shooting"]["equations"], "psi_rock_3");
  EXPECT_EQ(failed_ids(verify(d)), (std::set<std::string>{"count", "event_constraint:rock_3"}));
  d = flyby();
  drop(d["shooting"]["variables"], "t_rock_frac");
  EXPECT_TRUE(failed_ids(verify(d)).count("event_unknowns:rock"));
}

TEST(VerifyEvents, SlidingDepartureWithHt0AloneFails) {
  json d = slide();
  auto& e = equation(d, "transversality_t0")["expression"];
  e = "-(" + e.get<std::string>() + ")";
  EXPECT_EQ(verify(d)["verdict"], "pass");
  e = "H_t0";  // the paper's condition
  const json r = verify(d);
  EXPECT_EQ(failed_ids(r), std::set<std::string>{"transversality_t0"});
  const std::string fb = check(r, "transversality_t0")["feedback"];
  EXPECT_TRUE(contains(fb, "the departure body's motion is missing")) << fb;
  EXPECT_TRUE(contains(fb, "the coupling with tf is missing")) << fb;
}

}  // namespace

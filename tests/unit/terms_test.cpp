// Dynamics and costs as terms (issue 31): each builtin derivation lists its terms with their
// parameters, helios-verify recomputes each and names the one at fault, the code generator's
// template is chosen by its terms, and a third body is one term: stated in a sentence, derived,
// verified.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "helios/codegen/generate.hpp"
#include "helios/derivation/terms.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/chain_rule.hpp"
#include "helios/symbolic/expr.hpp"
#include "helios/verify/verify.hpp"

namespace {

using helios::io::json;

const char* kJupiter =
    "\nJupiter perturbs the spacecraft as a point mass of mu = 126686534 km^3/s^2 on a circular orbit of radius "
    "778570000 km, inclination 1.3 deg, node 100.5 deg, phase 40 deg.\n";

std::string problem_text(const std::string& scenario) {
  return helios::io::read_text(HELIOS_SOURCE_DIR "/scenarios/" + scenario + "/problem.txt");
}

json derive_text(const std::string& text) {
  return helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, "problem.txt"));
}

const json& derivation(const std::string& scenario) {
  static std::map<std::string, json> cache;
  if (!cache.count(scenario))
    cache[scenario] =
        scenario == "S01J" ? derive_text(problem_text("S01") + kJupiter) : derive_text(problem_text(scenario));
  return cache[scenario];
}

json verify(const json& d) {
  json report = helios::verify::verify_derivation(d, {});
  helios::io::validate("verify", report, "terms_test");
  return report;
}

const json& check(const json& report, const std::string& id) {
  for (const auto& c : report["checks"])
    if (c["id"] == id) return c;
  throw std::runtime_error("no check " + id);
}

// The feedback of a failed check `id` ("" when it passed).
std::string feedback(const json& d, const std::string& id) {
  const json r = verify(d);
  return check(r, id)["verdict"] == "fail" ? check(r, id)["feedback"].get<std::string>() : "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

json& term(json& d, const std::string& name) {
  for (auto& t : d["terms"])
    if (t["name"] == name) return t;
  throw std::runtime_error("no term " + name);
}

TEST(Terms, BuiltinDerivationsListTheirTermsWithTheirParameters) {
  const auto listing = [](const std::string& s) {
    std::string out;
    const auto terms = helios::derivation::read_terms(derivation(s), s);
    for (const auto& t : *terms) {
      out += (out.empty() ? "" : " ") + t.name + "(";
      for (std::size_t i = 0; i < t.parameters.size(); ++i) out += (i ? "," : "") + t.parameters[i];
      out += ")";
    }
    return out;
  };
  EXPECT_EQ(listing("S01"), "two_body(mu) thrust(Tmax,c) fuel(Tmax,c)");
  EXPECT_EQ(listing("S05"), "two_body(mu) j2(J2,Req) thrust(Tmax,c) fuel(Tmax,c)");
  EXPECT_EQ(listing("S08"), "two_body(mu) thrust(Tmax,c) initial_mass(Tmax,c)");
  EXPECT_EQ(listing("S11"), "two_body(mu) solar_sail(ac,rref) time()");
  EXPECT_EQ(listing("S12"), "two_body(mu) thrust(Tmax,c) user_acceleration() fuel(Tmax,c)");
  EXPECT_EQ(listing("S01J"),
            "two_body(mu) thrust(Tmax,c) third_body(mu_Jupiter,a_Jupiter,i_Jupiter,W_Jupiter,u0_Jupiter,n_Jupiter) "
            "fuel(Tmax,c)");
  EXPECT_EQ(term(const_cast<json&>(derivation("S12")), "user_acceleration")["acceleration"].size(), 3u);
}

TEST(Terms, VerifyRecomputesEveryTermOfTheBuiltinDerivations) {
  for (const std::string s : {"S01", "S05", "S08", "S11", "S12", "S01J"}) {
    SCOPED_TRACE(s);
    const json r = verify(derivation(s));
    EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
    EXPECT_EQ(check(r, "dynamics_terms")["verdict"], "pass");
    EXPECT_EQ(check(r, "cost_terms")["verdict"], "pass");
  }
}

TEST(Terms, ADerivationWithoutTermsFailsBothChecksSayingWhatToList) {
  json d = derivation("S01");
  d.erase("terms");
  EXPECT_TRUE(contains(feedback(d, "dynamics_terms"), "lists no terms"));
  EXPECT_TRUE(contains(feedback(d, "cost_terms"), "lists no terms"));
}

TEST(Terms, ATermListedButNotInTheDynamicsIsNamed) {
  json d = derivation("S05");
  json& terms = d["terms"];
  terms.insert(terms.begin() + 2, term(d, "j2"));  // j2 twice: the dynamics have it once
  EXPECT_TRUE(contains(feedback(d, "dynamics_terms"), "lacks the term j2")) << feedback(d, "dynamics_terms");
}

TEST(Terms, ATermInTheDynamicsButNotListedFails) {
  json d = derivation("S05");
  json& terms = d["terms"];
  terms.erase(terms.begin() + 1);  // j2
  const std::string why = feedback(d, "dynamics_terms");
  EXPECT_TRUE(contains(why, "is not the sum of its listed terms (two_body, thrust)")) << why;
  EXPECT_TRUE(contains(why, "J2")) << why;
}

TEST(Terms, ATermWithTheWrongSignIsNamed) {
  json d = derivation("S01");
  d["dynamics"]["state_rhs"][3] = "mu*rx*(rx^2+ry^2+rz^2)^(-3/2)+Tmax*u*ax/m";
  EXPECT_TRUE(contains(feedback(d, "dynamics_terms"), "dynamics.state_rhs[vx]: the term two_body has the wrong sign"))
      << feedback(d, "dynamics_terms");
}

TEST(Terms, AWrongParameterIsNamedWithItsTerm) {
  json d = derivation("S01");
  term(d, "thrust")["parameters"] = {"c", "Tmax"};
  const std::string why = feedback(d, "dynamics_terms");
  EXPECT_TRUE(contains(why, "depends on the parameters of thrust")) << why;
  term(d, "thrust")["parameters"] = {"Tmax", "isp"};
  EXPECT_EQ(feedback(d, "dynamics_terms"), "term thrust: its parameter 'isp' is not a parameter of the derivation.");
  term(d, "thrust")["parameters"] = {"Tmax"};
  EXPECT_EQ(feedback(d, "dynamics_terms"), "term thrust lists 1 parameter(s), it needs 2.");
}

TEST(Terms, AnUnknownTermOrAWrongCostIsNamed) {
  json d = derivation("S01");
  term(d, "thrust")["name"] = "lift";  // refused by the derivation's strict reader (an llm's feedback)
  try {
    verify(d);
    ADD_FAILURE() << "an unknown term was read";
  } catch (const helios::input_error& e) {
    EXPECT_TRUE(contains(e.what(), "field terms[1].name: unknown term 'lift'")) << e.what();
  }
  d = derivation("S01");
  term(d, "fuel") = {{"name", "time"}, {"kind", "cost"}, {"parameters", json::array()}};
  EXPECT_TRUE(contains(feedback(d, "cost_terms"), "is not the cost term time")) << feedback(d, "cost_terms");
  EXPECT_EQ(feedback(d, "dynamics_terms"), "");
}

TEST(Terms, TheThirdBodysMeanMotionAndPresenceAreChecked) {
  json d = derivation("S01J");
  for (auto& q : d["parameters"])
    if (q["name"] == "n_Jupiter") q["value"] = q["value"].get<double>() * 1.01;
  EXPECT_TRUE(contains(feedback(d, "dynamics_terms"), "term third_body (Jupiter): its mean motion n_Jupiter"))
      << feedback(d, "dynamics_terms");
  d = derivation("S01J");
  d["terms"].erase(d["terms"].begin() + 2);
  const std::string why = feedback(d, "dynamics_terms");
  EXPECT_TRUE(contains(why, "mu_Jupiter")) << why;
}

TEST(Terms, TheThirdBodySentenceAndItsRefusals) {
  const json spec = helios::spec::parse_problem_text(problem_text("S01") + kJupiter, "p.txt");
  const json& body = spec["dynamics"]["perturbations"][0];
  EXPECT_EQ(body["kind"], "third_body");
  EXPECT_EQ(body["name"], "Jupiter");
  EXPECT_DOUBLE_EQ(body["mu_km3_s2"].get<double>(), 126686534);
  EXPECT_DOUBLE_EQ(body["orbit_radius_km"].get<double>(), 778570000);
  EXPECT_DOUBLE_EQ(body["inclination_deg"].get<double>(), 1.3);
  EXPECT_DOUBLE_EQ(body["raan_deg"].get<double>(), 100.5);
  EXPECT_DOUBLE_EQ(body["phase_deg"].get<double>(), 40);
  const auto refusal = [](const std::string& sentence) {
    try {
      helios::spec::parse_problem_text(problem_text("S01") + "\n" + sentence + "\n", "p.txt");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string no_radius = refusal("Jupiter perturbs the spacecraft as a point mass of mu = 126686534 km^3/s^2.");
  EXPECT_TRUE(contains(no_radius, "the third body Jupiter needs the radius of its circular orbit, e.g. 'The Moon"))
      << no_radius;
  const std::string none = refusal("Jupiter perturbs the spacecraft.");
  EXPECT_TRUE(contains(none, "needs its gravitational parameter mu and the radius of its circular orbit")) << none;
  EXPECT_TRUE(contains(refusal("The Sun perturbs the spacecraft as a point mass of mu = 1 km^3/s^2 on a circular "
                               "orbit of radius 1 km."),
                       "Sun is the central body"));
}

TEST(Terms, TheTemplateIsChosenByTheTerms) {
  EXPECT_EQ(helios::codegen::generate(derivation("S01"), {}).template_modules,
            (std::vector<std::string>{"DYNAMICS", "SWITCH"}));
  EXPECT_EQ(helios::codegen::generate(derivation("S08"), {}).template_modules,
            (std::vector<std::string>{"DYNAMICS", "SWITCH"}));
  // The same expressions listed as other terms are not the template's problem.
  json d = derivation("S01");
  d["terms"].insert(d["terms"].begin() + 1, json{{"name", "j2"}, {"kind", "force"}, {"parameters", {"mu", "mu"}}});
  EXPECT_TRUE(helios::codegen::generate(d, {}).template_modules.empty());
  EXPECT_TRUE(helios::codegen::generate(derivation("S01J"), {}).template_modules.empty());
}

}  // namespace

// An engine of constant mass (issue 48): S14's GTO to GEO made planar, the mass constant at 1500 kg.
std::string constant_mass_text(const std::string& engine, const std::string& objective) {
  return "Problem T48: planar GTO to GEO at constant mass.\n"
         "The central body is the Earth with gravitational parameter 398600.47 km^3/s^2.\n" +
         engine +
         "\nThe spacecraft's mass is constant at 1500 kg.\n"
         "The spacecraft departs at t = 0 days from position [-46500, 0, 0] km with velocity [0, "
         "-1.4529784332509441, 0] km/s.\n"
         "At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.\n" +
         objective + "\n";
}

const char* kFreeTime = "The time of flight is free, at most 2 days.\nMinimize the time of flight.";
const char* kFixedFuel = "The time of flight is 0.9 days.\nMinimize the fuel consumption.";

std::vector<std::string> names_of(const json& list, const char* key) {
  std::vector<std::string> out;
  for (const auto& e : list) out.push_back(e[key].get<std::string>());
  return out;
}

TEST(Terms, AConstantMassHasNoMassStateAndTheL1Cost) {
  const std::string thrust = "The spacecraft has a maximum thrust of 60 N.";
  const std::string with_isp = "The spacecraft has a maximum thrust of 60 N and a specific impulse of 2000 s.";
  const json spec = helios::spec::parse_problem_text(constant_mass_text(thrust, kFreeTime), "p.txt");
  EXPECT_EQ(spec["spacecraft"]["mass_model"], "constant");
  EXPECT_FALSE(spec["spacecraft"].contains("isp_s"));
  const auto listing = [](const json& d) {
    std::string out;
    const auto terms = helios::derivation::read_terms(d, "d");
    for (const auto& t : *terms) {
      out += (out.empty() ? "" : " ") + t.name + "(";
      for (std::size_t i = 0; i < t.parameters.size(); ++i) out += (i ? "," : "") + t.parameters[i];
      out += ")";
    }
    return out;
  };
  const json time = derive_text(constant_mass_text(thrust, kFreeTime));
  const json fuel = derive_text(constant_mass_text(with_isp, kFixedFuel));
  const json delta_v = derive_text(constant_mass_text(thrust, kFixedFuel));
  EXPECT_EQ(listing(time), "two_body(mu) constant_mass_thrust(Tmax,mass) time()");
  EXPECT_EQ(listing(fuel), "two_body(mu) constant_mass_thrust(Tmax,mass,c) fuel(Tmax,c)");
  EXPECT_EQ(listing(delta_v), "two_body(mu) constant_mass_thrust(Tmax,mass) delta_v(Tmax,mass)");
  for (const json* d : {&time, &fuel, &delta_v}) {
    // No mass state, no mass costate: six states, and the acceleration Tmax u a / mass.
    EXPECT_EQ(names_of((*d)["states"], "name"), (std::vector<std::string>{"rx", "ry", "rz", "vx", "vy", "vz"}));
    EXPECT_EQ((*d)["costate_odes"].size(), 6u);
    EXPECT_EQ((*d)["dynamics"]["state_rhs"][3], "-(rx^2+ry^2+rz^2)^(-3/2)*mu*rx+Tmax*ax*mass^(-1)*u");
    const json r = verify(*d);
    EXPECT_EQ(r["verdict"], "pass") << r["feedback"];
  }
  // Minimum time: dH/du = -Tmax/mass |lambda_v|, full thrust throughout.
  EXPECT_EQ(time["control_law"]["throttle"]["switching_function"], "-Tmax*mass^(-1)*sqrt(l_vx^2+l_vy^2+l_vz^2)");
  // Minimum fuel: the L1 cost, priced by c where a specific impulse is given, else by the mass (delta-v).
  EXPECT_EQ(fuel["dynamics"]["running_cost"], "-Tmax*c^(-1)*eps*u+Tmax*c^(-1)*eps*u^2+Tmax*c^(-1)*u");
  EXPECT_EQ(delta_v["dynamics"]["running_cost"], "-Tmax*eps*mass^(-1)*u+Tmax*eps*mass^(-1)*u^2+Tmax*mass^(-1)*u");
  EXPECT_EQ(fuel["control_law"]["throttle"]["switching_function"],
            "-Tmax*mass^(-1)*sqrt(l_vx^2+l_vy^2+l_vz^2)+Tmax*c^(-1)*lambda0");
  EXPECT_EQ(delta_v["control_law"]["throttle"]["switching_function"],
            "-Tmax*mass^(-1)*sqrt(l_vx^2+l_vy^2+l_vz^2)+Tmax*lambda0*mass^(-1)");
  EXPECT_EQ(delta_v["homotopy"]["start"], 1.0);
  for (const json* d : {&time, &fuel, &delta_v}) EXPECT_NO_THROW(helios::io::validate("derivation", *d, "terms_test"));
}

TEST(Terms, AConstantMassDerivationMutatedFailsTheRowItBreaks) {
  const json d = derive_text(constant_mass_text("The spacecraft has a maximum thrust of 60 N.",
                                                "The time of flight is 0.9 days.\nMinimize the fuel consumption."));
  json m = d;  // the switching function without the L1 price
  m["control_law"]["throttle"]["switching_function"] = "-Tmax*mass^(-1)*sqrt(l_vx^2+l_vy^2+l_vz^2)";
  json r = verify(m);
  EXPECT_EQ(check(r, "throttle_switching")["verdict"], "fail");
  m = d;  // a mass flow no constant mass has
  for (auto& q : m["parameters"])
    if (q["name"] == "mass") q["value"] = 2.0;
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"), "its mass mass = 2 is not 1")) << feedback(m, "dynamics_terms");
  m = d;  // the thrust along the wrong direction
  m["dynamics"]["state_rhs"][4] = "-(rx^2+ry^2+rz^2)^(-3/2)*mu*ry+Tmax*ax*mass^(-1)*u";
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"), "dynamics.state_rhs[vy]")) << feedback(m, "dynamics_terms");
  m = d;  // a delta-v cost without its smoothing
  m["dynamics"]["running_cost"] = "Tmax*mass^(-1)*u";
  EXPECT_TRUE(contains(feedback(m, "cost_terms"), "is not the cost term delta_v")) << feedback(m, "cost_terms");
  m = d;  // a constant-mass thrust listed with a mass state's name
  term(m, "constant_mass_thrust")["name"] = "thrust";
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"),
                       "term thrust needs a throttle, three direction controls and a "
                       "mass state"))
      << feedback(m, "dynamics_terms");
}

TEST(Terms, AConstantMassIsRefusedWhereItContradictsTheText) {
  const auto refusal = [](const std::string& text) {
    try {
      helios::spec::parse_problem_text(text, "p.txt");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string engine = "The spacecraft has a maximum thrust of 60 N and a specific impulse of 2000 s.";
  EXPECT_TRUE(contains(refusal(constant_mass_text(engine, "Minimize the initial mass.")), "minimize the fuel"))
      << refusal(constant_mass_text(engine, "Minimize the initial mass."));
  const std::string twice = refusal(constant_mass_text(engine + "\nNeglect the propellant mass.", kFreeTime));
  EXPECT_TRUE(contains(twice, "the spacecraft's mass model is given twice")) << twice;
  // Without the constant mass the specific impulse is still required.
  std::string text = constant_mass_text("The spacecraft has a maximum thrust of 60 N.", kFreeTime);
  text.replace(text.find("The spacecraft's mass is constant at"), 36, "The spacecraft has an initial mass of");
  EXPECT_TRUE(contains(refusal(text), "isp_s")) << refusal(text);
}

// ---- A solar-electric engine (issue 48): T(r) = 2 eta P_in(r)/c, the costates carry dT/dr -----------

// -dH/dx at `at` by a central difference of step rel max(1, |x|).
double minus_dH_dx(const GiNaC::ex& H, const helios::symbolic::SymbolTable& table, const helios::symbolic::Values& at,
                   const std::string& x, double rel) {
  const double h = rel * std::max(1.0, std::fabs(at.at(x)));
  helios::symbolic::Values plus = at, minus = at;
  plus[x] += h;
  minus[x] -= h;
  return -(helios::symbolic::evaluate(H, table, plus) - helios::symbolic::evaluate(H, table, minus)) / (2 * h);
}

// A table with every name of derivation `d` and the intermediates substituted in whatever it parses.
struct Substituted {
  helios::symbolic::SymbolTable table;
  helios::symbolic::Values values;  // the parameters'
  explicit Substituted(const json& d) {
    for (const auto& s : d["states"]) table.get(s["name"]), table.get(s["costate"]);
    for (const auto& c : d["controls"]) table.get(c["name"]);
    for (const auto& q : d["parameters"]) values[table.get(q["name"]).get_name()] = q["value"];
    for (const char* n : {"lambda0", "eps", "t"}) table.get(n);
    GiNaC::exmap inlined;
    for (const auto& q : d.value("intermediates", json::array())) {
      const GiNaC::ex e = table.parse(q["expression"].get<std::string>(), "intermediates");
      inlined[table.get(q["name"])] = e;
      table.substitute_on_parse(inlined);
    }
  }
  double at(const json& text, const helios::symbolic::Values& point) {
    return helios::symbolic::evaluate(table.parse(text.get<std::string>(), "derivation"), table, point);
  }
};

const char* kS01Engine =
    "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.";
const char* kS15Engine =
    "The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, the bus uses 0.5 kW, the engine takes at most "
    "10 kW with an efficiency of 0.6 and a specific impulse of 2000 s.\nThe spacecraft has an initial mass of 1000 kg.";

// S01's text with its engine sentence replaced by `engine`.
std::string s01_with(const std::string& engine) {
  std::string text = problem_text("S01");
  text.replace(text.find(kS01Engine), std::string(kS01Engine).size(), engine);
  return text;
}

std::string refusal_of(const std::string& text) {
  try {
    derive_text(text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SolarElectric, TheSentenceIsDerivedAsOneTermWithRolesAndVerified) {
  const json spec = helios::spec::parse_problem_text(problem_text("S15"), "problem.txt");
  EXPECT_EQ(spec["spacecraft"],
            json::parse(R"({"array_power_1AU_W": 20000, "bus_power_W": 500, "max_engine_power_W": 10000,
                           "engine_efficiency": 0.6, "isp_s": 2000, "initial_mass_kg": 1000})"));
  const json& d = derivation("S15");
  EXPECT_NO_THROW(helios::io::validate("derivation", d, "terms_test"));
  std::string listed;
  const auto terms = helios::derivation::read_terms(d, "S15");
  for (const auto& t : *terms) {
    listed += (listed.empty() ? "" : " ") + t.name + "(";
    for (std::size_t i = 0; i < t.parameters.size(); ++i) listed += (i ? "," : "") + t.parameters[i];
    listed += ")";
  }
  EXPECT_EQ(listed, "two_body(mu) solar_electric_thrust(P0,Pbus,eta,c,Pmax,Pw) fuel(P0,Pbus,eta,c,Pmax,Pw)");
  std::map<std::string, std::string> roles;
  for (const auto& q : d["parameters"])
    if (q.contains("role") || q["name"].get<std::string>().find('_') == std::string::npos)
      roles[q["name"]] = q.value("role", "");  // the engine's and mu (not the targets' states)
  EXPECT_EQ(roles, (std::map<std::string, std::string>{{"mu", ""},
                                                       {"P0", "thrust_scale"},
                                                       {"Pbus", "thrust_scale"},
                                                       {"eta", ""},
                                                       {"c", "exhaust_velocity"},
                                                       {"Pmax", "thrust_scale"},
                                                       {"Pw", "thrust_scale"}}));
  // The thrust continuation multiplies every thrust_scale parameter by one factor: T(r), and so the
  // mass flow, must scale by it exactly, on either side of the cap.
  Substituted substituted(d);  // P_in and its gradient substituted
  helios::symbolic::SymbolTable& table = substituted.table;
  for (const auto& s : d["states"]) table.get(s["name"]);
  for (const auto& c : d["controls"]) table.get(c["name"]);
  helios::symbolic::Values own, scaled;
  for (const auto& q : d["parameters"]) {
    own[table.get(q["name"]).get_name()] = q["value"];
    scaled[q["name"]] = q["value"].get<double>() * (q.value("role", "") == "thrust_scale" ? 3.0 : 1.0);
  }
  const GiNaC::ex flow = table.parse(d["state_odes"][6]["rhs"].get<std::string>(), "S15");
  for (const double dist : {0.8, 1.38, 2.0}) {
    for (auto* v : {&own, &scaled}) (*v)["rx"] = dist, (*v)["ry"] = 0, (*v)["rz"] = 0, (*v)["m"] = 1, (*v)["u"] = 1;
    EXPECT_NEAR(helios::symbolic::evaluate(flow, table, scaled) / helios::symbolic::evaluate(flow, table, own), 3.0,
                1e-12);
  }
  // The constant engine's roles: Tmax scales the thrust, c is the exhaust velocity.
  for (const auto& q : derivation("S01")["parameters"])
    EXPECT_EQ(q.value("role", ""), q["name"] == "Tmax" ? "thrust_scale" : q["name"] == "c" ? "exhaust_velocity" : "");
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "pass") << r.dump(1);
  EXPECT_EQ(check(r, "dynamics_terms")["verdict"], "pass");
  EXPECT_EQ(check(r, "cost_terms")["verdict"], "pass");
}

// Every row of the SEP derivation against numbers computed here: the dynamics against T(r) in SI
// (newtons from watts), the costate rates against central differences of H, the switching function
// against a central difference of H along the throttle with the direction's law.
TEST(SolarElectric, EveryDerivationRowAgreesWithFiniteDifferences) {
  const json& d = derivation("S15");
  Substituted substituted(d);  // P_in and its gradient substituted
  helios::symbolic::SymbolTable& table = substituted.table;
  std::vector<std::string> states, costates;
  for (const auto& s : d["states"]) {
    states.push_back(s["name"]);
    costates.push_back(s["costate"]);
  }
  for (const auto& n : states) table.get(n);
  for (const auto& n : costates) table.get(n);
  for (const auto& c : d["controls"]) table.get(c["name"]);
  helios::symbolic::Values values;
  for (const auto& q : d["parameters"]) values[table.get(q["name"]).get_name()] = q["value"];
  for (const char* n : {"lambda0", "eps", "t"}) table.get(n);
  const auto parse = [&](const json& text) { return table.parse(text.get<std::string>(), "S15"); };
  const GiNaC::ex H = parse(d["hamiltonian"]);
  const double AU_m = 149597870.691e3, year_s = 365.25 * 86400, mass_kg = 1000, g0 = 9.80665, isp = 2000;
  const double accel_unit = AU_m / (year_s * year_s);
  std::mt19937_64 rng(48);
  std::uniform_real_distribution<double> uni(-1, 1);
  // Distances through the cap's crossing (P0/r^2 - Pbus = Pmax at r = sqrt(20/10.5) = 1.380 AU) and
  // the floor's (the bus takes all the arrays give at r = sqrt(20/0.5) = 6.325 AU).
  for (const double dist : {0.7, 1.0, 1.3, 1.375, 1.380, 1.385, 1.45, 1.65, 2.2, 6.0, 6.3, 6.325, 6.35, 6.5}) {
    SCOPED_TRACE(dist);
    helios::symbolic::Values at = values;
    double dir[3] = {uni(rng), uni(rng), uni(rng)};
    const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    at["rx"] = dist * dir[0] / n;
    at["ry"] = dist * dir[1] / n;
    at["rz"] = dist * dir[2] / n;
    for (const char* v : {"vx", "vy", "vz"}) at[v] = 6 * uni(rng);
    at["m"] = 0.7 + 0.2 * uni(rng);
    for (const auto& c : costates) at[c] = uni(rng);
    at["lambda0"] = 0.5;
    at["eps"] = 0.3;
    at["t"] = 0;
    at["u"] = 0.6;
    at["ax"] = 0.6, at["ay"] = 0.8, at["az"] = 0;
    // T(r) in newtons from the watts of the problem text: max(Pa, 0) less max(Pa - Pmax, 0) plus
    // max(-Pmax, 0), each max softened over its width (1% of the bus, 1% of Pmax, 1% of Pmax).
    const double available = 20000 / (dist * dist) - 500, pmax = 10000, width = 100, floor_width = 5;
    const auto soft = [](double x, double w) { return (x + std::sqrt(x * x + w * w)) / 2; };
    const double input = soft(available, floor_width) - soft(available - pmax, width) + soft(-pmax, width);
    EXPECT_GT(input, 0);
    const double thrust_N = 2 * 0.6 * input / (g0 * isp);
    const double thrust_accel = thrust_N / (mass_kg * at["m"]) / accel_unit;  // normalized
    const double mdot = -thrust_N / (g0 * isp) / mass_kg * year_s;            // normalized
    const auto rhs = [&](std::size_t i) {
      return helios::symbolic::evaluate(parse(d["state_odes"][i]["rhs"]), table, at);
    };
    helios::symbolic::Values coast = at;
    coast["u"] = 0;
    const double gravity_vx = helios::symbolic::evaluate(parse(d["state_odes"][3]["rhs"]), table, coast);
    EXPECT_NEAR((rhs(3) - gravity_vx) / (0.6 * 0.6 * thrust_accel), 1.0, 1e-9);
    EXPECT_NEAR(rhs(6) / (0.6 * mdot), 1.0, 1e-9);
    EXPECT_LT(rhs(6), 0) << "the mass flow never turns: the engine gets nothing where the bus takes all";
    // Costate rates: -dH/dx by central differences.
    for (std::size_t i = 0; i < states.size(); ++i) {
      SCOPED_TRACE(states[i]);
      const double fd = minus_dH_dx(H, table, at, states[i], 1e-5);
      const double row = helios::symbolic::evaluate(parse(d["costate_odes"][i]["rhs"]), table, at);
      EXPECT_NEAR(row, fd, 1e-6 * (1 + std::fabs(fd)));
    }
    // The switching function: dH/du at eps = 0 along the direction's law.
    helios::symbolic::Values law = at;
    law["eps"] = 0;
    for (std::size_t k = 0; k < 3; ++k)
      law[d["control_law"]["direction"]["controls"][k].get<std::string>()] =
          helios::symbolic::evaluate(parse(d["control_law"]["direction"]["law"][k]), table, at);
    helios::symbolic::Values up = law, down = law;
    up["u"] = 0.5 + 1e-4;
    down["u"] = 0.5 - 1e-4;
    const double fd = (helios::symbolic::evaluate(H, table, up) - helios::symbolic::evaluate(H, table, down)) / 2e-4;
    const double sw = helios::symbolic::evaluate(parse(d["control_law"]["throttle"]["switching_function"]), table, at);
    EXPECT_NEAR(sw, fd, 1e-7 * (1 + std::fabs(fd)));
  }
}

// A costate row without the dT/dr part (the thrust held at its value), a wrong coefficient in the
// thrust, a cap of another width: each fails verify, naming the row or the term.
TEST(SolarElectric, VerifyFailsAMutatedDTdrRowOrThrust) {
  const json& d = derivation("S15");
  Substituted substituted(d);  // P_in and its gradient substituted
  helios::symbolic::SymbolTable& table = substituted.table;
  for (const auto& s : d["states"]) table.get(s["name"]), table.get(s["costate"]);
  for (const auto& c : d["controls"]) table.get(c["name"]);
  for (const auto& q : d["parameters"]) table.get(q["name"]);
  for (const char* n : {"lambda0", "eps", "t"}) table.get(n);
  const GiNaC::ex H = table.parse(d["hamiltonian"].get<std::string>(), "S15");
  // P0 enters only as P0/r^2: with r^2 frozen into rho2 the derivative in rx drops dT/dr.
  const GiNaC::symbol rho2("rho2");
  const GiNaC::ex rx = table.get("rx"), ry = table.get("ry"), rz = table.get("rz");
  const GiNaC::ex r2 = rx * rx + ry * ry + rz * rz;
  const GiNaC::ex frozen = H.subs(table.get("P0") == table.get("P0") * r2 / rho2);
  const GiNaC::ex without = (-frozen.diff(GiNaC::ex_to<GiNaC::symbol>(rx))).subs(rho2 == r2);
  ASSERT_FALSE((without - table.parse(d["costate_odes"][0]["rhs"].get<std::string>(), "S15")).expand().is_zero());
  json m = d;
  m["costate_odes"][0]["rhs"] = helios::symbolic::to_text(without);
  json r = verify(m);
  EXPECT_EQ(r["verdict"], "fail");
  EXPECT_EQ(check(r, "costate_ode:l_rx")["verdict"], "fail") << check(r, "costate_ode:l_rx").dump();
  // The thrust's coefficient 2 eta written as eta in the dynamics and the cost alike: the derivation is
  // consistent with itself, but not the solar-electric term verify recomputes.
  m = d;
  for (auto& row : m["dynamics"]["state_rhs"]) {
    std::string s = row;
    for (std::size_t at = s.find("eta"); at != std::string::npos; at = s.find("eta", at + 8))
      s.replace(at, 3, "(eta/2)");
    row = s;
  }
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"), "solar_electric_thrust")) << feedback(m, "dynamics_terms");
  m = d;  // a cap of another width
  for (auto& q : m["parameters"])
    if (q["name"] == "Pw") q["value"] = 2 * q["value"].get<double>();
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"), "is not 1% of its maximum input power"))
      << feedback(m, "dynamics_terms");
}

TEST(SolarElectric, WhatItCannotFlyIsRefusedNamingTheField) {
  const std::string earth = refusal_of(s01_with(kS15Engine) + "");
  EXPECT_EQ(earth, "accepted");
  std::string text = s01_with(kS15Engine);
  text.replace(text.find("The central body is the Sun"), 27, "The central body is the Earth");
  EXPECT_TRUE(contains(refusal_of(text), "needs the Sun as the central body")) << refusal_of(text);
  text = s01_with(std::string(kS15Engine) + "\nThe spacecraft has a maximum thrust of 0.5 N.");
  EXPECT_TRUE(contains(refusal_of(text), "the thrust follows from the power")) << refusal_of(text);
  // A spec (written by hand or a model) with both a thrust and the arrays is refused, not half read.
  json spec = helios::spec::parse_problem_text(problem_text("S15"), "p.txt");
  spec["spacecraft"]["thrust_N"] = 0.5;
  try {
    helios::pmp::derive_from_spec(spec);
    ADD_FAILURE() << "a thrust beside the arrays was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "field /spacecraft/thrust_N")) << e.what();
  }
  text = s01_with(kS15Engine);
  text.replace(text.find("an efficiency of 0.6"), 20, "an efficiency of 1.6");
  EXPECT_TRUE(contains(refusal_of(text), "efficiency must be in (0, 1]")) << refusal_of(text);
  text = s01_with(kS15Engine);
  text.replace(text.find("20 kW"), 5, "20 kN");
  EXPECT_TRUE(contains(refusal_of(text), "kN")) << refusal_of(text);
}

// The cap stated by the engine's maximum thrust is the input power at which it gives that thrust,
// T c / (2 eta): 0.5 N at 2000 s and an efficiency of 0.5 is the 9806.65 W cap; with both stated,
// the lower one binds.
TEST(SolarElectric, ACapStatedByItsThrustIsThePowerThatGivesIt) {
  const auto pmax_W = [](const std::string& engine) {
    const json d = derive_text(s01_with("The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, " + engine +
                                        " with an efficiency of 0.5 and a specific impulse of 2000 s.\nThe "
                                        "spacecraft has an initial mass of 1000 kg."));
    double pmax = NAN, p0 = NAN;
    for (const auto& q : d["parameters"]) {
      if (q["name"] == "Pmax") pmax = q["value"];
      if (q["name"] == "P0") p0 = q["value"];
    }
    return pmax / p0 * 20000;  // in W, through P0's own normalization
  };
  EXPECT_NEAR(pmax_W("the engine gives at most 0.5 N") / 9806.65, 1.0, 1e-12);
  EXPECT_NEAR(pmax_W("the engine gives at most 500 mN, the engine takes at most 5 kW") / 5000, 1.0, 1e-12);
  EXPECT_NEAR(pmax_W("a maximum thrust of 0.25 N, the engine takes at most 9 kW") / 4903.325, 1.0, 1e-12);
}

// In the 1-AU limit (arrays so large that the cap always binds, Pmax = T c / (2 eta)), the
// derivation is S01's with T(r) = Tmax up to the smooth cap's Pw^2/(4 (Pa - Pmax)) < 1e-6 Tmax.
TEST(SolarElectric, WithTheCapAlwaysBindingTheThrustIsTheConstantEngines) {
  const json sep = derive_text(s01_with(
      "The spacecraft is solar-electric: its arrays give 1000 MW at 1 AU, the engine takes at most 9806.65 W with an "
      "efficiency of 0.5 and a specific impulse of 2000 s.\nThe spacecraft has an initial mass of 1000 kg."));
  const json& s01 = derivation("S01");
  double tmax = 0, c_sep = 0, c_s01 = 0;
  for (const auto& q : s01["parameters"]) {
    if (q["name"] == "Tmax") tmax = q["value"];
    if (q["name"] == "c") c_s01 = q["value"];
  }
  for (const auto& q : sep["parameters"])
    if (q["name"] == "c") c_sep = q["value"];
  EXPECT_DOUBLE_EQ(c_sep, c_s01);
  Substituted substituted(sep);  // P_in and its gradient substituted
  helios::symbolic::SymbolTable& table = substituted.table;
  for (const auto& s : sep["states"]) table.get(s["name"]);
  for (const auto& c : sep["controls"]) table.get(c["name"]);
  helios::symbolic::Values at;
  for (const auto& q : sep["parameters"]) at[table.get(q["name"]).get_name()] = q["value"];
  for (const char* n : {"lambda0", "eps", "t"}) table.get(n);
  for (const double dist : {0.9, 1.0, 1.7}) {
    at["rx"] = dist, at["ry"] = 0, at["rz"] = 0, at["m"] = 1, at["u"] = 1;
    const double flow =
        -helios::symbolic::evaluate(table.parse(sep["state_odes"][6]["rhs"].get<std::string>(), "sep"), table, at);
    EXPECT_NEAR(flow * c_sep / tmax, 1.0, 1e-6);
  }
}

// ---- atmospheric drag: one term (pmp/terms/drag.cpp), its recomputation (verify/terms/drag.cpp) and
// its sentence (spec/forms/drag.cpp), nothing else

const char* kDrag =
    "\nAtmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential atmosphere of "
    "density 3.6e-12 kg/m^3 at 400 km altitude with scale height 58 km.\n";

// S05 (a J2 orbit raise about the Earth at 7000 km) with drag: derived as one more term, verified, the
// drag in its rows is the physical deceleration of the text's numbers, its costate rows are -dH/dx by
// central differences, and verify fails a costate row without drag or a drag of the wrong sign.
TEST(Drag, TheSentenceIsOneTermDerivedAndVerified) {
  const json d = derive_text(problem_text("S05") + kDrag);
  const json& plain = derivation("S05");
  EXPECT_EQ(term(const_cast<json&>(d), "drag")["parameters"], json({"Bd", "r0", "H", "w"}));
  EXPECT_EQ(verify(d)["verdict"], "pass") << verify(d).dump(1);
  helios::symbolic::SymbolTable table;
  for (const auto& s : d["states"]) table.get(s["name"]), table.get(s["costate"]);
  for (const auto& c : d["controls"]) table.get(c["name"]);
  for (const auto& q : d["parameters"]) table.get(q["name"]);
  for (const char* n : {"lambda0", "eps", "t"}) table.get(n);
  helios::symbolic::Values at;
  for (const auto& q : d["parameters"]) at[q["name"].get<std::string>()] = q["value"];
  const auto parse = [&](const json& e) { return table.parse(e.get<std::string>(), "drag"); };
  const double R = 6378.137, T = std::sqrt(R * R * R / 398600.4418);  // the units: km and s
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (const double altitude_km : {200.0, 400.0, 622.0}) {
    SCOPED_TRACE(altitude_km);
    // On the x axis, moving along y with a radial and a vertical part, engine off.
    const double r_km = R + altitude_km, v[3] = {0.1, 7.7, 0.3};
    at["rx"] = r_km / R, at["ry"] = 0, at["rz"] = 0;
    at["vx"] = v[0] * T / R, at["vy"] = v[1] * T / R, at["vz"] = v[2] * T / R;
    at["m"] = 0.9, at["u"] = 0, at["ax"] = 1, at["ay"] = 0, at["az"] = 0;
    for (const auto& s : d["states"]) at[s["costate"].get<std::string>()] = uni(rng);
    at["lambda0"] = 1, at["eps"] = 0.5, at["t"] = 0;
    // -1/2 rho Cd A / m |v_rel| v_rel with v_rel = v - w z x r, in m/s^2.
    const double w = 7.2921159e-5, rel[3] = {v[0], v[1] - w * r_km, v[2]};
    const double speed = std::sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]) * 1e3;
    const double rho = 3.6e-12 * std::exp(-(altitude_km - 400) / 58);
    for (int k = 0; k < 3; ++k) {
      const double want = -0.5 * rho * 2.2 * 4 / (500 * 0.9) * speed * rel[k] * 1e3;
      const double got = (helios::symbolic::evaluate(parse(d["state_odes"][3 + k]["rhs"]), table, at) -
                          helios::symbolic::evaluate(parse(plain["state_odes"][3 + k]["rhs"]), table, at)) *
                         R * 1e3 / (T * T);
      // Less the rows without drag: gravity's 8 m/s^2 leaves an absolute round-off of about 1e-15 of it.
      EXPECT_NEAR(got, want, 1e-9 * std::fabs(want) + 1e-13) << k;
    }
    // The costate rows: -dH/dx by central differences (thrusting, so every part is in H).
    at["u"] = 0.6, at["ax"] = 0.6, at["ay"] = 0.8;
    const GiNaC::ex H = parse(d["hamiltonian"]);
    for (const auto& s : d["states"]) {
      const std::string x = s["name"];
      SCOPED_TRACE(x);
      const double fd = minus_dH_dx(H, table, at, x, 1e-6);
      double row = 0;
      for (const auto& c : d["costate_odes"])
        if (c["costate"] == s["costate"]) row = helios::symbolic::evaluate(parse(c["rhs"]), table, at);
      EXPECT_NEAR(row, fd, 1e-6 * (1 + std::fabs(fd)));
    }
  }
  json m = d;  // the l_vx row of the problem without drag
  m["costate_odes"][3] = plain["costate_odes"][3];
  EXPECT_EQ(check(verify(m), "costate_ode:l_vx")["verdict"], "fail");
  m = d;  // drag that pushes: its sign turned in the dynamics
  for (auto& row : m["dynamics"]["state_rhs"]) {
    std::string s = row;
    for (std::size_t at = s.find("Bd"); at != std::string::npos; at = s.find("Bd", at + 5)) s.replace(at, 2, "(-Bd)");
    row = s;
  }
  EXPECT_TRUE(contains(feedback(m, "dynamics_terms"), "the term drag has the wrong sign"))
      << feedback(m, "dynamics_terms");
}

TEST(Drag, WhatItCannotBeIsRefusedAndNeglectingItAddsNothing) {
  const json spec = helios::spec::parse_problem_text(problem_text("S05") + "\nNeglect atmospheric drag.\n", "p.txt");
  EXPECT_EQ(spec["dynamics"]["perturbations"], json::parse(R"([{"kind": "j2"}])"));
  // An atmosphere at rest, stated: w = 0.
  const json still = derive_text(problem_text("S05") +
                                 "\nThe spacecraft feels atmospheric drag with Cd = 2.2 and an area of 4 m^2 in a "
                                 "non-rotating atmosphere of density 3.6e-12 kg/m^3 at 400 km altitude and a scale "
                                 "height of 58 km.\n");
  for (const auto& q : still["parameters"])
    if (q["name"] == "w") {
      EXPECT_EQ(q["value"], 0.0);
    }
  EXPECT_TRUE(contains(refusal_of(problem_text("S01") + kDrag), "drag needs a planet with an atmosphere"))
      << refusal_of(problem_text("S01") + kDrag);
  const std::string half = problem_text("S05") + "\nAtmospheric drag acts on the spacecraft with Cd = 2.2.\n";
  EXPECT_TRUE(contains(refusal_of(half), "atmospheric drag needs its area (m^2), the density (kg/m^3)"))
      << refusal_of(half);
}

// ---- a solar-electric thruster given by fits to its input power (pmp/terms/solar_electric_fits.cpp):
// the intermediates P_in, T_P, F_P and P_in's gradient keep its rows short --------------------------

const char* kFitsArrays = "The spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW.\n";
const char* kNstarLike =
    "The thruster's thrust is -1.9137 + 36.242 P - 0.5 P^2 mN and its mass flow is 0.47556 + 0.90209 P + 0.01 P^3 "
    "mg/s for an input power P between 0.5 and 2.6 kW.\nThe spacecraft has an initial mass of 150 kg.";

// A random state and costate at the Sun's distance `dist` (AU), with a throttle and a direction.
helios::symbolic::Values point_at(const json& d, const helios::symbolic::Values& parameters, double dist,
                                  std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(-1, 1);
  helios::symbolic::Values at = parameters;
  double dir[3] = {uni(rng), uni(rng), uni(rng)};
  const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  at["rx"] = dist * dir[0] / n, at["ry"] = dist * dir[1] / n, at["rz"] = dist * dir[2] / n;
  for (const char* v : {"vx", "vy", "vz"}) at[v] = 6 * uni(rng);
  at["m"] = 0.7 + 0.2 * uni(rng);
  for (const auto& s : d["states"]) at[s["costate"].get<std::string>()] = uni(rng);
  at["lambda0"] = 0.5, at["eps"] = 0.3, at["t"] = 0, at["u"] = 0.6;
  at["ax"] = 0.6, at["ay"] = 0.8, at["az"] = 0;
  return at;
}

// S01's transfer with fits equal to S15's engine (T = 2 eta P / (g0 Isp), F = T / (g0 Isp)) derive S15's dynamics and
// costate rates (its P_in kept by name and differentiated through), list their term and verify.
TEST(FittedThruster, FitsEqualToTheEfficiencyEngineDeriveItsRows) {
  const std::string fits =
      "The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, the bus uses 0.5 kW.\nThe thruster's thrust is "
      "61.1829727786757 P mN and its mass flow is 3.1194634650301425 P mg/s, with P its input power in kW up to 10 "
      "kW.\nThe spacecraft has an initial mass of 1000 kg.";
  const json d = derive_text(s01_with(fits));
  EXPECT_NO_THROW(helios::io::validate("derivation", d, "terms_test"));
  std::vector<std::string> intermediates;
  for (const auto& q : d["intermediates"]) intermediates.push_back(q["name"]);
  EXPECT_EQ(intermediates, (std::vector<std::string>{"P_in", "T_P", "F_P", "dP_in_drx", "dP_in_dry", "dP_in_drz"}));
  const auto terms = helios::derivation::read_terms(d, "fits");
  ASSERT_EQ(terms->size(), 3u);
  EXPECT_EQ((*terms)[1].name, "solar_electric_fitted_thrust");
  EXPECT_EQ((*terms)[1].parameters.size(), 14u);  // P0 Pbus Pmax Pw T0..T4 F0..F4: no lowest power
  EXPECT_EQ((*terms)[2].parameters, (*terms)[1].parameters);
  for (const auto& row : d["costate_odes"]) EXPECT_LT(row["rhs"].get<std::string>().size(), 2000u) << row;
  const json r = verify(d);
  EXPECT_EQ(r["verdict"], "pass") << r.dump(1);
  // S01's target in S15's units: the same points give the same rows (the parameters differ in name).
  const json& s15 = derivation("S15");
  Substituted fitted(d), efficiency(s15);
  std::mt19937_64 rng(15);
  for (const double dist : {0.7, 1.0, 1.38, 1.65, 3.0}) {
    SCOPED_TRACE(dist);
    helios::symbolic::Values at = point_at(d, fitted.values, dist, rng), at15 = at;
    for (const auto& [name, value] : efficiency.values) at15[name] = value;
    for (std::size_t i = 0; i < 7; ++i) {
      const double a = fitted.at(d["state_odes"][i]["rhs"], at), b = efficiency.at(s15["state_odes"][i]["rhs"], at15);
      EXPECT_NEAR(a, b, 1e-11 * (1 + std::fabs(b))) << "state " << i;
      const double la = fitted.at(d["costate_odes"][i]["rhs"], at);
      const double lb = efficiency.at(s15["costate_odes"][i]["rhs"], at15);
      EXPECT_NEAR(la, lb, 1e-9 * (1 + std::fabs(lb))) << "costate " << i;
    }
  }
}

// Every row of S01's transfer by an NSTAR-like quadratic/cubic fit with a lowest power against numbers computed here:
// the dynamics against the fits in SI at the input power of the text's watts, the costate rates
// against central differences of H, the switching function against H along the throttle.
TEST(FittedThruster, EveryDerivationRowAgreesWithTheFitsAndFiniteDifferences) {
  const json d = derive_text(s01_with(std::string(kFitsArrays) + kNstarLike));
  EXPECT_EQ(verify(d)["verdict"], "pass");
  Substituted s(d);
  const GiNaC::ex H = s.table.parse(d["hamiltonian"].get<std::string>(), "H");
  const double AU_m = 149597870.691e3, year_s = 365.25 * 86400, mass_kg = 150;
  const double accel_unit = AU_m / (year_s * year_s);
  std::mt19937_64 rng(26);
  // Through the cap (4.7 kW at 1 AU, 2.6 kW at 1.33 AU) and the lowest power (0.5 kW at 2.5 AU).
  for (const double dist : {0.8, 1.0, 1.3, 1.33, 1.36, 1.65, 2.2, 2.45, 2.5, 2.55, 3.5}) {
    SCOPED_TRACE(dist);
    helios::symbolic::Values at = point_at(d, s.values, dist, rng);
    const auto soft = [](double x, double w) { return (x + std::sqrt(x * x + w * w)) / 2; };
    const double available = 5000 / (dist * dist) - 300;
    const double P = soft(available, 3) - soft(available - 2600, 26) + soft(-2600, 26), kW = P / 1000;
    const double on = 1 / (1 + std::exp(-(P - 500) / 5));
    const double thrust_N = on * (-1.9137 + 36.242 * kW - 0.5 * kW * kW) * 1e-3;
    const double flow_kg_s = on * (0.47556 + 0.90209 * kW + 0.01 * kW * kW * kW) * 1e-6;
    const auto rhs = [&](std::size_t i, const helios::symbolic::Values& p) {
      return s.at(d["state_odes"][i]["rhs"], p);
    };
    helios::symbolic::Values coast = at;
    coast["u"] = 0;
    const double accel = thrust_N / (mass_kg * at["m"]) / accel_unit, flow = flow_kg_s / mass_kg * year_s;
    EXPECT_NEAR(rhs(3, at) - rhs(3, coast), 0.6 * 0.6 * accel, 1e-10 * (1 + std::fabs(accel)));
    EXPECT_NEAR(rhs(6, at), -0.6 * flow, 1e-10 * (1 + flow));
    if (on > 1e-3) EXPECT_NEAR(rhs(6, at) / (-0.6 * flow), 1.0, 1e-9);
    for (std::size_t i = 0; i < 7; ++i) {
      const std::string x = d["states"][i]["name"];
      SCOPED_TRACE(x);
      const double fd = minus_dH_dx(H, s.table, at, x, 1e-6);
      EXPECT_NEAR(s.at(d["costate_odes"][i]["rhs"], at), fd, 1e-6 * (1 + std::fabs(fd)));
    }
    helios::symbolic::Values up = at, down = at;
    up["eps"] = down["eps"] = 0;
    up["u"] = 0.5 + 1e-4;
    down["u"] = 0.5 - 1e-4;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::string a = d["control_law"]["direction"]["controls"][k];
      up[a] = down[a] = s.at(d["control_law"]["direction"]["law"][k], at);
    }
    const double fd =
        (helios::symbolic::evaluate(H, s.table, up) - helios::symbolic::evaluate(H, s.table, down)) / 2e-4;
    EXPECT_NEAR(s.at(d["control_law"]["throttle"]["switching_function"], at), fd, 1e-7 * (1 + std::fabs(fd)));
  }
}

// A costate row without its dT/dr part, a thrust fit changed in its intermediate, the power's
// gradient changed, a step of another width: each fails verify, naming the row or the term; an
// intermediate that uses a costate, or a shooting row that names one, is refused in one line.
TEST(FittedThruster, VerifyFailsAMutatedRowOrIntermediate) {
  const json d = derive_text(s01_with(std::string(kFitsArrays) + kNstarLike));
  const auto mutated = [&](const std::function<void(json&)>& change) {
    json m = d;
    change(m);
    return m;
  };
  const auto replace_all = [](std::string s, const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
      s.replace(at, from.size(), to);
    return s;
  };
  const json no_dTdr = mutated(
      [&](json& m) { m["costate_odes"][0]["rhs"] = replace_all(m["costate_odes"][0]["rhs"], "dP_in_drx", "0"); });
  EXPECT_EQ(check(verify(no_dTdr), "costate_ode:l_rx")["verdict"], "fail");
  const json thrust = mutated([&](json& m) {
    m["intermediates"][1]["expression"] = replace_all(m["intermediates"][1]["expression"], "T1", "(1.01*T1)");
  });
  EXPECT_TRUE(contains(feedback(thrust, "dynamics_terms"), "solar_electric_fitted_thrust"))
      << feedback(thrust, "dynamics_terms");
  const json gradient = mutated([&](json& m) {
    for (auto& q : m["intermediates"])
      if (q["name"] == "dP_in_dry") q["expression"] = "1.01*(" + q["expression"].get<std::string>() + ")";
  });
  const json gradient_report = verify(gradient);
  EXPECT_EQ(check(gradient_report, "costate_ode:l_ry")["verdict"], "fail");
  EXPECT_EQ(check(gradient_report, "costate_ode:l_rx")["verdict"], "pass");
  // the wrong partial fails its own check, and the row that names it says so
  EXPECT_EQ(check(gradient_report, "intermediate:dP_in_dry")["verdict"], "fail");
  EXPECT_EQ(check(gradient_report, "intermediate:dP_in_drx")["verdict"], "pass");
  EXPECT_TRUE(contains(check(gradient_report, "costate_ode:l_ry")["feedback"].get<std::string>(),
                       "It names dP_in_dry, which fails its own check (intermediates): correct it first."));
  const json step = mutated([&](json& m) {
    for (auto& q : m["parameters"])
      if (q["name"] == "Pn") q["value"] = 3 * q["value"].get<double>();
  });
  EXPECT_TRUE(contains(feedback(step, "dynamics_terms"), "is not 1% of Pmin")) << feedback(step, "dynamics_terms");
  const json in_row = mutated([&](json& m) {
    m["shooting"]["equations"][0]["expression"] =
        m["shooting"]["equations"][0]["expression"].get<std::string>() + "+0*P_in";
  });
  try {
    helios::verify::verify_derivation(in_row, {});
    ADD_FAILURE() << "an intermediate in a shooting equation was read";
  } catch (const std::exception& e) {
    EXPECT_TRUE(contains(e.what(), "field /shooting/equations/0/expression: uses the intermediate P_in")) << e.what();
  }
  const json costate = mutated([&](json& m) { m["intermediates"][0]["expression"] = "l_rx"; });
  try {
    helios::verify::verify_derivation(costate, {});
    ADD_FAILURE() << "an intermediate in a costate was read";
  } catch (const std::exception& e) {
    EXPECT_TRUE(contains(e.what(), "the intermediate P_in uses l_rx")) << e.what();
  }
}

// A chain of intermediates, each small as written, whose substitution asks for a million terms
// ((rx + ... + vz)^40 as a fourth power of a tenth power) is refused in one line, not expanded.
TEST(FittedThruster, IntermediatesThatWouldExpandPastTheLimitAreRefused) {
  json d = derive_text(s01_with(std::string(kFitsArrays) + kNstarLike));
  d["intermediates"].push_back(
      {{"name", "Q1"}, {"meaning", "a tenth power"}, {"expression", "(rx+ry+rz+vx+vy+vz)^10"}});
  d["intermediates"].push_back({{"name", "Q2"}, {"meaning", "its fourth power"}, {"expression", "Q1^4"}});
  try {
    helios::verify::verify_derivation(d, {});
    ADD_FAILURE() << "a substitution of 1e6 terms was accepted";
  } catch (const std::exception& e) {
    EXPECT_TRUE(contains(e.what(), "with its intermediates substituted would expand to about 1.2e+06 terms"))
        << e.what();
  }
}

// What the fits cannot be: negative where the engine runs (without a lowest power the range starts
// at no power), beside an efficiency (the sentence's refusal), or without arrays.
TEST(FittedThruster, AFitNegativeWhereTheEngineRunsIsRefused) {
  const std::string no_bottom = refusal_of(s01_with(
      std::string(kFitsArrays) +
      "The thruster's thrust is -1.9137 + 36.242 P mN and its mass flow is 0.47556 + 0.90209 P mg/s, with P its input "
      "power in kW up to 2.6 kW.\nThe spacecraft has an initial mass of 150 kg."));
  EXPECT_TRUE(contains(no_bottom, "-1.91")) << no_bottom;
  EXPECT_TRUE(contains(no_bottom, "state the range's bottom")) << no_bottom;
  json spec = helios::spec::parse_problem_text(s01_with(std::string(kFitsArrays) + kNstarLike), "problem.txt");
  spec["spacecraft"]["mass_flow_polynomial_mg_s"] = json::array({0.47556, -0.5});
  try {
    helios::pmp::derive_from_spec(spec);
    ADD_FAILURE() << "a mass flow negative at 2.6 kW was derived";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "field /spacecraft/mass_flow_polynomial_mg_s")) << e.what();
  }
}

// A spec written by hand skips the sentence's rule that the jet power T^2/(2 mdot) stays below the
// input power; the term keeps it: a mass flow given in kg/s read as mg/s is refused at derivation.
TEST(FittedThruster, AJetPowerAboveTheInputPowerIsRefusedInASpecWrittenByHand) {
  json spec = helios::spec::parse_problem_text(s01_with(std::string(kFitsArrays) + kNstarLike), "problem.txt");
  EXPECT_NO_THROW(helios::pmp::derive_from_spec(spec));
  for (auto& c : spec["spacecraft"]["mass_flow_polynomial_mg_s"]) c = c.get<double>() / 1000;
  try {
    helios::pmp::derive_from_spec(spec);
    ADD_FAILURE() << "fits whose jet power is 1000 times the input power were derived";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what,
                         "field /spacecraft/thrust_polynomial_mN: with mass_flow_polynomial_mg_s it gives a jet "
                         "power T^2/(2 mdot) of "))
        << what;
    EXPECT_TRUE(contains(what, "at an input power of 500 W")) << what;
  }
}

// A thruster table (spacecraft.thruster_table) is fitted by the term: a table of the NSTAR-like fits'
// own values over their range derives the fits' parameters, and the table's meaning says how it was
// fitted; a table no polynomial follows, or beside fits, is refused naming the field.
json nstar_table_spec(const std::vector<double>& powers_kW) {
  json spec = helios::spec::parse_problem_text(s01_with(std::string(kFitsArrays) + kNstarLike), "problem.txt");
  json& sc = spec["spacecraft"];
  const std::vector<double> T = sc["thrust_polynomial_mN"], F = sc["mass_flow_polynomial_mg_s"];
  const auto at = [](const std::vector<double>& c, double P) {
    double v = 0;
    for (std::size_t k = c.size(); k-- > 0;) v = v * P + c[k];
    return v;
  };
  for (const char* key :
       {"thrust_polynomial_mN", "mass_flow_polynomial_mg_s", "min_engine_power_W", "max_engine_power_W"})
    sc.erase(key);
  for (const double P : powers_kW)
    sc["thruster_table"].push_back(
        {{"input_power_W", P * 1000}, {"thrust_N", at(T, P) * 1e-3}, {"mass_flow_kg_s", at(F, P) * 1e-6}});
  return spec;
}

TEST(FittedThruster, ATableOfTheFitsValuesDerivesTheFits) {
  const json fits = derive_text(s01_with(std::string(kFitsArrays) + kNstarLike));
  const json table = helios::pmp::derive_from_spec(nstar_table_spec({0.5, 0.8, 1.1, 1.4, 1.7, 2.0, 2.3, 2.6}));
  std::map<std::string, double> want;
  for (const auto& q : fits["parameters"]) want[q["name"]] = q["value"];
  int compared = 0;
  for (const auto& q : table["parameters"]) {
    const std::string name = q["name"];
    if (!want.count(name)) continue;
    ++compared;
    const double scale = name[0] == 'T' || name[0] == 'F' ? std::fabs(want["T1"]) + std::fabs(want["F1"]) : 1.0;
    EXPECT_NEAR(q["value"].get<double>(), want[name], 1e-9 * (scale + std::fabs(want[name]))) << name;
    if (name == "T0")
      EXPECT_TRUE(contains(q["meaning"].get<std::string>(),
                           "(least squares over the thruster table's 8 rows: the thrust of degree 2, off by at most "))
          << q["meaning"];
  }
  EXPECT_EQ(compared, static_cast<int>(want.size()));
  EXPECT_EQ(verify(table)["verdict"], "pass");
}

TEST(FittedThruster, ATableNoPolynomialFollowsOrBesideFitsIsRefused) {
  json kinked = nstar_table_spec({0.5, 0.8, 1.1, 1.4, 1.7, 2.0, 2.3, 2.6});
  kinked["spacecraft"]["thruster_table"][5]["thrust_N"] = 0.080;  // a jump of 20 % at 2 kW
  try {
    helios::pmp::derive_from_spec(kinked);
    ADD_FAILURE() << "a table with a kink was fitted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "field /spacecraft/thruster_table/")) << e.what();
    EXPECT_TRUE(contains(e.what(), "no polynomial of degree 4 or less in the power follows the table")) << e.what();
  }
  json both = nstar_table_spec({0.5, 1.5, 2.6});
  both["spacecraft"]["thrust_polynomial_mN"] = json::array({1, 30});
  try {
    helios::pmp::derive_from_spec(both);
    ADD_FAILURE() << "a table beside fits was derived";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(),
                         "field /spacecraft/thrust_polynomial_mN: the thruster table gives the engine's "
                         "performance and its power range; drop thrust_polynomial_mN"))
        << e.what();
  }
  json unsorted = nstar_table_spec({0.5, 1.5, 1.2, 2.6});
  try {
    helios::pmp::derive_from_spec(unsorted);
    ADD_FAILURE() << "a table out of order was derived";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "field /spacecraft/thruster_table/2/input_power_W: 1200 W is not above"))
        << e.what();
  }
}

// The chain rule through named intermediates differentiates as the substituted expression does,
// and a named partial stands for its intermediate's own derivative.
TEST(ChainRule, DifferentiatesThroughIntermediatesAsTheirSubstitution) {
  const GiNaC::symbol x("x"), y("y"), p("p"), q("q"), dp("dp");
  const GiNaC::ex p_of = GiNaC::sqrt(x * x + y), q_of = GiNaC::pow(p, 3) + x * p;
  helios::symbolic::ChainRule chain;
  chain.add(p, p_of);
  chain.add(q, q_of);
  const GiNaC::ex e = q * GiNaC::sin(p) + x;
  const GiNaC::exmap inlined = {{p, p_of}, {q, q_of.subs(p == p_of)}};
  const GiNaC::lst point = {x == 0.7, y == 1.3};
  for (const auto& v : {x, y}) {
    const GiNaC::ex through = chain.diff(e, v).subs(inlined), direct = e.subs(inlined).diff(v);
    EXPECT_NEAR(GiNaC::ex_to<GiNaC::numeric>((through - direct).subs(point).evalf()).to_double(), 0, 1e-12);
  }
  chain.add(dp, p_of.diff(x));
  chain.name_partial(p, x, dp);
  EXPECT_TRUE(chain.diff(p * p, x).is_equal(2 * p * dp));
  EXPECT_THROW(chain.add(p, x), std::invalid_argument);
}

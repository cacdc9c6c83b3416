// Dynamics and costs as terms (issue 31): each builtin derivation lists its terms with their
// parameters, helios-verify recomputes each and names the one at fault, the code generator's
// template is chosen by its terms, and a third body is one term: stated in a sentence, derived,
// verified.
#include <gtest/gtest.h>

#include <map>
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
  term(d, "thrust")["name"] = "drag";  // refused by the derivation's strict reader (an llm's feedback)
  try {
    verify(d);
    ADD_FAILURE() << "an unknown term was read";
  } catch (const helios::input_error& e) {
    EXPECT_TRUE(contains(e.what(), "field terms[1].name: unknown term 'drag'")) << e.what();
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

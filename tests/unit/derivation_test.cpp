#include "helios/derivation/reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "helios/derivation/document.hpp"
#include "helios/derivation/names.hpp"
#include "helios/io/error.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "helios/sweep/sweep.hpp"

namespace {

using helios::derivation::Document;
using helios::derivation::Reader;
using helios::derivation::Unit;
using helios::derivation::Units;
using helios::io::json;

json derivation_of(const std::string& scenario) {
  return helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
      helios::io::read_text(std::string(HELIOS_SOURCE_DIR) + "/scenarios/" + scenario + "/problem.txt"), scenario));
}

Units heliocentric() {
  Units u;
  u.length = "AU";
  u.time = "Julian year";
  u.length_km = 149597870.691;
  u.time_s = 31557600.0;
  u.mass_kg = 1000.0;
  return u;
}

TEST(DerivationUnits, ParsesProductsQuotientsAndPowers) {
  const Units u = heliocentric();
  EXPECT_EQ(u.parse("AU", "w"), (Unit{1, 0, 0}));
  EXPECT_EQ(u.parse("AU/Julian year", "w"), (Unit{1, -1, 0}));
  EXPECT_EQ(u.parse("AU^3/Julian year^2", "w"), (Unit{3, -2, 0}));
  EXPECT_EQ(u.parse("initial mass*AU/Julian year^2", "w"), (Unit{1, -2, 1}));
  EXPECT_EQ(u.parse("AU/Julian year/Julian year", "w"), (Unit{1, -2, 0}));
  EXPECT_EQ(u.parse("final mass", "w"), (Unit{0, 0, 1}));
  EXPECT_EQ(u.parse("1", "w"), (Unit{0, 0, 0}));
}

TEST(DerivationUnits, BaseUnitNamesMayHoldSpacesAndParentheses) {
  Units u = heliocentric();
  u.length = "Earth radius";
  u.time = "time unit (mu = 1)";
  EXPECT_EQ(u.parse("Earth radius^3/time unit (mu = 1)^2", "w"), (Unit{3, -2, 0}));
}

TEST(DerivationUnits, SiFactorsAreComputedFromTheBaseUnits) {
  const Units u = heliocentric();
  EXPECT_DOUBLE_EQ(u.si_factor(u.parse("AU", "w")), 149597870691.0);
  EXPECT_DOUBLE_EQ(u.si_factor(u.parse("AU/Julian year", "w")), 149597870691.0 / 31557600.0);
  EXPECT_DOUBLE_EQ(u.si_factor(u.parse("initial mass*AU/Julian year^2", "w")),
                   1000.0 * 149597870691.0 / (31557600.0 * 31557600.0));
  EXPECT_DOUBLE_EQ(u.si_factor(u.parse("1", "w")), 1.0);
  EXPECT_DOUBLE_EQ(u.to_si(2.0, u.parse("Julian year^-1", "w")), 2.0 / 31557600.0);
  EXPECT_DOUBLE_EQ(Units::factor(u.parse("AU/Julian year", "w"), u.length_km, u.time_s, u.mass_kg),
                   149597870.691 / 31557600.0);
}

TEST(DerivationUnits, AnUnknownUnitIsAnInputErrorNamingTheFieldAndTheFactor) {
  const Units u = heliocentric();
  try {
    u.parse("AU/fortnight", "derivation.json: field /parameters/3/unit");
    FAIL() << "no error";
  } catch (const helios::input_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("derivation.json: field /parameters/3/unit"), std::string::npos) << what;
    EXPECT_NE(what.find("'fortnight'"), std::string::npos) << what;
  }
  EXPECT_THROW(u.parse("AU^x", "w"), helios::input_error);
}

TEST(DerivationReader, ReadsNamesSymbolsAndUnitsOfS01) {
  const json d = derivation_of("S01");
  const Reader r(d, "S01/derivation.json");
  EXPECT_EQ(r.states, (std::vector<std::string>{"rx", "ry", "rz", "vx", "vy", "vz", "m"}));
  EXPECT_EQ(r.costates.size(), r.states.size());
  EXPECT_EQ(r.controls[static_cast<std::size_t>(r.throttle_index)], "u");
  EXPECT_EQ(r.variables.size(), d.at("shooting").at("variables").size());
  for (const auto& name : {"t", "rx_tf", "l_m_t0", "Tmax", "lambda0"}) EXPECT_TRUE(r.symbols.has(name)) << name;
  EXPECT_EQ(r.state_quantities.back().unit, (Unit{0, 0, 1}));
  const auto* c = r.exhaust_velocity();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->name, "c");
  EXPECT_NEAR(r.units.to_si(c->value, c->unit), 2000 * 9.80665, 1e-6);  // Isp 2000 s
}

TEST(DerivationReader, AStateOfAnUnreadableUnitNamesTheFileAndField) {
  json d = derivation_of("S01");
  d["states"][6]["unit"] = "tonne";
  try {
    const Reader r(d, "S01/derivation.json");
    FAIL() << "no error";
  } catch (const helios::input_error& e) {
    EXPECT_NE(std::string(e.what()).find("S01/derivation.json: field /states/6/unit"), std::string::npos) << e.what();
  }
}

// The message of the input_error reading `d` throws, "" when it reads.
std::string read_error(const json& d, bool parse_units = true) {
  try {
    const Reader r(d, "x.json", parse_units);
  } catch (const helios::input_error& e) {
    return e.what();
  }
  return "";
}

TEST(DerivationReader, ReadsStrictlyWhatAModelMayHaveWrittenWrong) {
  json d = derivation_of("S01");
  d["states"][2].erase("costate");
  EXPECT_EQ(read_error(d), "x.json: field /states/2/costate is missing");
  d = derivation_of("S01");
  d["controls"][1]["kind"] = "throttle";
  EXPECT_EQ(read_error(d), "x.json: more than one throttle control (u, ax)");
  d = derivation_of("S01");
  d["controls"][2]["kind"] = "gimbal";
  EXPECT_EQ(read_error(d), "x.json: control ay has unknown kind 'gimbal'");
  d = derivation_of("S01");
  d["parameters"][0]["value"] = "39.5";
  EXPECT_EQ(read_error(d), "x.json: field /parameters/0/value must be a number, got \"39.5\"");
  d = derivation_of("S01");
  d["states"] = json::array();
  EXPECT_EQ(read_error(d), "x.json: field states must be a non-empty array");
  // The verifier reads the names without the units (it checks the mathematics, not unit texts).
  d = derivation_of("S01");
  d["states"][6]["unit"] = "tonne";
  EXPECT_NE(read_error(d), "");
  EXPECT_EQ(read_error(d, false), "");
}

TEST(DerivationReader, ASailHasNoExhaustVelocity) {
  const json d = derivation_of("S11");
  EXPECT_EQ(Reader(d).exhaust_velocity(), nullptr);
}

TEST(DerivationDocument, ReadsEverySectionOfS01) {
  const json d = derivation_of("S01");
  const Document doc(d, "S01/derivation.json");
  EXPECT_EQ(doc.problem_id, "S01");
  EXPECT_EQ(doc.hamiltonian.text, d["hamiltonian"].get<std::string>());
  EXPECT_EQ(doc.hamiltonian.pointer, "/hamiltonian");
  ASSERT_EQ(doc.dynamics.state_rhs.size(), 7u);
  EXPECT_EQ(doc.dynamics.state_rhs[3].pointer, "/dynamics/state_rhs/3");
  ASSERT_EQ(doc.costate_odes.size(), 7u);
  EXPECT_EQ(doc.costate_odes[6].name, "l_m");
  EXPECT_EQ(doc.costate_odes[6].rhs.pointer, "/costate_odes/6/rhs");
  ASSERT_TRUE(doc.control_law.direction && doc.control_law.throttle);
  EXPECT_FALSE(doc.control_law.sail);
  EXPECT_EQ(doc.control_law.direction->controls, (std::vector<std::string>{"ax", "ay", "az"}));
  EXPECT_EQ(doc.control_law.throttle->bounds, (std::vector<double>{0, 1}));
  EXPECT_EQ(doc.times.final_time, "fixed");
  EXPECT_TRUE(doc.times.tf);
  EXPECT_EQ(doc.shooting.variables.size(), doc.shooting.equations.size());
  ASSERT_NE(doc.shooting.equation("normalization"), nullptr);
  EXPECT_EQ(doc.shooting.equation("nosuch"), nullptr);
  EXPECT_FALSE(doc.constraints.empty());
  EXPECT_TRUE(doc.interior_events.empty());
  // Parameters carry their role; units are exponents of length, time and mass.
  EXPECT_EQ(doc.parameter("c").role, helios::derivation::Role::ExhaustVelocity);
  EXPECT_EQ(doc.parameter("mu").role, helios::derivation::Role::Constant);
  EXPECT_EQ(doc.parameter("Tmax").unit, (Unit{1, -2, 1}));
  // An expression parses over the document's symbols, in its field's name when it cannot.
  EXPECT_FALSE(doc.parse(doc.hamiltonian).is_zero());
  try {
    doc.parse({"rx*nosuch", "/hamiltonian"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("S01/derivation.json: field /hamiltonian: cannot parse", 0), 0u) << e.what();
  }
}

TEST(DerivationDocument, RuntimeEvaluatedParametersHaveTheirRole) {
  const Document doc(derivation_of("S10"));
  ASSERT_FALSE(doc.runtime_evaluated.empty());
  for (const auto& p : doc.parameter_quantities)
    EXPECT_EQ(
        p.role == helios::derivation::Role::RuntimeEvaluated,
        std::find(doc.runtime_evaluated.begin(), doc.runtime_evaluated.end(), p.name) != doc.runtime_evaluated.end())
        << p.name;
}

TEST(DerivationDocument, ReadsEventsInequalitiesAndBodies) {
  for (const char* scenario : {"S04", "S09", "S10", "S11"}) {
    const json d = derivation_of(scenario);
    const Document doc(d);
    EXPECT_EQ(doc.interior_events.size(), d.value("events", json::array()).size()) << scenario;
    EXPECT_EQ(doc.bodies.size(), d.value("bodies", json::array()).size()) << scenario;
    std::size_t inequalities = 0;
    for (const auto& e : d["shooting"]["equations"]) inequalities += e.contains("inequality") ? 1 : 0;
    std::size_t read = 0;
    for (const auto& e : doc.shooting.equations) read += e.inequality ? 1 : 0;
    EXPECT_EQ(read, inequalities) << scenario;
    for (std::size_t k = 0; k < doc.interior_events.size(); ++k) {
      EXPECT_EQ(doc.interior_events[k].id, d["events"][k]["id"].get<std::string>());
      EXPECT_EQ(doc.interior_events[k].state_map.size(), doc.states.size());
      EXPECT_EQ(doc.interior_events[k].time_expression.pointer, "/events/" + std::to_string(k) + "/time/expression");
    }
  }
}

// The message of the input_error reading `d` as a document throws, "" when it reads.
std::string document_error(const json& d) {
  try {
    const Document doc(d, "x.json");
  } catch (const helios::input_error& e) {
    return e.what();
  }
  return "";
}

TEST(DerivationDocument, AMissingOrMistypedFieldNamesItsPointer) {
  json d = derivation_of("S01");
  EXPECT_EQ(document_error(d), "");
  d.erase("hamiltonian");
  EXPECT_EQ(document_error(d), "x.json: field /hamiltonian is missing");
  d = derivation_of("S01");
  d["costate_odes"][2]["rhs"] = 3;
  EXPECT_EQ(document_error(d), "x.json: field /costate_odes/2/rhs must be a string, got 3");
  d = derivation_of("S01");
  d["dynamics"]["state_rhs"] = "rx";
  EXPECT_EQ(document_error(d), "x.json: field /dynamics/state_rhs must be an array, got \"rx\"");
  d = derivation_of("S01");
  d["control_law"]["direction"]["law"][1] = json::array();
  EXPECT_EQ(document_error(d), "x.json: field /control_law/direction/law/1 must be a string, got []");
  d = derivation_of("S01");
  d["times"]["tf_window"] = {0.5, "1"};
  EXPECT_EQ(document_error(d), "x.json: field /times/tf_window/1 must be a number, got \"1\"");
  d = derivation_of("S01");
  d["shooting"]["equations"][0].erase("scale");
  EXPECT_EQ(document_error(d), "x.json: field /shooting/equations/0/scale is missing");
  d = derivation_of("S09");
  d["events"][0]["costate_map"][1]["variable"] = 7;
  EXPECT_EQ(document_error(d), "x.json: field /events/0/costate_map/1/variable must be a string, got 7");
}

// A field only helios-derive writes (a reason, a scale, an initial guess) is optional to read, but
// of its type when given: its error names the field and the value like any other.
TEST(DerivationDocument, AMistypedOptionalFieldOfASharedSectionNamesItsPointer) {
  json d = derivation_of("S01");
  d["control_law"]["direction"]["reason"] = 3;
  EXPECT_EQ(document_error(d), "x.json: field /control_law/direction/reason must be a string, got 3");
  d = derivation_of("S01");
  d["control_law"]["direction"]["dH_da"][0] = false;
  EXPECT_EQ(document_error(d), "x.json: field /control_law/direction/dH_da/0 must be a string, got false");
  d = derivation_of("S01");
  d["shooting"]["variables"][1]["init"] = json::array();
  EXPECT_EQ(document_error(d), "x.json: field /shooting/variables/1/init must be a string, got []");
  d = derivation_of("S01");
  d["control_law"]["throttle"].erase("smoothing");
  d["control_law"]["direction"].erase("reason");
  d["shooting"]["variables"][1].erase("init");
  EXPECT_EQ(document_error(d), "");
}

// The derivation of every scenario: S01..S16, and the sweep P01 at its first cell.
std::vector<std::pair<std::string, json>> every_derivation() {
  std::vector<std::pair<std::string, json>> out;
  for (int k = 1; k <= 16; ++k) {
    const std::string s = std::string(k < 10 ? "S0" : "S") + std::to_string(k);
    out.emplace_back(s, derivation_of(s));
  }
  const std::string path = std::string(HELIOS_SOURCE_DIR) + "/scenarios/P01/problem.txt";
  const std::string text = helios::sweep::cell_problem(helios::io::read_text(path), path, 9700, 350);
  out.emplace_back("P01", helios::pmp::derive_from_spec(helios::spec::parse_problem_text(text, path)));
  return out;
}

// The sections helios-derive and the readers share (sections.hpp) are one model: written by
// helios-derive, read into a Document and written again, each is the same JSON to the byte.
TEST(DerivationSections, WriteReadWriteGivesTheSameJson) {
  namespace sections = helios::derivation::sections;
  for (const auto& [scenario, d] : every_derivation()) {
    const Document doc(d, scenario);
    EXPECT_EQ(sections::to_json(doc.control_law).dump(), d.at("control_law").dump()) << scenario;
    EXPECT_EQ(sections::to_json(doc.initial_values).dump(), d.at("initial_values").dump()) << scenario;
    EXPECT_EQ(sections::to_json(doc.event_value_list).dump(), d.value("event_values", json::array()).dump())
        << scenario;
    EXPECT_EQ(sections::to_json(doc.shooting).dump(), d.at("shooting").dump()) << scenario;
    EXPECT_EQ(sections::to_json(doc.intermediate_list).dump(), d.value("intermediates", json::array()).dump())
        << scenario;
    EXPECT_EQ(sections::to_json(doc.constraints).dump(), d.at("constraints").dump()) << scenario;
    EXPECT_EQ(sections::to_json(doc.interior_events).dump(), d.value("events", json::array()).dump()) << scenario;
  }
}

// The grammar of names.hpp, spelled out once here as the artifacts have it.
TEST(DerivationNames, MakesTheNamesOfTheArtifact) {
  namespace names = helios::derivation::names;
  EXPECT_EQ(names::costate("vx"), "l_vx");
  EXPECT_EQ(names::at_t0("l_m"), "l_m_t0");
  EXPECT_EQ(names::at_tf("rx"), "rx_tf");
  EXPECT_EQ(names::before("rx", "mars"), "rx_mars_m");
  EXPECT_EQ(names::after(names::costate("m"), "mars"), "l_m_mars_p");
  EXPECT_EQ(names::event_time("mars"), "t_mars");
  EXPECT_EQ(names::event_departure_time("mars"), "t_mars_dep");
  EXPECT_EQ(names::event_fraction("mars"), "t_mars_frac");
  EXPECT_EQ(names::fraction("t0"), "t0_frac");
  EXPECT_EQ(names::multiplier("mars_2", 3), "nu_mars_2_3");
  EXPECT_EQ(names::hamiltonian("tf"), "H_tf");
  EXPECT_EQ(names::hamiltonian_before("mars"), "H_mars_m");
  EXPECT_EQ(names::hamiltonian_after("mars"), "H_mars_p");
  EXPECT_EQ(names::constraint_row("arrival", 7), "psi_arrival_7");
  EXPECT_EQ(names::jump_row("mars", "m"), "jump_mars_m");
  EXPECT_EQ(names::time_row("mars"), "time_mars");
  EXPECT_EQ(names::stationarity_row("mars", "delta_mars"), "stationarity_mars_delta_mars");
  EXPECT_EQ(names::transversality_row("m"), "transversality_m");
  EXPECT_EQ(names::transversality_row(names::at_t0("m")), "transversality_m_t0");
  EXPECT_EQ(names::transversality_row("tf"), "transversality_tf");
  EXPECT_EQ(names::target_component(names::departure_label("mars"), "vx"), "mars_dep_vx");
  EXPECT_EQ(names::rate("mars_rx"), "mars_rx_rate");
  EXPECT_EQ(names::initial_value("ceres_rx"), "ceres_rx_0");
  EXPECT_EQ(names::relative("rx", "mars"), "rx_mars_rel");
}

TEST(DerivationNames, ReadsTheNamesBack) {
  namespace names = helios::derivation::names;
  EXPECT_EQ(names::costate_state("l_vx"), "vx");
  EXPECT_EQ(names::costate_state("vx"), "");
  EXPECT_TRUE(names::is_costate("l_"));
  EXPECT_TRUE(names::is_before_or_after("rx_mars_m"));
  EXPECT_TRUE(names::is_before_or_after("l_m_mars_p"));
  EXPECT_FALSE(names::is_before_or_after("_m"));
  EXPECT_FALSE(names::is_before_or_after("rx_tf"));
  EXPECT_TRUE(names::is_multiplier_of("nu_mars_2_3", "mars_2"));
  EXPECT_FALSE(names::is_multiplier_of("nu_mars_2_3", "mars"));  // mars_2's, not mars's
  EXPECT_FALSE(names::is_multiplier_of("nu_mars_", "mars"));
  EXPECT_TRUE(names::is_constraint_row("psi_arrival_1"));
  EXPECT_FALSE(names::is_constraint_row("jump_mars_m"));
  EXPECT_EQ(names::hamiltonian_label("H_mars_m"), "mars_m");
  EXPECT_EQ(names::hamiltonian_label("H_tf"), "tf");
  EXPECT_EQ(names::hamiltonian_label("H_"), "");
  EXPECT_EQ(names::hamiltonian_label("hamiltonian_tf"), "");
}

}  // namespace

#include "helios/derivation/reader.hpp"

#include <gtest/gtest.h>

#include <string>

#include "helios/io/error.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"

namespace {

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

}  // namespace

#include "helios/spec/parse.hpp"

#include <gtest/gtest.h>

#include <string>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;

const std::string kSource = HELIOS_SOURCE_DIR;

std::string s01_text() {
  return helios::io::read_text(kSource + "/scenarios/S01/problem.txt");
}

json parse(const std::string& text) {
  return helios::spec::parse_problem_text(text, "problem.txt");
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const helios::input_error& e) {
    return e.what();
  }
  return "";
}

TEST(Parse, S01ReadsEveryFactInSpecUnits) {
  const json spec = parse(s01_text());
  EXPECT_NO_THROW(helios::io::validate("spec", spec, "spec"));
  EXPECT_EQ(spec["problem"]["id"], "S01");
  EXPECT_TRUE(IsClose(spec["central_body"]["mu_km3_s2"], 1.32712440018e11, 0, 1e-15));
  EXPECT_TRUE(IsClose(spec["spacecraft"]["thrust_N"], 0.5, 0, 1e-15));
  EXPECT_TRUE(IsClose(spec["spacecraft"]["isp_s"], 2000, 0, 1e-15));
  EXPECT_TRUE(IsClose(spec["spacecraft"]["initial_mass_kg"], 1000, 0, 1e-15));
  EXPECT_TRUE(IsClose(spec["time"]["tof_days"], 348.795, 0, 1e-15));
  EXPECT_EQ(spec["objective"]["kind"], "minimum_fuel");
  ASSERT_EQ(spec["constraints"].size(), 2u);
  const json& dep = spec["constraints"][0];
  EXPECT_EQ(dep["kind"], "initial_state");
  EXPECT_TRUE(IsClose(dep["target"]["position_km"][0], -140699693, 0, 1e-15));
  EXPECT_TRUE(IsClose(dep["target"]["velocity_km_s"][2], 4.337725e-4, 0, 1e-15));
  const json& arr = spec["constraints"][1];
  EXPECT_EQ(arr["kind"], "rendezvous");
  EXPECT_EQ(arr["at"], "tf");
  EXPECT_TRUE(IsClose(arr["target"]["velocity_km_s"][2], 9.21486e-2, 0, 1e-15));
}

TEST(Parse, UnitsAreConverted) {
  const std::string text = s01_text();
  const json mn = parse(replaced(text, "0.5 N", "500 mN"));
  EXPECT_TRUE(IsClose(mn["spacecraft"]["thrust_N"], 0.5, 0, 1e-15));
  const json secs = parse(replaced(text, "348.795 days", "30135888 s"));
  EXPECT_TRUE(IsClose(secs["time"]["tof_days"], 348.795, 0, 1e-15));
  const json meters =
      parse(replaced(text, "[9.774596, -28.07828, 4.337725e-4] km/s", "[9774.596, -28078.28, 0.4337725] m/s"));
  EXPECT_TRUE(IsClose(meters["constraints"][0]["target"]["velocity_km_s"][0], 9.774596, 0, 1e-15));
  const json au = parse(replaced(text, "[-172682023, 176959469, 7948912] km", "[1, 0, 0] AU"));
  EXPECT_TRUE(IsClose(au["constraints"][1]["target"]["position_km"][0], 149597870.691, 0, 1e-15));
}

TEST(Parse, CentralBodyWithoutMuUsesKnownValue) {
  const json spec = parse(replaced(s01_text(), " with gravitational parameter 1.32712440018e11 km^3/s^2", ""));
  EXPECT_TRUE(IsClose(spec["central_body"]["mu_km3_s2"], 1.32712440018e11, 0, 1e-15));
}

TEST(Parse, UnusableSentenceIsQuotedWithItsLine) {
  const std::string text = s01_text() + "The spacecraft likes jazz.\n";
  EXPECT_EQ(error_of(text),
            "problem.txt:9: cannot use sentence \"The spacecraft likes jazz\": it matches no form of the controlled "
            "English (see README.md, 'Controlled English')");
}

TEST(Parse, WrongUnitNamesTheUnit) {
  const std::string err = error_of(replaced(s01_text(), "0.5 N", "0.5 kg"));
  EXPECT_NE(err.find("unit 'kg' is not a force unit (use N, mN)"), std::string::npos) << err;
}

TEST(Parse, MissingFactsAndRepeatsAreErrors) {
  EXPECT_EQ(error_of(replaced(s01_text(), "Minimize the fuel consumption.", "")),
            "problem.txt: the problem text never states the objective (add a sentence such as \"Minimize the fuel "
            "consumption.\")");
  const std::string twice = error_of(s01_text() + "The time of flight is 100 days.\n");
  EXPECT_NE(twice.find("the time of flight is given twice"), std::string::npos) << twice;
  const std::string negative = error_of(replaced(s01_text(), "348.795 days", "-3 days"));
  EXPECT_NE(negative.find("time of flight must be positive"), std::string::npos) << negative;
}

TEST(Parse, CommentsAndLineBreaksInsideSentences) {
  std::string text = s01_text();
  text = replaced(text, "a specific impulse of 2000 s and", "a specific impulse of 2000 s\n# a comment line\nand");
  EXPECT_TRUE(IsClose(parse(text)["spacecraft"]["isp_s"], 2000, 0, 1e-15));
}

}  // namespace

namespace {

json parse_scenario(const std::string& id) {
  const std::string path = kSource + "/scenarios/" + id + "/problem.txt";
  return helios::spec::parse_problem_text(helios::io::read_text(path), path);
}

TEST(Parse, J2CentralBodyAndPerturbation) {
  const json s = parse_scenario("S05");
  EXPECT_EQ(s["central_body"]["j2"], 1.08262668e-3);
  EXPECT_EQ(s["central_body"]["radius_km"], 6378.137);
  EXPECT_EQ(s["dynamics"]["perturbations"], json::parse(R"([{"kind": "j2"}])"));
  // J2 without the body's coefficient cannot be formulated.
  const std::string text = replaced(helios::io::read_text(kSource + "/scenarios/S05/problem.txt"),
                                    " and J2 coefficient 1.08262668e-3", "");
  EXPECT_NE(error_of(text).find("needs the central body's J2 coefficient"), std::string::npos) << error_of(text);
}

TEST(Parse, CoastingTargetKeepsItsInitialState) {
  const json target = parse_scenario("S06")["constraints"][1]["target"];
  EXPECT_EQ(target["kind"], "coasting");
  EXPECT_EQ(target["position_km"][2], 1462.832958);
}

TEST(Parse, SolarSailMinimumTimeWithAWindow) {
  const json s = parse_scenario("S11");
  EXPECT_EQ(s["dynamics"]["propulsion"], "solar_sail");
  EXPECT_EQ(s["spacecraft"]["sail_characteristic_acceleration_mm_s2"], 1.0);
  EXPECT_TRUE(IsClose(s["spacecraft"]["sail_reference_distance_AU"].get<double>(), 1.0, 1e-15, 0));
  EXPECT_EQ(s["objective"]["kind"], "minimum_time");
  EXPECT_EQ(s["time"]["final_time"], "free");
  EXPECT_EQ(s["time"]["tof_min_days"], 100.0);
  EXPECT_EQ(s["time"]["tof_max_days"], 1000.0);
  const json at_most = parse(replaced(helios::io::read_text(kSource + "/scenarios/S11/problem.txt"),
                                      "free, between 100 days and 1000 days", "free, at most 2 years"));
  EXPECT_EQ(at_most["time"]["tof_min_days"], 0.0);
  EXPECT_EQ(at_most["time"]["tof_max_days"], 730.5);  // Julian years
  const std::string sail_with_engine =
      helios::io::read_text(kSource + "/scenarios/S11/problem.txt") + "The spacecraft has a maximum thrust of 1 N.\n";
  EXPECT_NE(error_of(sail_with_engine).find("solar sail"), std::string::npos) << error_of(sail_with_engine);
}

TEST(Parse, UserAccelerationIsCheckedAtParseTime) {
  const json s = parse_scenario("S12");
  const json& a = s["dynamics"]["perturbations"][0];
  EXPECT_EQ(a["name"], "srp");
  EXPECT_EQ(a["unit"], "m/s^2");
  EXPECT_EQ(a["components"][0], "1.6416e-4/m*(149597870.691/r)^2*x/r");
  const std::string text = helios::io::read_text(kSource + "/scenarios/S12/problem.txt");
  const std::string unknown = replaced(text, "^2*x/r,", "^2*x/rho,");
  EXPECT_NE(error_of(unknown).find("rho"), std::string::npos) << error_of(unknown);
  const std::string two = replaced(text, ", 1.6416e-4/m*(149597870.691/r)^2*z/r]", "]");
  EXPECT_NE(error_of(two).find("three components"), std::string::npos) << error_of(two);
  const std::string unit = replaced(text, "z/r] m/s^2", "z/r] N");
  EXPECT_NE(error_of(unit).find("not an acceleration unit"), std::string::npos) << error_of(unit);
}

}  // namespace

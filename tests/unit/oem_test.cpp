#include "helios/oem/oem.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "helios/astro/constants.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"

namespace {

using helios::io::json;
using helios::oem::oem_epoch;
using helios::oem::oem_from_run;
using helios::oem::oem_segment_starts;
using helios::oem::read_trajectory;
using helios::oem::TrajectorySample;

const std::string kFixtures = std::string(HELIOS_SOURCE_DIR) + "/tests/fixtures/oem";

// ---- epochs ----------------------------------------------------------------------------------

TEST(OemEpoch, Mjd2000ZeroIsMidnightAndJ2000IsNoon) {
  // MJD2000 = MJD - 51544 (helios::astro::MJD_MINUS_MJD2000): day 0 starts at 2000-01-01T00:00, and
  // J2000.0 (JD 2451545.0) is MJD2000 0.5.
  EXPECT_EQ(oem_epoch(0.0), "2000-01-01T00:00:00.000000");
  EXPECT_EQ(oem_epoch(helios::astro::JD_J2000 - helios::astro::JD_OF_MJD2000), "2000-01-01T12:00:00.000000");
  EXPECT_EQ(oem_epoch(helios::oem::kOemDefaultEpochMjd2000), "2000-01-01T12:00:00.000000");
}

TEST(OemEpoch, HalfDaysAndTheDayBefore) {
  EXPECT_EQ(oem_epoch(1.0), "2000-01-02T00:00:00.000000");
  EXPECT_EQ(oem_epoch(-0.5), "1999-12-31T12:00:00.000000");
  EXPECT_EQ(oem_epoch(-1.0), "1999-12-31T00:00:00.000000");
}

TEST(OemEpoch, LeapDays) {
  EXPECT_EQ(oem_epoch(59.0), "2000-02-29T00:00:00.000000");  // 2000 is a leap year (divisible by 400)
  EXPECT_EQ(oem_epoch(60.0), "2000-03-01T00:00:00.000000");
  EXPECT_EQ(oem_epoch(8825.0), "2024-02-29T00:00:00.000000");
  EXPECT_EQ(oem_epoch(36584.0), "2100-03-01T00:00:00.000000");  // 2100 is not: 28 February, then 1 March
  EXPECT_EQ(oem_epoch(36583.0), "2100-02-28T00:00:00.000000");
}

TEST(OemEpoch, FractionalSecondsRoundToTheMicrosecond) {
  EXPECT_EQ(oem_epoch(1.25 / 86400.0), "2000-01-01T00:00:01.250000");
  EXPECT_EQ(oem_epoch(1.0 + 3661.000001 / 86400.0), "2000-01-02T01:01:01.000001");
  EXPECT_EQ(oem_epoch(1.0 - 0.4e-6 / 86400.0), "2000-01-02T00:00:00.000000");  // rounds up across midnight
  EXPECT_EQ(oem_epoch(1.0 - 0.6e-6 / 86400.0), "2000-01-01T23:59:59.999999");
  // S07's departure (solution.json departure_mjd2000).
  EXPECT_EQ(oem_epoch(10320.903927704128), "2028-04-03T21:41:39.353637");
}

TEST(OemEpoch, OutsideYears1To9999IsAnError) {
  EXPECT_THROW(oem_epoch(3.0e6), std::invalid_argument);
  EXPECT_THROW(oem_epoch(-8.0e5), std::invalid_argument);
  EXPECT_THROW(oem_epoch(std::nan("")), std::invalid_argument);
}

// ---- trajectory.csv and segments -------------------------------------------------------------

std::vector<TrajectorySample> samples_at(const std::vector<double>& times) {
  std::ostringstream csv;
  csv << "t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s,m_kg,u\n";
  for (const double t : times) csv << t << ",1,2,3,4,5,6,100,1\n";
  return read_trajectory(csv.str(), "traj.csv");
}

TEST(OemSegments, NoEventsIsOneSegment) {
  EXPECT_EQ(oem_segment_starts(samples_at({0, 1, 2, 3}), {}, "traj.csv"), (std::vector<std::size_t>{0}));
}

TEST(OemSegments, ARepeatedTimeStartsASegment) {
  EXPECT_EQ(oem_segment_starts(samples_at({0, 1, 2, 2, 3, 4, 4, 5}), {0, 0}, "traj.csv"),
            (std::vector<std::size_t>{0, 3, 6}));
}

TEST(OemSegments, AStepOfTheStaysLengthStartsASegment) {
  // A 30-day stay after t = 2, then a flyby (repeated time) at 33.
  EXPECT_EQ(oem_segment_starts(samples_at({0, 1, 2, 32, 33, 33, 34}), {30, 0}, "traj.csv"),
            (std::vector<std::size_t>{0, 3, 5}));
}

TEST(OemSegments, EventsThatDoNotMatchTheSpecAreErrors) {
  try {
    oem_segment_starts(samples_at({0, 1, 1, 2}), {}, "traj.csv");
    FAIL() << "a repeated time without an event";
  } catch (const helios::input_error& e) {
    EXPECT_NE(std::string(e.what()).find("traj.csv:4: field t_days"), std::string::npos) << e.what();
  }
  EXPECT_THROW(oem_segment_starts(samples_at({0, 1, 2}), {0}, "traj.csv"), helios::input_error);      // event missing
  EXPECT_THROW(oem_segment_starts(samples_at({0, 1, 1, 2}), {30}, "traj.csv"), helios::input_error);  // stay due
  EXPECT_THROW(oem_segment_starts(samples_at({0, 2, 1}), {}, "traj.csv"), helios::input_error);       // time goes back
}

TEST(OemTrajectory, MalformedCsvNamesFileLineAndField) {
  const auto message = [](const std::string& csv) {
    try {
      read_trajectory(csv, "traj.csv");
    } catch (const helios::input_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s\n0,1,2,3,4,x,6\n"),
            "traj.csv:2: field vy_km_s: 'x' is not a finite number");
  EXPECT_EQ(message("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s\n0,1,2,3,4,5,nan\n"),
            "traj.csv:2: field vz_km_s: 'nan' is not a finite number");
  EXPECT_NE(message("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s\n0,1,2,3,4,5\n").find("no column vz_km_s"),
            std::string::npos);
  EXPECT_NE(message("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s\n0,1,2\n").find("traj.csv:2: 3 fields"),
            std::string::npos);
  EXPECT_NE(message("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s\n").find("no samples"), std::string::npos);
}

TEST(OemTrajectory, CrlfLineEndsAreRead) {
  const auto samples =
      read_trajectory("t_days,rx_km,ry_km,rz_km,vx_km_s,vy_km_s,vz_km_s,u\r\n0,1,2,3,4,5,6,1\r\n", "traj.csv");
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].throttle, 1.0);
  EXPECT_LT(samples[0].mass_kg, 0);  // no m_kg column
}

// ---- the whole OEM of the fixture run (S08's spec, a trimmed solution, 17 of its samples) ------

struct Fixture {
  json spec = helios::io::read_artifact("spec", kFixtures + "/spec.json");
  json solution = helios::io::read_artifact("solution", kFixtures + "/solution.json");
  std::string csv = helios::io::read_text(kFixtures + "/trajectory.csv");
};

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(OemRun, FixtureHasFourSegmentsInTheEclipticFrame) {
  const Fixture f;
  const auto oem = oem_from_run(f.spec, f.solution, f.csv);
  ASSERT_TRUE(oem);
  EXPECT_EQ(oem->rfind("CCSDS_OEM_VERS = 2.0\n", 0), 0u);
  EXPECT_EQ(count(*oem, "META_START\n"), 4u);  // stay at Nikko, flyby of Ast_8648, stay at Tengstrom
  EXPECT_EQ(count(*oem, "REF_FRAME = ECLIPJ2000\n"), 4u);
  EXPECT_EQ(count(*oem, "CENTER_NAME = SUN\n"), 4u);
  EXPECT_EQ(count(*oem, "TIME_SYSTEM = TDB\n"), 4u);
  EXPECT_NE(oem->find("START_TIME = 2028-03-27T14:24:00.000000\n"), std::string::npos);  // MJD2000 10313.6
  EXPECT_NE(oem->find("COMMENT Mass 1867.760280 kg at START_TIME"), std::string::npos);
  EXPECT_NE(oem->find("lander of 50 kg left"), std::string::npos);
  EXPECT_NE(oem->find("CREATION_DATE = 2000-01-01T00:00:00\n"), std::string::npos);
  // The same inputs give the same bytes.
  EXPECT_EQ(*oem, *oem_from_run(f.spec, f.solution, f.csv));
}

TEST(OemRun, WithoutAnEpochTheDefaultIsUsedAndSaid) {
  Fixture f;
  f.spec["time"].erase("epoch_mjd2000");
  const auto oem = oem_from_run(f.spec, f.solution, f.csv);
  ASSERT_TRUE(oem);
  EXPECT_NE(oem->find("START_TIME = 2000-01-01T12:00:00.000000\n"), std::string::npos);
  EXPECT_NE(oem->find("COMMENT The problem states no calendar epoch"), std::string::npos);
}

TEST(OemRun, EarthCentredIsEme2000AndOtherCentresAreRefused) {
  Fixture f;
  f.spec["central_body"]["name"] = "Earth";
  const auto oem = oem_from_run(f.spec, f.solution, f.csv);
  ASSERT_TRUE(oem);
  EXPECT_NE(oem->find("CENTER_NAME = EARTH\nREF_FRAME = EME2000\n"), std::string::npos);
  f.spec["central_body"]["name"] = "Mars";
  try {
    oem_from_run(f.spec, f.solution, f.csv, {"s.json", "sol.json", "t.csv"});
    FAIL() << "no frame for Mars";
  } catch (const helios::input_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("s.json: field /central_body/name: ", 0), 0u) << e.what();
  }
}

TEST(OemRun, NotConvergedGivesNothingAndAnotherProblemIsAnError) {
  Fixture f;
  f.solution["status"] = "not_converged";
  EXPECT_FALSE(oem_from_run(f.spec, f.solution, f.csv));
  f.solution["status"] = "converged";
  f.solution["problem"]["id"] = "S01";
  EXPECT_THROW(oem_from_run(f.spec, f.solution, f.csv), helios::input_error);
}

}  // namespace

#include "helios/score/sweep.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"

namespace {

namespace fs = std::filesystem;
using helios::input_error;
using helios::io::json;
using namespace helios::score;

const json kSweep = json::parse(R"({
  "departure_mjd2000": {"start": 9700, "stop": 9780, "step": 40},
  "tof_days": {"start": 300, "stop": 400, "count": 3},
  "plot": "propellant_kg",
  "bench": {"departure_mjd2000": {"values": [1, 2.5]}, "tof_days": {"start": 0.1, "stop": 0.3, "step": 0.1}}
})");

TEST(SweepGrid, RangesStepsCountsAndValues) {
  const SweepGrid g = read_sweep(kSweep, "sweep.json");
  EXPECT_EQ(g.departures_mjd2000, (std::vector<double>{9700, 9740, 9780}));
  EXPECT_EQ(g.tofs_days, (std::vector<double>{300, 350, 400}));
  const SweepGrid b = read_sweep(kSweep, "sweep.json", "bench");
  EXPECT_EQ(b.departures_mjd2000, (std::vector<double>{1, 2.5}));
  ASSERT_EQ(b.tofs_days.size(), 3u);
  EXPECT_EQ(cell_name(2.5, b.tofs_days[2]), "d2.5_t0.3");
}

TEST(SweepGrid, BadInputNamesTheField) {
  json j = kSweep;
  j["tof_days"]["count"] = 0;
  try {
    read_sweep(j, "P01/sweep.json");
    FAIL() << "count 0 accepted";
  } catch (const input_error& e) {
    EXPECT_NE(std::string(e.what()).find("P01/sweep.json: field /tof_days/count"), std::string::npos) << e.what();
  }
  j = kSweep;
  j["departure_mjd2000"]["step"] = -1;
  EXPECT_THROW(read_sweep(j, "s"), input_error);
  j = kSweep;
  j["plot"] = "delta_v";
  EXPECT_THROW(read_sweep(j, "s"), input_error);
  j = kSweep;
  j["tofs"] = 1;
  EXPECT_THROW(read_sweep(j, "s"), input_error);
  EXPECT_THROW(read_sweep(kSweep, "s", "fine"), input_error);
  j = kSweep;
  j["tof_days"] = {{"values", {300, 300}}};
  EXPECT_THROW(read_sweep(j, "s"), input_error);
}

TEST(SweepCells, ChainsAlongTofColdFirst) {
  const auto cells = sweep_cells(read_sweep(kSweep, "s"));
  ASSERT_EQ(cells.size(), 9u);
  EXPECT_EQ(cells[0].name, "d9700_t300");
  EXPECT_EQ(cells[0].warm_from, "");
  EXPECT_EQ(cells[1].name, "d9700_t350");
  EXPECT_EQ(cells[1].warm_from, "d9700_t300");
  EXPECT_EQ(cells[3].name, "d9740_t300");
  EXPECT_EQ(cells[3].warm_from, "");
  EXPECT_EQ(cells[8].warm_from, "d9780_t350");
}

TEST(SweepCells, ProblemTextsAndFragment) {
  EXPECT_EQ(cell_problem("at MJD2000 @DEPARTURE_MJD2000@, @TOF_DAYS@ days", "t", 9700.5, 300),
            "at MJD2000 9700.5, 300 days");
  EXPECT_THROW(cell_problem("no placeholders", "t", 1, 2), input_error);
  const fs::path dir = fs::temp_directory_path() / ("helios-sweep-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const SweepGrid g = read_sweep(kSweep, "s");
  const std::string tmpl = "@DEPARTURE_MJD2000@ @TOF_DAYS@\n";
  const std::string mk = write_sweep_cells(g, tmpl, "t", dir.string());
  EXPECT_EQ(helios::io::read_text((dir / "d9740_t350" / "problem.txt").string()), "9740 350\n");
  EXPECT_NE(mk.find("SWEEP_WARM_d9740_t350 := d9740_t300\n"), std::string::npos) << mk;
  EXPECT_NE(mk.find((dir / "d9740_t350/solution.json").string() + ": " + (dir / "d9740_t300/solution.json").string()),
            std::string::npos);
  // An unchanged text is not rewritten (make would redo a finished cell).
  const auto before = fs::last_write_time(dir / "d9700_t300" / "problem.txt");
  write_sweep_cells(g, tmpl, "t", dir.string());
  EXPECT_EQ(fs::last_write_time(dir / "d9700_t300" / "problem.txt"), before);
  // sweep.csv: a converged cell, an unconverged one, the others missing.
  helios::io::write_text_atomic(
      (dir / "d9700_t300" / "solution.json").string(),
      R"({"status": "converged", "propellant_kg": 123.5, "max_residual": 1e-12, "start": "cold"})");
  helios::io::write_text_atomic((dir / "d9700_t350" / "solution.json").string(),
                                R"({"status": "not_converged", "start": "cold-after-warm-failed"})");
  const std::string csv = sweep_csv(g, sweep_rows(g, dir.string()));
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "departure_mjd2000,tof_days,cell,status,propellant_kg,max_residual,start");
  EXPECT_NE(csv.find("\n9700,300,d9700_t300,converged,123.5,1.000e-12,cold\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n9700,350,d9700_t350,not_converged,,,cold-after-warm-failed\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n9780,400,d9780_t400,missing,,,\n"), std::string::npos) << csv;
  // A converged solution without the plotted key is refused.
  helios::io::write_text_atomic((dir / "d9700_t300" / "solution.json").string(), R"({"status": "converged"})");
  EXPECT_THROW(sweep_rows(g, dir.string()), input_error);
  fs::remove_all(dir);
}

}  // namespace

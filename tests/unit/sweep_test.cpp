#include "helios/sweep/sweep.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"

namespace {

namespace fs = std::filesystem;
using helios::input_error;
using helios::io::json;
using namespace helios::sweep;

const json kSweep = json::parse(R"({
  "departure_mjd2000": {"start": 9700, "stop": 9780, "step": 40},
  "tof_days": {"start": 300, "stop": 400, "count": 3},
  "plot": "propellant_kg",
  "boundary": false,
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

// A sweep's folder under the test's temporary directory, removed at the end.
struct SweepDir {
  fs::path path = fs::temp_directory_path() / ("helios-sweep-test-" + std::to_string(::getpid()) + "-" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  SweepDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~SweepDir() { fs::remove_all(path); }
  void write(const std::string& file, const std::string& text) const {
    fs::create_directories((path / file).parent_path());
    helios::io::write_text_atomic((path / file).string(), text);
  }
};

const std::string kTemplate =
    "# a comment. With a sentence end.\n"
    "Problem P99: Earth to Mars.\n"
    "The central body is the Sun with gravitational parameter 1.32712440018e11 km^3/s^2.\n"
    "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.\n"
    "The spacecraft departs at MJD2000 @DEPARTURE_MJD2000@ from Earth. The time of flight is @TOF_DAYS@ days.\n"
    "At the final time the spacecraft rendezvouses with Mars.\n"
    "Minimize the fuel consumption.\n";

// A solution.json of schemas/solution.schema.json with `status` and the keys of `extra` (a
// converged one flies `tof` days from `departure`).
std::string solution(const std::string& status, json extra = json::object()) {
  json s = {{"schema", "helios/solution"},
            {"schema_version", 1},
            {"producer", {{"tool", "helios-solve"}, {"version", "0"}, {"backend", "builtin"}}},
            {"problem", {{"id", "P99"}}},
            {"status", status},
            {"compile", {{"ok", true}, {"cached", true}, {"source_sha256", "0"}, {"command", "g++"}}},
            {"seed", 1},
            {"iterations", 0},
            {"function_evaluations", 0},
            {"timings", {{"compile_s", 0}, {"run_s", 0}, {"total_s", 0}}}};
  s.update(extra);
  return s.dump();
}
std::string converged(double departure, double tof, json extra = json::object()) {
  json s = {{"departure_mjd2000", departure}, {"tof_days", tof}, {"max_residual", 0}, {"x", json::array()},
            {"residuals", json::array()},     {"epsilon", 0}};
  s.update(extra);
  return solution("converged", s);
}
// A search record of `starts` starts and `extremals` extremals.
json search(int starts, int extremals, bool saturated) {
  json list = json::array();
  for (int k = 0; k < extremals; ++k)
    list.push_back({{"id", k},
                    {"objective", 1},
                    {"revolutions", 1},
                    {"switches", 0},
                    {"reached", 1},
                    {"first_start", 1},
                    {"from", "start"},
                    {"max_residual", 0},
                    {"polished", false},
                    {"method", "single"}});
  return {{"method", "seeded"},     {"threads", 1},
          {"starts", starts},       {"converged_at_eps_start", 1},
          {"continued", 1},         {"converged_at_eps_0", 1},
          {"seconds", 0},           {"cut_by_time", false},
          {"saturated", saturated}, {"extremals_at_eps_start", json::array()},
          {"extremals", list}};
}

TEST(SweepCells, ProblemTextsAndFragment) {
  EXPECT_EQ(cell_problem("at MJD2000 @DEPARTURE_MJD2000@, @TOF_DAYS@ days", "t", 9700.5, 300),
            "at MJD2000 9700.5, 300 days");
  EXPECT_THROW(cell_problem("no placeholders", "t", 1, 2), input_error);
  const fs::path dir = fs::temp_directory_path() / ("helios-sweep-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const SweepGrid g = read_sweep(kSweep, "s");
  const std::string tmpl = kTemplate;
  const std::string mk = write_sweep_cells(g, tmpl, "t", dir.string());
  EXPECT_EQ(helios::io::read_text((dir / "d9740_t350" / "problem.txt").string()),
            cell_problem(kTemplate, "t", 9740, 350));
  EXPECT_NE(cell_problem(kTemplate, "t", 9740, 350).find("MJD2000 9740 from Earth. The time of flight is 350 days."),
            std::string::npos);
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
      converged(9700, 300, {{"propellant_kg", 123.5}, {"max_residual", 1e-12}, {"start", "cold"}}));
  helios::io::write_text_atomic((dir / "d9700_t350" / "solution.json").string(),
                                solution("not_converged", {{"start", "cold-after-warm-failed"}}));
  const std::string csv = sweep_csv(g, sweep_rows(g, dir.string()));
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "departure_mjd2000,tof_days,cell,status,propellant_kg,max_residual,start,answer_from,extremals_compared,"
            "t_min_days,boundary_saturated");
  EXPECT_NE(csv.find("\n9700,300,d9700_t300,converged,123.5,1.000e-12,cold,own,1,,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n9700,350,d9700_t350,not_converged,,,cold-after-warm-failed,,,,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n9780,400,d9780_t400,missing,,,,,,,\n"), std::string::npos) << csv;
  // A converged solution without the plotted key is refused.
  helios::io::write_text_atomic((dir / "d9700_t300" / "solution.json").string(), converged(9700, 300));
  EXPECT_THROW(sweep_rows(g, dir.string()), input_error);
  fs::remove_all(dir);
}

// Issue 46: a cell whose text states another epoch or time of flight than its grid values (a
// placeholder read in weeks, glued to a digit, only in a comment, in a bound) flies another problem
// than its label: the sweep is refused before any cell is written, naming the cell and the values.
TEST(SweepCells, ACellThatStatesAnotherProblemThanItsLabelIsRefused) {
  const SweepDir dir;
  const SweepGrid g = read_sweep(kSweep, "s");
  const auto with = [](const std::string& from, const std::string& to) {
    std::string t = kTemplate;
    return t.replace(t.find(from), from.size(), to);
  };
  const std::string tof = "The time of flight is @TOF_DAYS@ days.";
  for (const auto& [text, stated] : std::vector<std::pair<std::string, std::string>>{
           {with(tof, "The time of flight is @TOF_DAYS@ weeks."), "time of flight of 2100 d"},
           {with(tof, "The time of flight is 1@TOF_DAYS@ days."), "time of flight of 1300 d"},
           {with(tof, "The time of flight is 350 days.") + "# @TOF_DAYS@\n", "time of flight of 350 d"},
           {with(tof, "The time of flight is free, between @TOF_DAYS@ days and 500 days."), "free time of flight"},
           {with("MJD2000 @DEPARTURE_MJD2000@", "MJD2000 1@DEPARTURE_MJD2000@"), "departure MJD2000 19700"}}) {
    try {
      write_sweep_cells(g, text, "P99/problem.txt", dir.path.string());
      ADD_FAILURE() << text << " accepted";
    } catch (const input_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("P99/problem.txt: the sweep's cell d9700_t300 states"), std::string::npos) << what;
      EXPECT_NE(what.find(stated), std::string::npos) << what;
      EXPECT_NE(what.find("not its grid values, departure MJD2000 9700 and 300 d"), std::string::npos) << what;
    }
    EXPECT_TRUE(fs::is_empty(dir.path)) << text;
  }
}

// --sweep writes a row only for a solution of its cell's problem: schema-valid, and a converged one
// at the cell's departure epoch and time of flight.
TEST(SweepRows, ASolutionOfAnotherProblemIsRefused) {
  const SweepDir dir;
  const SweepGrid g = read_sweep(kSweep, "s");
  write_sweep_cells(g, kTemplate, "t", dir.path.string());
  dir.write("d9700_t300/solution.json", converged(9700, 300, {{"propellant_kg", 1}}));
  EXPECT_EQ(sweep_rows(g, dir.path.string())[0].status, "converged");
  for (const auto& [text, why] : std::vector<std::pair<std::string, std::string>>{
           {converged(9700, 2100, {{"propellant_kg", 1}}), "time of flight of 2100 d"},
           {converged(19700, 300, {{"propellant_kg", 1}}), "departure MJD2000 19700"},
           {solution("dancing"), "solution schema violation"},
           {R"({"status": "converged", "propellant_kg": 1})", "field /schema is missing"}}) {
    dir.write("d9700_t300/solution.json", text);
    try {
      sweep_rows(g, dir.path.string());
      ADD_FAILURE() << text << " accepted";
    } catch (const input_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("d9700_t300/solution.json"), std::string::npos) << what;
      EXPECT_NE(what.find(why), std::string::npos) << what;
    }
  }
}

TEST(SweepBoundary, WindowFromTheGridOrStated) {
  json j = kSweep;
  j.erase("boundary");
  const SweepGrid g = read_sweep(j, "s");
  EXPECT_TRUE(g.boundary);
  EXPECT_EQ(g.boundary_tof_min_days, 75);
  EXPECT_EQ(g.boundary_tof_max_days, 800);
  j["boundary"] = {{"tof_min_days", 50}, {"tof_max_days", 700}};
  EXPECT_EQ(read_sweep(j, "s").boundary_tof_max_days, 700);
  EXPECT_FALSE(read_sweep(kSweep, "s").boundary);
  for (const json& bad : {json{{"tof_min_days", 301}}, json{{"tof_max_days", 399}}, json{{"tof_min_days", 0}},
                          json{{"tmin", 1}}, json(true), json("no")}) {
    j["boundary"] = bad;
    try {
      read_sweep(j, "P01/sweep.json");
      ADD_FAILURE() << bad.dump() << " accepted";
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find("P01/sweep.json: field /boundary"), std::string::npos) << e.what();
    }
  }
}

TEST(SweepBoundary, TheTemplatesProblemInMinimumTime) {
  json j = kSweep;
  j["boundary"] = {{"tof_min_days", 50}, {"tof_max_days", 700}};
  const SweepGrid g = read_sweep(j, "s");
  const std::string text = boundary_problem(g, kTemplate, "P99/problem.txt", 9740);
  EXPECT_EQ(text,
            "# a comment. With a sentence end.\n"
            "Problem P99: Earth to Mars.\n"
            "The central body is the Sun with gravitational parameter 1.32712440018e11 km^3/s^2.\n"
            "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 "
            "kg.\n"
            "The spacecraft departs at MJD2000 9740 from Earth. The time of flight is free, between 50 days and 700 "
            "days.\n"
            "At the final time the spacecraft rendezvouses with Mars.\n"
            "Minimize the time of flight.\n");
  EXPECT_EQ(boundary_name(9740), "b9740");
  // No objective sentence, two of them: refused, naming the template.
  for (const std::string& bad :
       {std::string(kTemplate).replace(kTemplate.find("Minimize the fuel consumption."), 30, ""),
        kTemplate + "Minimize the propellant mass.\n"}) {
    try {
      boundary_problem(g, bad, "P99/problem.txt", 9740);
      ADD_FAILURE() << bad << " accepted";
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find("P99/problem.txt: the sweep's boundary"), std::string::npos) << e.what();
    }
  }
  // An objective already minimum time: its cells minimize a fixed time of flight, which the parser
  // refuses at the template's objective sentence.
  try {
    boundary_problem(g,
                     std::string(kTemplate).replace(kTemplate.find("Minimize the fuel consumption."), 30,
                                                    "Minimize the time of flight."),
                     "P99/problem.txt", 9740);
    ADD_FAILURE() << "a minimum-time template accepted";
  } catch (const input_error& e) {
    EXPECT_NE(std::string(e.what()).find("P99/problem.txt:7: cannot use sentence \"Minimize the time of flight\": the "
                                         "time of flight is fixed"),
              std::string::npos)
        << e.what();
  }
  // The boundary's settings: the sweep's without its search budget.
  EXPECT_EQ(boundary_settings(json{{"seed", 1}, {"search_starts", 16}, {"max_attempts", 64}}), json({{"seed", 1}}));
}

TEST(SweepBoundary, CellsBelowItAreInfeasibleAndNotSolved) {
  const SweepDir dir;
  json j = kSweep;
  j["boundary"] = {{"tof_min_days", 50}, {"tof_max_days", 700}};
  const SweepGrid g = read_sweep(j, "s");
  const std::string fragment = write_sweep_boundary(g, kTemplate, "t", json{{"seed", 1}}, dir.path.string());
  EXPECT_NE(fragment.find("SWEEP_BOUNDARY := b9700 b9740 b9780\n"), std::string::npos) << fragment;
  EXPECT_TRUE(fs::exists(dir.path / "b9740" / "settings.json"));
  // While a boundary is missing, no cell.
  EXPECT_TRUE(feasible_cells(g, dir.path.string()).empty());
  EXPECT_EQ(write_sweep_cells(g, kTemplate, "t", dir.path.string()).find("SWEEP_CELLS :=\n") != std::string::npos,
            true);
  // t_min 320 d at 9700: its 300-day cell is infeasible, the row starts cold at 350; 9740 failed
  // (every cell solved); 9780's t_min is a grid value: that cell is feasible.
  dir.write("b9700/solution.json", converged(9700, 320, {{"search", search(128, 2, true)}}));
  dir.write("b9740/solution.json", solution("not_converged"));
  dir.write("b9780/solution.json", converged(9780, 300.0000000001));
  const auto cells = feasible_cells(g, dir.path.string());
  ASSERT_EQ(cells.size(), 8u);
  EXPECT_EQ(cells[0].name, "d9700_t350");
  EXPECT_EQ(cells[0].warm_from, "");
  EXPECT_EQ(cells[1].warm_from, "d9700_t350");
  EXPECT_EQ(cells[2].name, "d9740_t300");
  EXPECT_EQ(cells[5].name, "d9780_t300");
  write_sweep_cells(g, kTemplate, "t", dir.path.string());
  EXPECT_FALSE(fs::exists(dir.path / "d9700_t300"));
  const auto rows = sweep_rows(g, dir.path.string());
  EXPECT_EQ(rows[0].status, "infeasible");
  EXPECT_EQ(rows[0].boundary.t_min_days, 320);
  EXPECT_TRUE(rows[0].boundary.saturated);
  EXPECT_EQ(rows[0].boundary.extremals, 2);
  EXPECT_EQ(rows[1].status, "missing");
  const std::string csv = sweep_csv(g, rows);
  EXPECT_NE(csv.find("\n9700,300,d9700_t300,infeasible,,,,,,320,true\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n9740,300,d9740_t300,missing,,,,,,,\n"), std::string::npos) << csv;
}

// The cross-check's rounds with a stand-in solver: a try's objective is its neighbour answer's
// plus 10 kg (continuation loses a little), so an answer spreads only to worse or missing cells.
TEST(SweepCrosscheck, ImprovesUntilNoCellDoesAndResumes) {
  const SweepDir dir;
  const SweepGrid g = read_sweep(json::parse(R"({"departure_mjd2000": {"values": [1]},
      "tof_days": {"values": [10, 20, 30]}, "boundary": false})"),
                                 "s");
  for (const char* cell : {"d1_t10", "d1_t20", "d1_t30"}) dir.write(std::string(cell) + "/shoot.cpp", "");
  dir.write("d1_t10/solution.json", converged(1, 10, {{"propellant_kg", 100}}));
  dir.write("d1_t20/solution.json", converged(1, 20, {{"propellant_kg", 200}}));
  dir.write("d1_t30/solution.json", solution("not_converged"));
  // It flies its own cell (the shoot.cpp's folder d1_t<tof>) with its neighbour's answer's propellant
  // plus 10 kg.
  dir.write("answer.json",
            converged(1, 0,
                      {{"tof_days", "TOF"},
                       {"propellant_kg", "PROPELLANT"},
                       {"warm_start", {{"from", "FROM"}, {"neighbour_status", "converged"}, {"used", true}}}}));
  dir.write("solver.sh",
            "#!/bin/sh\n"
            "cell=$(basename \"$(dirname \"$1\")\")\n"
            "while [ $# -gt 0 ]; do case $1 in --warm-start) from=$2; shift;; -o) out=$2; shift;; esac; shift; done\n"
            "m=$(sed -n 's/.*\"propellant_kg\": *\\([0-9.]*\\).*/\\1/p' \"$from\")\n"
            "sed -e \"s/\\\"TOF\\\"/${cell#*_t}/\" -e \"s/\\\"PROPELLANT\\\"/$((m + 10))/\" -e \"s|FROM|$from|\" \\\n"
            "  \"$(dirname \"$0\")/answer.json\" >\"$out\"\n");
  fs::permissions(dir.path / "solver.sh", fs::perms::owner_all);
  CrosscheckOptions o;
  o.solver = (dir.path / "solver.sh").string();
  o.jobs = 2;
  const json first = crosscheck(g, dir.path.string(), o);
  EXPECT_EQ(first.at("rounds"), 3) << first.dump(1);
  EXPECT_EQ(first.at("runs"), 7);
  EXPECT_EQ(first.at("improved"), json({"d1_t20", "d1_t30"}));
  const json& cells = first.at("cells");
  EXPECT_EQ(cells.at("d1_t10").at("answer_from"), "own");
  EXPECT_EQ(cells.at("d1_t10").at("propellant_kg"), 100);
  EXPECT_EQ(cells.at("d1_t20").at("answer_from"), "d1_t10");
  EXPECT_EQ(cells.at("d1_t20").at("propellant_kg"), 110);
  EXPECT_EQ(cells.at("d1_t20").at("answer"), "d1_t20/crosscheck/r1_from_d1_t10/solution.json");
  EXPECT_EQ(cells.at("d1_t30").at("answer_from"), "d1_t20");
  EXPECT_EQ(cells.at("d1_t30").at("propellant_kg"), 120);
  // d1_t20 compared its own 200 kg, 110 from d1_t10, and 220 and 130 from d1_t30's two answers.
  EXPECT_EQ(cells.at("d1_t20").at("extremals_compared"), 4);
  EXPECT_EQ(cells.at("d1_t20").at("tried").size(), 3u);
  const auto rows = sweep_rows(g, dir.path.string(), first);
  EXPECT_EQ(rows[2].status, "converged");
  EXPECT_EQ(rows[2].objective, 120);
  EXPECT_EQ(rows[2].answer_from, "d1_t20");
  // A second cross-check reuses every try on disk.
  const json second = crosscheck(g, dir.path.string(), o);
  EXPECT_EQ(second.at("runs"), 0);
  EXPECT_EQ(second.at("cells"), cells);
}

}  // namespace

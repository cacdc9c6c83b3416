// The search's chooser (templates/runtime/search/chooser.hpp), the one place the answer is decided,
// on pools of extremals: made up to isolate each rule, and recorded from real runs
// (tests/fixtures/pools: the search record of a solution.json, trimmed by tests/fixtures/pools/trim.jq),
// where the chooser must return what the run returned and give its status.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "helios/solve/verdict.hpp"
#include "runtime_records.hpp"
#include "search/chooser.hpp"

namespace {

using helios_rt::Extremal;
using helios_rt::SearchRecord;
using helios_rt::Status;

Extremal extremal(double cost, double revolutions = 1) {
  Extremal e;
  e.shape.cost = cost;
  e.shape.revolutions = revolutions;
  return e;
}

// solution.json's status of a verdict (the runtime's status_text, which this test does not link).
std::string status_name(Status s) {
  switch (s) {
    case Status::kConverged:
      return "converged";
    case Status::kInfeasible:
      return "infeasible";
    case Status::kTimeout:
      return "timeout";
    default:
      return "not_converged";
  }
}

std::string days(double d) {
  return std::to_string(d) + " days";
}

helios_rt::Verdict verdict_of(const SearchRecord& rec) {
  return helios_rt::verdict(rec, days, days, "nothing reached");
}

TEST(Chooser, ReturnsTheLowestObjectiveAmongTheReturnableOnly) {
  SearchRecord rec;
  rec.extremals = {extremal(3), extremal(1), extremal(0.5), extremal(0.7), extremal(0.9), extremal(2)};
  rec.extremals[1].outside_window = true;  // 1: its final time is outside the window
  rec.extremals[2].polished = false;       // 0.5: did not converge again at the integrator's tolerance
  rec.extremals[3].shape.off_side = "h.n_arrival > 0 (prograde)";  // 0.7: on the mirror of the target
  EXPECT_EQ(helios_rt::best_index(rec), 4);
  EXPECT_DOUBLE_EQ(helios_rt::best_objective(rec), 0.9);
  const helios_rt::Choice c = helios_rt::choose(rec, "by 2 routes");
  EXPECT_EQ(c.returned, 4);
  EXPECT_EQ(c.reason, "the lowest objective of the 6 distinct extremals reached at eps = 0 by 2 routes");
}

TEST(Chooser, AmongEqualObjectivesTheFirstReachedIsReturned) {
  SearchRecord rec;
  rec.extremals = {extremal(2), extremal(1), extremal(1)};
  EXPECT_EQ(helios_rt::choose(rec, "").returned, 1);
  rec.extremals = {extremal(1)};
  EXPECT_EQ(helios_rt::choose(rec, "by 1 route").reason, "the only extremal reached at eps = 0 by 1 route");
}

TEST(Chooser, NothingReturnableReturnsNothing) {
  SearchRecord rec;
  EXPECT_EQ(helios_rt::choose(rec, "").returned, -1);
  EXPECT_TRUE(std::isinf(helios_rt::best_objective(rec)));
  rec.extremals = {extremal(1)};
  rec.extremals[0].outside_window = true;
  EXPECT_EQ(helios_rt::choose(rec, "").returned, -1);
}

TEST(Chooser, SettledByStartsSaturatedOnEnoughConvergedOrByAFewRevolutionBest) {
  SearchRecord rec;
  rec.extremals = {extremal(1, 8.6)};
  rec.saturated = true;
  rec.converged_start = helios_rt::kMinConverged;
  EXPECT_TRUE(helios_rt::settled(rec));
  rec.converged_start = helios_rt::kMinConverged - 1;  // saturated on few: starts find little
  EXPECT_FALSE(helios_rt::settled(rec));
  rec.extremals = {extremal(1, 2.4)};  // a best of few revolutions: where starts are reliable
  EXPECT_TRUE(helios_rt::settled(rec));
  rec.extremals[0].outside_window = true;  // not returnable: nothing settles
  rec.saturated = false;
  EXPECT_FALSE(helios_rt::settled(rec));
}

TEST(Chooser, WithBoundsTheLowestObjectiveThePassesReachedIsReturned) {
  SearchRecord rec;
  rec.extremals = {extremal(1), extremal(2), extremal(3)};
  for (auto& e : rec.extremals) e.bounded_tried = true;
  rec.extremals[0].bounded_objective = NAN;  // its passes did not converge
  rec.extremals[1].bounded_objective = 2.5;
  rec.extremals[2].bounded_objective = 2.4;
  const helios_rt::Choice c = helios_rt::choose_with_bounds(rec);
  EXPECT_EQ(c.returned, 2);
  EXPECT_EQ(c.reason, "the lowest objective with the bounds reached from the 3 distinct extremals of pass 1");
  rec.extremals[2].bounded_tried = false;
  rec.extremals[2].bounded_objective = NAN;
  EXPECT_EQ(helios_rt::choose_with_bounds(rec).returned, 1);
}

TEST(Chooser, InfeasibleOnlyWhereASettledMinimumTimeExceedsTheBound) {
  SearchRecord rec;
  rec.extremals = {extremal(7.09, 8.6)};
  rec.extremals[0].outside_window = true;
  rec.extremals[0].tf_days = 7.09;
  rec.minimum_time_days = 7.09;
  rec.bound_days = 2;
  rec.minimum_time_how = "the window opened to 64 days";
  rec.minimum_time_settled = true;
  helios_rt::Verdict v = verdict_of(rec);
  EXPECT_EQ(v.status, Status::kInfeasible);
  EXPECT_EQ(
      v.detail,
      "no transfer within the stated bound of 2.000000 days: the minimum time is 7.090000 days (the window opened "
      "to 64 days)");
  // not settled: no proof, said so
  rec.minimum_time_settled = false;
  v = verdict_of(rec);
  EXPECT_EQ(v.status, Status::kNotConverged);
  EXPECT_NE(v.detail.find("did not settle"), std::string::npos) << v.detail;
  // a minimum time within the bound proves nothing
  rec.minimum_time_settled = true;
  rec.minimum_time_days = 1.9;
  EXPECT_EQ(verdict_of(rec).status, Status::kNotConverged);
  // a returnable extremal is an answer, whatever else the record says
  rec.minimum_time_days = 7.09;
  rec.extremals.push_back(extremal(1.5));
  rec.returned = 1;
  EXPECT_EQ(verdict_of(rec).status, Status::kConverged);
}

TEST(Chooser, NoExtremalCostlierThanTheMinimumTimeAndACoastIsReturned) {
  SearchRecord rec;
  rec.extremals = {extremal(0.13), extremal(0.11)};
  rec.coast_bound = 0.108;  // the minimum-time transfer completed by a coast burns less than both
  EXPECT_EQ(helios_rt::choose(rec, "").returned, -1);
  const helios_rt::Verdict v = verdict_of(rec);
  EXPECT_EQ(v.status, Status::kNotConverged);
  EXPECT_NE(v.detail.find("more than the minimum-time transfer completed by a coast"), std::string::npos) << v.detail;
  rec.coast_bound = 0.12;
  EXPECT_EQ(helios_rt::choose(rec, "").returned, 1);
}

TEST(Chooser, TheTimeLimitAndWhatWasFoundInsteadAreSaid) {
  SearchRecord rec;
  rec.time_limit_hit = true;
  EXPECT_EQ(verdict_of(rec).status, Status::kTimeout);
  rec.time_limit_hit = false;
  EXPECT_EQ(verdict_of(rec).detail, "nothing reached");
  rec.extremals = {extremal(1), extremal(2)};
  rec.extremals[0].shape.off_side = "h.n_arrival > 0";
  rec.extremals[1].shape.off_side = "h.n_arrival > 0";
  EXPECT_NE(verdict_of(rec).detail.find("mirror of a target"), std::string::npos);
  rec.extremals = {extremal(0.4)};
  rec.extremals[0].outside_window = true;
  rec.extremals[0].tf_days = 0.4;
  rec.bound_days = 2;
  const std::string detail = verdict_of(rec).detail;
  EXPECT_NE(detail.find("before the window opens"), std::string::npos) << detail;
  rec.extremals[0].outside_window = false;
  rec.extremals[0].polished = false;
  EXPECT_NE(verdict_of(rec).detail.find("converged again"), std::string::npos);
}

// A recorded pool (tests/fixtures/pools/*.json): the extremals of a run's search record, what the
// run returned and its status.
SearchRecord record_of(const nlohmann::json& pool) {
  SearchRecord rec;
  for (const auto& e : pool.at("extremals")) {
    Extremal x = extremal(e.at("objective").get<double>(), e.at("revolutions").get<double>());
    x.polished = e.value("polished", true);
    x.outside_window = e.value("outside_window", false);
    x.shape.off_side = e.value("off_side", "");
    x.tf_days = e.contains("tf_days") ? e.at("tf_days").get<double>() : NAN;
    rec.extremals.push_back(x);
  }
  rec.saturated = pool.value("saturated", false);
  rec.converged_start = pool.value("converged_at_eps_start", 0);
  if (pool.contains("minimum_time")) {
    const auto& m = pool.at("minimum_time");
    rec.minimum_time_days = m.at("tf_days").get<double>();
    rec.bound_days = m.at("bound_days").is_number() ? m.at("bound_days").get<double>() : NAN;
    rec.minimum_time_settled = m.at("settled").get<bool>();
    rec.minimum_time_how = m.at("how").get<std::string>();
  }
  rec.time_limit_hit = pool.value("time_limit_hit", false);
  if (pool.contains("coast_bound")) rec.coast_bound = pool.at("coast_bound").get<double>();
  return rec;
}

TEST(Chooser, RecordedPoolsGiveWhatTheirRunsReturned) {
  const std::filesystem::path dir = std::filesystem::path(HELIOS_SOURCE_DIR) / "tests/fixtures/pools";
  int pools = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    ++pools;
    std::ifstream in(entry.path());
    const nlohmann::json pool = nlohmann::json::parse(in);
    SearchRecord rec = record_of(pool);
    const helios_rt::Choice c = helios_rt::choose(rec, "");
    EXPECT_EQ(c.returned, pool.value("returned", -1)) << entry.path();
    rec.returned = c.returned;
    EXPECT_EQ(status_name(verdict_of(rec).status), pool.at("status").get<std::string>()) << entry.path();
  }
  EXPECT_GE(pools, 3);
}

}  // namespace

// The helios-verify accuracy corpus (tests/verify-corpus/manifest.json, issue 4 item 4): every
// correct derivation must pass, every broken one must fail exactly the checks the manifest names,
// each failed check with feedback, and each verdict in well under a second. A case is its base (a
// seed or base derivation) with the case's RFC 6902 JSON Patch applied, if it has one.
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>

#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/verify/verify.hpp"
#include "test_helpers.hpp"

namespace {

using helios::io::json;

const std::string kCorpus = HELIOS_SOURCE_DIR "/tests/verify-corpus/";

// The derivation of a manifest case, schema-valid.
json derivation_of(const json& c) {
  json derivation = helios::io::read_json(kCorpus + c.at("base").get<std::string>());
  if (c.contains("patch"))
    derivation = derivation.patch(helios::io::read_json(kCorpus + c.at("patch").get<std::string>()));
  helios::io::validate("derivation", derivation, c.at("name"));
  return derivation;
}

std::string names(const std::set<std::string>& ids) {
  std::string out;
  for (const auto& id : ids) out += (out.empty() ? "" : ", ") + id;
  return "{" + out + "}";
}

TEST(VerifyCorpus, EveryVerdictIsRightAndNamesTheFaultyCheck) {
  const json manifest = helios::io::read_json(kCorpus + "manifest.json");
  const json& cases = manifest.at("cases");
  ASSERT_GE(cases.size(), 40u);
  std::size_t right = 0, correct = 0, broken = 0;
  double slowest = 0;
  std::string slowest_case;
  for (const auto& c : cases) {
    const std::string name = c.at("name");
    SCOPED_TRACE(name);
    const json derivation = derivation_of(c);
    const auto t0 = std::chrono::steady_clock::now();
    const json report = helios::verify::verify_derivation(derivation, {});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    helios::io::validate("verify", report, name);
    if (seconds > slowest) {
      slowest = seconds;
      slowest_case = name;
    }
    std::set<std::string> failed, expected;
    for (const auto& check : report["checks"])
      if (check["verdict"] == "fail") {
        failed.insert(check["id"].get<std::string>());
        EXPECT_FALSE(check["feedback"].get<std::string>().empty()) << check["id"];
      }
    for (const auto& id : c.at("fails")) expected.insert(id.get<std::string>());
    (expected.empty() ? correct : broken) += 1;
    EXPECT_EQ(report["verdict"], c.at("verdict")) << report["feedback"];
    EXPECT_EQ(names(failed), names(expected)) << report["feedback"];
    if (report["verdict"] == c.at("verdict") && failed == expected) ++right;
    EXPECT_LT(seconds, 1.0 * helios::test::kTimeScale);
  }
  EXPECT_EQ(right, cases.size()) << right << " of " << cases.size() << " verdicts right";
  RecordProperty("cases", static_cast<int>(cases.size()));
  RecordProperty("correct_cases", static_cast<int>(correct));
  RecordProperty("broken_cases", static_cast<int>(broken));
  RecordProperty("slowest_case", slowest_case + " " + std::to_string(slowest) + " s");
}

}  // namespace

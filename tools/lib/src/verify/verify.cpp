#include "helios/verify/verify.hpp"

#include <string>
#include <vector>

#include "context.hpp"
#include "family.hpp"
#include "helios/io/schema.hpp"

namespace helios::verify {
namespace {

using detail::Check;
using io::json;

// The verify artifact of the checks, in order: verdict, summary and the failures' feedback.
json report(const derivation::Document& derivation, const VerifyOptions& options, const std::vector<Check>& checks) {
  json doc = io::artifact_header("verify", "helios-verify", "builtin");
  doc["problem"] = {{"id", derivation.problem_id}};
  doc["derivation_producer"] = derivation.producer.is_null() ? json::object() : derivation.producer;
  doc["settings"] = {{"points", options.points}, {"seed", options.seed}, {"rel_tolerance", detail::kTol}};
  int passed = 0, failed = 0;
  json list = json::array();
  std::vector<std::string> feedback;
  for (const auto& c : checks) {
    list.push_back(c.to_json());
    if (c.pass) {
      ++passed;
    } else {
      ++failed;
      feedback.push_back(c.feedback);
    }
  }
  doc["verdict"] = failed == 0 ? "pass" : "fail";
  doc["checks"] = list;
  doc["summary"] = {{"passed", passed}, {"failed", failed}, {"total", passed + failed}};
  doc["feedback"] = detail::join(feedback, " ");
  return doc;
}

}  // namespace

json verify_derivation(const json& derivation, const VerifyOptions& options) {
  const detail::Context ctx(derivation, options);
  std::vector<Check> checks;
  for (auto* make : {&detail::control_family, &detail::boundary_family, &detail::event_family, &detail::shape_family,
                     &detail::target_family, &detail::terms_family})
    for (auto& c : make(ctx)->run()) checks.push_back(std::move(c));
  return report(ctx.doc, options, checks);
}

}  // namespace helios::verify

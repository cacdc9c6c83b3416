#include "helios/score/score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/report/report.hpp"

namespace helios::score {
namespace {

using io::json;

// ---------------------------------------------------------------------------------------------
// Helpers.

std::string fmt(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

json detail(const std::string& id, const std::string& verdict, double points, double max, const std::string& note) {
  return json{{"id", id}, {"verdict", verdict}, {"points", points}, {"max", max}, {"note", note}};
}

json opt_number(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

json dimension(double points, double max, json details) {
  return json{{"points", std::clamp(points, 0.0, max)}, {"max", max}, {"details", std::move(details)}};
}

const json* field(const std::optional<json>& doc, const char* pointer) {
  if (!doc || !doc->is_object()) return nullptr;
  const json::json_pointer p(pointer);
  return doc->contains(p) ? &doc->at(p) : nullptr;
}

std::optional<double> number_at(const std::optional<json>& doc, const char* pointer) {
  const json* v = field(doc, pointer);
  if (v && v->is_number()) return v->get<double>();
  return std::nullopt;
}

std::string string_at(const std::optional<json>& doc, const char* pointer) {
  const json* v = field(doc, pointer);
  return v && v->is_string() ? v->get<std::string>() : std::string();
}

// Compares a spec value with an expected one; empty string = match, else why not.
// NOTE: numbers (and arrays of numbers, component-wise) match if
// |found - expected| <= abs_tol + rel_tol * |expected|.
std::string compare(const json& found, const json& expected, double rel_tol, double abs_tol) {
  const auto close = [&](double f, double e) { return std::fabs(f - e) <= abs_tol + rel_tol * std::fabs(e); };
  const std::string tol = " (rel_tol " + io::short_number(rel_tol) +
                          (abs_tol > 0 ? ", abs_tol " + io::short_number(abs_tol) : std::string()) + ")";
  if (expected.is_number()) {
    if (!found.is_number())
      return "expected a number " + io::short_number(expected.get<double>()) + ", found " + found.dump();
    if (!close(found.get<double>(), expected.get<double>()))
      return "found " + io::short_number(found.get<double>()) + ", expected " +
             io::short_number(expected.get<double>()) + tol;
    return "";
  }
  if (expected.is_array()) {
    if (!found.is_array() || found.size() != expected.size())
      return "expected an array of " + std::to_string(expected.size()) + " numbers, found " + found.dump();
    for (std::size_t i = 0; i < expected.size(); ++i) {
      if (!found[i].is_number()) return "component " + std::to_string(i) + " is " + found[i].dump() + ", not a number";
      if (!close(found[i].get<double>(), expected[i].get<double>()))
        return "component " + std::to_string(i) + ": found " + io::short_number(found[i].get<double>()) +
               ", expected " + io::short_number(expected[i].get<double>()) + tol;
    }
    return "";
  }
  if (found != expected) return "found " + found.dump() + ", expected " + expected.dump();
  return "";
}

// d1: one fact of expected_parse looked up in the spec.
json score_fact(const json& fact, const std::optional<json>& spec, double share) {
  const std::string id = fact["id"].get<std::string>();
  const std::string rel = fact["pointer"].get<std::string>();
  const json& expected = fact["value"];
  const double rel_tol = fact.value("rel_tol", 0.0);
  const double abs_tol = fact.value("abs_tol", 0.0);
  json d;
  const auto finish = [&](bool pass, const std::string& pointer, const json* found, const std::string& note) {
    d = detail(id, pass ? "pass" : (spec ? "fail" : "missing"), pass ? share : 0.0, share, note);
    d["pointer"] = pointer;
    d["expected"] = expected;
    d["found"] = found ? *found : json(nullptr);
    return d;
  };

  if (!fact.contains("in")) {
    if (!spec) return finish(false, rel, nullptr, "no spec.json");
    const json::json_pointer p(rel);
    if (!spec->contains(p)) return finish(false, rel, nullptr, "spec has no " + rel);
    const json& found = spec->at(p);
    const std::string why = compare(found, expected, rel_tol, abs_tol);
    return finish(why.empty(), rel, &found, why.empty() ? "matches" : why);
  }

  const std::string array = fact["in"]["array"].get<std::string>();
  const json& where = fact["in"]["where"];
  std::string filter;
  for (auto it = where.begin(); it != where.end(); ++it)
    filter += (filter.empty() ? "" : " and ") + it.key() + " = " + it.value().dump();
  const std::string looked_for = array + "/<" + filter + ">" + rel;
  if (!spec) return finish(false, looked_for, nullptr, "no spec.json");
  const json::json_pointer ap(array);
  if (!spec->contains(ap) || !spec->at(ap).is_array())
    return finish(false, looked_for, nullptr, "spec has no array " + array);
  const json& items = spec->at(ap);
  // Any element with the `where` values may hold the fact, so a reordered array still scores.
  std::optional<std::pair<std::string, std::string>> first_miss;  // pointer, why
  const json* first_found = nullptr;
  std::size_t candidates = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const json& item = items[i];
    if (!item.is_object()) continue;
    bool selected = true;
    for (auto it = where.begin(); it != where.end(); ++it)
      selected = selected && item.contains(it.key()) && item[it.key()] == it.value();
    if (!selected) continue;
    ++candidates;
    const std::string pointer = array + "/" + std::to_string(i) + rel;
    const json::json_pointer p(rel);
    if (!item.contains(p)) {
      if (!first_miss) first_miss = {{pointer, "has no " + rel}};
      continue;
    }
    const json& found = item.at(p);
    const std::string why = compare(found, expected, rel_tol, abs_tol);
    if (why.empty()) return finish(true, pointer, &found, "matches");
    if (!first_miss) {
      first_miss = {{pointer, why}};
      first_found = &found;
    }
  }
  if (candidates == 0) return finish(false, looked_for, nullptr, "no element of " + array + " has " + filter);
  std::string note = first_miss->second;
  if (candidates > 1)
    note = "none of the " + std::to_string(candidates) + " elements with " + filter + " matches; first: " + note;
  return finish(false, first_miss->first, first_found, note);
}

json score_parse(const json& reference, const std::optional<json>& spec) {
  const json& facts = reference["expected_parse"];
  const double share = kParseMax / static_cast<double>(facts.size());
  json details = json::array();
  std::size_t passed = 0;
  for (const json& fact : facts) {
    details.push_back(score_fact(fact, spec, share));
    if (details.back()["verdict"] == "pass") ++passed;
  }
  // Points from the count, not a sum of shares, so a perfect parse is exactly kParseMax.
  return dimension(kParseMax * static_cast<double>(passed) / static_cast<double>(facts.size()), kParseMax, details);
}

json score_derive(const json& reference, const std::optional<json>& derivation, const std::optional<json>& verify,
                  std::optional<long>& shooting_variables) {
  json details = json::array();
  double points = 0;

  // Verification: kDeriveVerifyMax scaled by the fraction of checks that passed.
  if (!verify) {
    details.push_back(detail("verify", "missing", 0, kDeriveVerifyMax, "no verify.json"));
  } else {
    const std::string verdict = string_at(verify, "/verdict");
    std::size_t passed = 0, total = 0;
    const json* checks = field(verify, "/checks");
    if (checks && checks->is_array() && !checks->empty()) {
      total = checks->size();
      for (const json& c : *checks)
        if (c.is_object() && c.value("verdict", "") == "pass") ++passed;
    } else if (number_at(verify, "/summary/total").value_or(0) > 0) {
      total = static_cast<std::size_t>(*number_at(verify, "/summary/total"));
      passed =
          static_cast<std::size_t>(std::clamp(number_at(verify, "/summary/passed").value_or(0), 0.0, double(total)));
    } else {
      total = 1;
      passed = verdict == "pass" ? 1 : 0;
    }
    const double pts = kDeriveVerifyMax * static_cast<double>(passed) / static_cast<double>(total);
    const std::string v = passed == total ? "pass" : (passed == 0 ? "fail" : "partial");
    details.push_back(detail("verify", v, pts, kDeriveVerifyMax,
                             "verdict " + (verdict.empty() ? std::string("missing") : verdict) + ", " +
                                 std::to_string(passed) + " of " + std::to_string(total) + " checks passed"));
    points += pts;
  }

  // Shooting-variable count.
  if (reference.is_null()) {
    const json* vars = field(derivation, "/shooting/variables");
    if (vars && vars->is_array()) shooting_variables = static_cast<long>(vars->size());
    details.push_back(detail("shooting_variables", "no_reference", 0, 0, "no reference: the count is not compared"));
    return dimension(points, kDeriveVerifyMax, details);
  }
  const long expected = reference["expected_shooting_variables"].get<long>();
  if (!derivation) {
    details.push_back(detail("shooting_variables", "missing", 0, kDeriveVariablesMax, "no derivation.json"));
  } else {
    const json* vars = field(derivation, "/shooting/variables");
    json d;
    if (!vars || !vars->is_array()) {
      d = detail("shooting_variables", "fail", 0, kDeriveVariablesMax, "derivation has no /shooting/variables array");
      d["found"] = nullptr;
    } else {
      shooting_variables = static_cast<long>(vars->size());
      const bool ok = *shooting_variables == expected;
      d = detail("shooting_variables", ok ? "pass" : "fail", ok ? kDeriveVariablesMax : 0, kDeriveVariablesMax,
                 std::to_string(*shooting_variables) + " shooting variables, expected " + std::to_string(expected));
      d["found"] = *shooting_variables;
      points += ok ? kDeriveVariablesMax : 0;
    }
    d["expected"] = expected;
    details.push_back(d);
  }
  return dimension(points, kDeriveMax, details);
}

std::string status_note(const std::optional<json>& solution) {
  const std::string status = string_at(solution, "/status");
  const std::string detail_text = string_at(solution, "/status_detail");
  return "status " + (status.empty() ? std::string("missing") : status) +
         (detail_text.empty() ? "" : " (" + detail_text + ")");
}

json score_compile(const std::optional<json>& solution) {
  json details = json::array();
  if (!solution) {
    details.push_back(detail("compile", "missing", 0, kCompileMax, "no solution.json"));
    return dimension(0, kCompileMax, details);
  }
  const json* ok = field(solution, "/compile/ok");
  const bool compiled = ok && ok->is_boolean() && ok->get<bool>();
  details.push_back(detail("compile", compiled ? "pass" : "fail", compiled ? kCompileMax : 0, kCompileMax,
                           compiled ? "compile.ok" : "compile.ok is not true; " + status_note(solution)));
  return dimension(compiled ? kCompileMax : 0, kCompileMax, details);
}

json score_converge(const json& reference, const std::optional<json>& solution) {
  json details = json::array();
  if (!solution) {
    details.push_back(detail("status", "missing", 0, kConvergeStatusMax, "no solution.json"));
    details.push_back(detail("residual", "missing", 0, kConvergeResidualMax, "no solution.json"));
    return dimension(0, kConvergeMax, details);
  }
  const bool converged = string_at(solution, "/status") == "converged";
  details.push_back(detail("status", converged ? "pass" : "fail", converged ? kConvergeStatusMax : 0,
                           kConvergeStatusMax, status_note(solution)));
  if (reference.is_null()) {
    json d = detail("residual", "no_reference", 0, 0, "no reference: max_residual is not compared with one");
    d["found"] = opt_number(number_at(solution, "/max_residual"));
    details.push_back(d);
    return dimension(converged ? kConvergeStatusMax : 0, kConvergeStatusMax, details);
  }
  const double limit = reference["result"]["max_residual"].get<double>();
  const auto residual = number_at(solution, "/max_residual");
  const bool small = residual && *residual < limit;
  json d = detail("residual", small ? "pass" : "fail", small ? kConvergeResidualMax : 0, kConvergeResidualMax,
                  residual ? "max_residual " + fmt(*residual, "%.3g") + (small ? " < " : " >= ") + fmt(limit, "%.3g")
                           : "no max_residual in solution.json");
  d["expected"] = "< " + fmt(limit, "%.3g");
  d["found"] = residual ? json(*residual) : json(nullptr);
  details.push_back(d);
  return dimension((converged ? kConvergeStatusMax : 0) + (small ? kConvergeResidualMax : 0), kConvergeMax, details);
}

// The quantity d5 scores: the initial mass (minimum-initial-mass problems), the final mass, or the
// time of flight, whichever the reference gives.
struct Accuracy {
  std::string id, key, unit, symbol;
  double ref = 0, tol = 0;
};

Accuracy accuracy_quantity(const json& reference) {
  const json& r = reference["result"];
  if (r.contains("initial_mass_kg"))
    return {"initial_mass",
            "initial_mass_kg",
            "kg",
            "m_0",
            r["initial_mass_kg"].get<double>(),
            r["tolerance_kg"].get<double>()};
  if (r.contains("final_mass_kg"))
    return {
        "final_mass", "final_mass_kg", "kg", "m_f", r["final_mass_kg"].get<double>(), r["tolerance_kg"].get<double>()};
  return {"final_time", "tof_days", "days", "tof", r["tof_days"].get<double>(), r["tolerance_days"].get<double>()};
}

json score_accuracy(const json& reference, const std::optional<json>& solution) {
  json details = json::array();
  const Accuracy q = accuracy_quantity(reference);
  const double ref = q.ref, tol = q.tol;
  const auto mf = number_at(solution, ("/" + q.key).c_str());
  json d;
  double points = 0;
  if (!solution) {
    d = detail(q.id, "missing", 0, kAccuracyMax, "no solution.json");
  } else if (string_at(solution, "/status") != "converged") {
    // The result of an unconverged run belongs to no trajectory that satisfies the constraints.
    d = detail(q.id, "fail", 0, kAccuracyMax, "not scored: " + status_note(solution));
  } else if (!mf) {
    d = detail(q.id, "fail", 0, kAccuracyMax, "no " + q.key + " in solution.json");
  } else {
    const double err = std::fabs(*mf - ref);
    // NOTE: full points within tol, then linear to 0 at kAccuracyZeroAt * tol.
    if (err <= tol)
      points = kAccuracyMax;
    else
      points = std::max(0.0, kAccuracyMax * (kAccuracyZeroAt * tol - err) / ((kAccuracyZeroAt - 1) * tol));
    const std::string verdict = points >= kAccuracyMax ? "pass" : (points > 0 ? "partial" : "fail");
    const std::string u = " " + q.unit;
    d = detail(q.id, verdict, points, kAccuracyMax,
               q.symbol + " " + fmt(*mf, "%.6f") + u + " vs " + fmt(ref, "%.6f") + u + ": error " + fmt(err, "%.6f") +
                   u + ", tolerance " + io::short_number(tol) + u + ", 0 points at " +
                   io::short_number(kAccuracyZeroAt * tol) + u);
  }
  d["expected"] = ref;
  d["found"] = mf ? json(*mf) : json(nullptr);
  details.push_back(d);
  return dimension(points, kAccuracyMax, details);
}

std::string cell_points(const json& dim) {
  std::string s = fmt(dim.value("points", 0.0), "%.2f");
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string cell(const json& v, const char* format) {
  return v.is_number() ? fmt(v.get<double>(), format) : std::string("n/a");
}

}  // namespace

void check_reference(const json& r, const std::string& source) {
  io::validate("reference", r, source);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < r["expected_parse"].size(); ++i)
    if (!ids.insert(r["expected_parse"][i]["id"].get<std::string>()).second)
      throw input_error(source + ": field /expected_parse/" + std::to_string(i) + "/id repeats the id " +
                        r["expected_parse"][i]["id"].dump());
}

// The dimensions a reference scores (d1's facts, d5's accuracy) without one: no points of none.
json no_reference(const std::string& id, const std::string& note) {
  return dimension(0, 0, json::array({detail(id, "no_reference", 0, 0, "no reference: " + note)}));
}

json score_run(const ScoreInputs& in) {
  const bool has_reference = !in.reference.is_null();
  if (has_reference) check_reference(in.reference, in.reference_source);
  const json& ref = in.reference;
  const std::string scenario = has_reference ? ref["scenario"].get<std::string>() : in.scenario;
  if (scenario.empty()) throw input_error("a score without a reference needs the scenario's name");

  // The run's backend comes from the latest stage that ran, its model from the latest stage a
  // model wrote (helios-solve and helios-verify record none).
  std::string backend, model;
  for (const auto* doc : {&in.solution, &in.verify, &in.derivation, &in.spec}) {
    const std::string b = string_at(*doc, "/producer/backend");
    if (backend.empty() && (b == "builtin" || b == "llm")) backend = b;
    if (model.empty() && b == "llm") model = string_at(*doc, "/producer/model");
  }
  if (backend.empty()) backend = "builtin";
  json out = io::artifact_header("score", "helios-score", backend);
  if (!model.empty()) out["producer"]["model"] = model;
  out["scenario"] = scenario;
  out["reference"] =
      has_reference ? json{{"provenance", ref["provenance"]}, {"citation", ref["citation"]}} : json(nullptr);
  out["inputs"] = {{"spec", in.spec.has_value()},
                   {"derivation", in.derivation.has_value()},
                   {"verify", in.verify.has_value()},
                   {"solution", in.solution.has_value()}};

  json warnings = json::array();
  const std::pair<const char*, const std::optional<json>*> named[] = {
      {"spec", &in.spec}, {"derivation", &in.derivation}, {"solution", &in.solution}};
  for (const auto& [name, doc] : named) {
    const std::string id = string_at(*doc, "/problem/id");
    if (has_reference && !id.empty() && id != scenario)
      warnings.push_back(std::string(name) + ".json is problem \"" + id + "\" but the reference is scenario \"" +
                         scenario + "\"");
  }
  if (in.verify) {
    const std::string verdict = string_at(in.verify, "/verdict");
    if (verdict != "pass" && verdict != "fail")
      warnings.push_back("verify.json has no verdict \"pass\" or \"fail\" (found " +
                         (verdict.empty() ? "none" : verdict) + ")");
  }

  std::optional<long> shooting_variables;
  json dims = json::object();
  dims["d1_parse"] = has_reference ? score_parse(ref, in.spec)
                                   : no_reference("facts", "the spec's facts are not compared with expected ones");
  dims["d2_derive"] = score_derive(ref, in.derivation, in.verify, shooting_variables);
  dims["d3_compile"] = score_compile(in.solution);
  dims["d4_converge"] = score_converge(ref, in.solution);
  dims["d5_accuracy"] =
      has_reference ? score_accuracy(ref, in.solution) : no_reference("accuracy", "no published result to compare");
  double total = 0, max_total = 0;
  for (auto it = dims.begin(); it != dims.end(); ++it) {
    total += it.value()["points"].get<double>();
    max_total += it.value()["max"].get<double>();
  }
  out["dimensions"] = dims;
  out["total"] = std::clamp(total, 0.0, 100.0);
  out["max_total"] = std::lround(max_total);

  const auto mf = number_at(in.solution, "/final_mass_kg");
  const auto ref_mf = number_at(ref, "/result/final_mass_kg");  // none without a reference
  const std::string status = string_at(in.solution, "/status");
  out["measured"] = {{"final_mass_kg", opt_number(mf)},
                     {"reference_final_mass_kg", opt_number(ref_mf)},
                     {"error_kg", mf && ref_mf ? json(std::fabs(*mf - *ref_mf)) : json(nullptr)},
                     {"max_residual", opt_number(number_at(in.solution, "/max_residual"))},
                     {"shooting_variables", shooting_variables ? json(*shooting_variables) : json(nullptr)},
                     {"status", status.empty() ? json(nullptr) : json(status)}};
  if (!has_reference) {
    if (const auto tof = number_at(in.solution, "/tof_days")) out["measured"]["tof_days"] = *tof;
    if (!warnings.empty()) out["warnings"] = warnings;
    io::validate("score", out, "output score");
    return out;
  }
  out["measured"]["reference_max_residual"] = ref["result"]["max_residual"];
  out["measured"]["reference_shooting_variables"] = ref["expected_shooting_variables"];
  if (const auto ref_m0 = number_at(ref, "/result/initial_mass_kg")) {
    const auto m0 = number_at(in.solution, "/initial_mass_kg");
    out["measured"]["initial_mass_kg"] = opt_number(m0);
    out["measured"]["reference_initial_mass_kg"] = *ref_m0;
    out["measured"]["error_initial_mass_kg"] = m0 ? json(std::fabs(*m0 - *ref_m0)) : json(nullptr);
  }
  if (const auto ref_tof = number_at(ref, "/result/tof_days")) {
    const auto tof = number_at(in.solution, "/tof_days");
    out["measured"]["tof_days"] = opt_number(tof);
    out["measured"]["reference_tof_days"] = *ref_tof;
    out["measured"]["error_days"] = tof ? json(std::fabs(*tof - *ref_tof)) : json(nullptr);
  }
  if (!warnings.empty()) out["warnings"] = warnings;
  io::validate("score", out, "output score");
  return out;
}

std::string render_scoreboard(const std::vector<json>& scores) {
  static const char* const kDims[] = {"d1_parse", "d2_derive", "d3_compile", "d4_converge", "d5_accuracy"};
  std::ostringstream md;
  md << "# HELIOS scoreboard\n\n"
     << "Rubric: d1 parse 30, d2 derive 20, d3 compile 20, d4 converge 20, d5 accuracy 10 (total 100). "
     << "m_f in kg; residual = max |F| in normalized units.\n\n"
     << "| scenario | backend | d1 parse | d2 derive | d3 compile | d4 converge | d5 accuracy | total | m_f | m_f ref "
        "| error | residual |\n"
     << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  double sums[5] = {0, 0, 0, 0, 0};
  double grand = 0;
  for (const json& s : scores) {
    const json& p = s.value("producer", json::object());
    std::string backend = p.value("backend", "?");
    if (p.contains("model") && p["model"].is_string()) backend += " (" + p["model"].get<std::string>() + ")";
    md << "| " << report::markdown_text(s.value("scenario", "?")) << " | " << report::markdown_text(backend);
    for (int i = 0; i < 5; ++i) {
      const json& dim = s["dimensions"][kDims[i]];
      sums[i] += dim.value("points", 0.0);
      md << " | " << cell_points(dim);
    }
    grand += s.value("total", 0.0);
    const json& m = s["measured"];
    md << " | " << cell_points(json{{"points", s.value("total", 0.0)}}) << " | " << cell(m["final_mass_kg"], "%.3f")
       << " | " << cell(m["reference_final_mass_kg"], "%.3f") << " | " << cell(m["error_kg"], "%.3f") << " | "
       << cell(m["max_residual"], "%.1e") << " |\n";
  }
  const std::size_t n = scores.size();
  md << "| **total** | " << n << " scenario" << (n == 1 ? "" : "s");
  for (double v : sums) md << " | **" << cell_points(json{{"points", v}}) << "**";
  md << " | **" << cell_points(json{{"points", grand}}) << " / " << 100 * n << "** | | | | |\n";
  return md.str();
}

std::string render_search_table(const std::vector<json>& scores, const std::vector<std::optional<json>>& solutions) {
  std::ostringstream md;
  md << "\n## The solutions and their search\n\n"
     << "From each run's solution.json: the shooting variables it solved for, the extremals the search compared, "
        "whether it saturated (the chance that another start finds a new extremal fell below its bound), its starts, "
        "and the solve's wall time.\n\n"
     << "| scenario | status | tof [d] | propellant [kg] | variables | extremals | saturated | starts | solve [s] |\n"
     << "|---|---|--:|--:|--:|--:|---|--:|--:|\n";
  for (std::size_t k = 0; k < scores.size(); ++k) {
    if (!solutions[k]) continue;
    const json& sol = *solutions[k];
    const json& search = sol.value("search", json::object());
    const json extremals =
        search.contains("extremals") && search["extremals"].is_array() ? json(search["extremals"].size()) : json();
    const json saturated = search.value("saturated", json());
    const json variables = sol.contains("x") && sol["x"].is_array() ? json(sol["x"].size()) : json();
    md << "| " << report::markdown_text(scores[k].value("scenario", "?")) << " | "
       << report::markdown_text(sol.value("status", "?")) << " | " << cell(sol.value("tof_days", json()), "%.3f")
       << " | " << cell(sol.value("propellant_kg", json()), "%.3f") << " | " << cell(variables, "%.0f") << " | "
       << cell(extremals, "%.0f") << " | " << (saturated.is_boolean() ? (saturated.get<bool>() ? "yes" : "no") : "-")
       << " | " << cell(search.value("starts", json()), "%.0f") << " | "
       << cell(sol.value("timings", json::object()).value("total_s", json()), "%.1f") << " |\n";
  }
  return md.str();
}

std::string scoreboard_from_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw input_error(dir + ": not a folder, expected a run folder such as runs/builtin");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::path candidate = entry.path() / "score.json";
    if (entry.is_directory(ec) && fs::is_regular_file(candidate, ec)) files.push_back(candidate);
  }
  if (ec) throw input_error(dir + ": cannot list: " + ec.message());
  if (files.empty()) throw input_error(dir + ": no */score.json found, run helios-score for a scenario first");
  std::sort(files.begin(), files.end());
  std::vector<json> scores;
  std::vector<std::optional<json>> solutions;
  bool any_solution = false;
  for (const auto& f : files) {
    scores.push_back(io::read_artifact("score", f.string()));
    const fs::path solution = f.parent_path() / "solution.json";
    solutions.push_back(fs::is_regular_file(solution, ec)
                            ? std::optional<json>(io::read_artifact("solution", solution.string()))
                            : std::nullopt);
    any_solution = any_solution || solutions.back().has_value();
  }
  return render_scoreboard(scores) + (any_solution ? render_search_table(scores, solutions) : "");
}

namespace {

// One scenario run found under a runs tree, for the paper's tables.
struct RunRecord {
  std::string group;  // "<backend> (<model>)" or the backend
  std::string scenario;
  double score = 0;
  bool compiled = false, converged = false;
  bool has_repair_loop = false, compiled_first = false;
  int repair_rounds = 0, derive_rounds = 0, requests = 0;
  long prompt_tokens = 0, completion_tokens = 0, total_tokens = 0;
};

// Runs are grouped by backend and model, so repeated runs of one model in several folders
// (runs/llm-a, runs/llm-b) count together; the folder name stands in for an unknown backend.
std::string group_label(const std::string& folder, const std::string& backend, const std::string& model) {
  std::string label = backend.empty() ? folder : backend;
  if (!model.empty()) label += " (" + model + ")";
  return label;
}

std::string frac(int k, int n) {
  return std::to_string(k) + "/" + std::to_string(n);
}

std::string thousands(long v) {
  std::string s = std::to_string(v);
  for (int i = static_cast<int>(s.size()) - 3; i > (v < 0 ? 1 : 0); i -= 3) s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

RunRecord read_run(const std::filesystem::path& folder, const std::string& run_folder) {
  namespace fs = std::filesystem;
  RunRecord r;
  const json score = io::read_artifact("score", (folder / "score.json").string());
  r.scenario = score.value("scenario", folder.filename().string());
  r.score = score.value("total", 0.0);
  const json& d3 = score["dimensions"]["d3_compile"];
  r.compiled = d3.value("points", 0.0) >= d3.value("max", kCompileMax);
  r.converged = score["measured"].value("status", json()).is_string() && score["measured"]["status"] == "converged";
  std::string model = score["producer"].value("model", "");
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    const std::string name = f.filename().string();
    if (name.size() > 16 && name.substr(name.size() - 16) == ".transcript.json") {
      const json t = io::read_artifact("transcript", f.string());
      r.prompt_tokens += t["usage"]["prompt_tokens"].get<long>();
      r.completion_tokens += t["usage"]["completion_tokens"].get<long>();
      r.total_tokens += t["usage"]["total_tokens"].get<long>();
      r.requests += static_cast<int>(t["turns"].size());
      if (t["purpose"] == "repair") ++r.repair_rounds;
      if (t["purpose"] == "derive") ++r.derive_rounds;
      if (model.empty()) model = t["producer"].value("model", "");
    }
  }
  if (fs::exists(folder / "compile.r1.json")) {
    r.has_repair_loop = true;
    r.compiled_first = io::read_artifact("compile", (folder / "compile.r1.json").string())["ok"].get<bool>();
  } else {
    r.compiled_first = r.compiled;
  }
  r.group = group_label(run_folder, score["producer"].value("backend", ""), model);
  return r;
}

// Every <run folder>/<scenario>/ under `root` that has a score.json, in name order.
std::vector<RunRecord> read_runs(const std::string& root) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw input_error(root + ": not a folder, expected a runs tree such as runs/");
  std::vector<fs::path> run_folders;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (e.is_directory(ec) && e.path().filename().string().front() != '.') run_folders.push_back(e.path());
  std::sort(run_folders.begin(), run_folders.end());
  std::vector<RunRecord> runs;
  for (const auto& folder : run_folders) {
    std::vector<fs::path> scenarios;
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.is_directory(ec) && fs::is_regular_file(e.path() / "score.json", ec)) scenarios.push_back(e.path());
    std::sort(scenarios.begin(), scenarios.end());
    for (const auto& s : scenarios) runs.push_back(read_run(s, folder.filename().string()));
  }
  if (runs.empty())
    throw input_error(root + ": no <backend>/<scenario>/score.json found, run make scenario=S01 [BACKEND=llm] first");
  return runs;
}

// The runs grouped by backend (model) and scenario, and the three tables written from them.
class RunTables {
 public:
  explicit RunTables(std::vector<RunRecord> runs) : runs_(std::move(runs)) {
    for (const auto& r : runs_) {
      if (std::find(groups_.begin(), groups_.end(), r.group) == groups_.end()) groups_.push_back(r.group);
      if (std::find(scenarios_.begin(), scenarios_.end(), r.scenario) == scenarios_.end())
        scenarios_.push_back(r.scenario);
    }
    std::sort(scenarios_.begin(), scenarios_.end());
  }

  // Table 1: per scenario and group, then each group's totals in bold.
  void comparison(std::ostream& md) const {
    md << "## Table 1: per-scenario comparison of backends and models\n\n"
       << "| scenario | backend (model) | runs | mean score | compiled | converged |\n"
       << "|---|---|--:|--:|--:|--:|\n";
    for (const auto& scenario : scenarios_)
      for (const auto& group : groups_) comparison_row(md, group, scenario);
    for (const auto& group : groups_) comparison_row(md, group, "");
  }

  void tokens(std::ostream& md) const {
    md << "\n## Table 2: token consumption\n\n"
       << "| backend (model) | scenarios | requests | input tokens | output tokens | total tokens | "
          "total per scenario |\n"
       << "|---|--:|--:|--:|--:|--:|--:|\n";
    for (const auto& group : groups_) {
      const auto sel = select(group, "");
      long in = 0, out = 0, total = 0;
      int requests = 0;
      for (const auto* r : sel) {
        in += r->prompt_tokens;
        out += r->completion_tokens;
        total += r->total_tokens;
        requests += r->requests;
      }
      const long n = static_cast<long>(sel.size());
      md << "| " << report::markdown_text(group) << " | " << n << " | " << requests << " | " << thousands(in) << " | "
         << thousands(out) << " | " << thousands(total) << " | " << thousands((total + n / 2) / n) << " |\n";
    }
  }

  void repair_loop(std::ostream& md) const {
    md << "\n## Table 3: effect of the compile-repair loop\n\n"
       << "| backend (model) | scenarios | compiled before repair | compiled after repair | repaired | "
          "repair rounds used |\n"
       << "|---|--:|--:|--:|--:|--:|\n";
    for (const auto& group : groups_) {
      const auto sel = select(group, "");
      int before = 0, after = 0, repaired = 0, rounds = 0;
      bool loop = false;
      for (const auto* r : sel) {
        before += r->compiled_first;
        after += r->compiled;
        repaired += !r->compiled_first && r->compiled;
        rounds += r->repair_rounds;
        loop = loop || r->has_repair_loop;
      }
      const int n = static_cast<int>(sel.size());
      md << "| " << report::markdown_text(group) << " | " << n << " | " << frac(before, n) << " | " << frac(after, n)
         << " | " << repaired << " | " << (loop ? std::to_string(rounds) : std::string("no loop")) << " |\n";
    }
  }

 private:
  // The runs of `group` on `scenario` ("" = every scenario).
  std::vector<const RunRecord*> select(const std::string& group, const std::string& scenario) const {
    std::vector<const RunRecord*> out;
    for (const auto& r : runs_)
      if (r.group == group && (scenario.empty() || r.scenario == scenario)) out.push_back(&r);
    return out;
  }

  // One row of table 1: the runs of `group` on `scenario` ("" = all scenarios), bold for the totals.
  void comparison_row(std::ostream& md, const std::string& group, const std::string& scenario) const {
    const auto sel = select(group, scenario);
    if (sel.empty()) return;
    double sum = 0;
    int compiled = 0, converged = 0;
    for (const auto* r : sel) {
      sum += r->score;
      compiled += r->compiled;
      converged += r->converged;
    }
    const int n = static_cast<int>(sel.size());
    const std::string b = scenario.empty() ? "**" : "";
    md << "| " << (scenario.empty() ? "**all**" : report::markdown_text(scenario)) << " | "
       << report::markdown_text(group) << " | " << n << " | " << b << fmt(sum / n, "%.1f") << b << " | " << b
       << frac(compiled, n) << b << " | " << b << frac(converged, n) << b << " |\n";
  }

  std::vector<RunRecord> runs_;
  std::vector<std::string> groups_, scenarios_;
};

}  // namespace

std::string tables_from_runs(const std::string& root) {
  const RunTables tables(read_runs(root));
  std::ostringstream md;
  md << "# HELIOS results across backends and models\n\n"
     << "From every `<run folder>/<scenario>/` under " << report::markdown_text(root)
     << " that has a score.json. Rubric as in the scoreboard (total 100); tokens from the llm "
        "transcripts (`*.transcript.json`).\n\n";
  tables.comparison(md);
  tables.tokens(md);
  tables.repair_loop(md);
  return md.str();
}

}  // namespace helios::score

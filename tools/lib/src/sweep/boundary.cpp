// A sweep's feasibility boundary: each departure's minimum-time transfer (helios/sweep/sweep.hpp).
// A cell whose time of flight is below it cannot be flown by the stated engine; the boundary's
// problem is the template's own, with the time of flight freed and minimized.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/solve/verdict.hpp"
#include "helios/spec/parse.hpp"
#include "helios/sweep/sweep.hpp"

namespace helios::sweep {

namespace fs = std::filesystem;
using io::json;

namespace {

// The sentences of a problem text as [begin, end) spans: from the first character after a
// sentence's end ('.' then white space or the end of the text) to its own '.', skipping comment
// lines ('#' first on the line) and blank space.
std::vector<std::pair<std::size_t, std::size_t>> sentence_spans(const std::string& text) {
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  std::size_t i = 0, begin = std::string::npos;
  bool line_start = true;
  while (i < text.size()) {
    const char ch = text[i];
    if (begin == std::string::npos) {
      if (line_start && ch == '#') {
        i = text.find('\n', i);
        if (i == std::string::npos) break;
        continue;
      }
      if (!std::isspace(static_cast<unsigned char>(ch))) begin = i;
    }
    line_start = ch == '\n';
    if (begin != std::string::npos && ch == '.' &&
        (i + 1 == text.size() || std::isspace(static_cast<unsigned char>(text[i + 1])))) {
      spans.emplace_back(begin, i + 1);
      begin = std::string::npos;
    }
    ++i;
  }
  if (begin != std::string::npos) spans.emplace_back(begin, text.size());
  return spans;
}

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// An objective sentence begins with one of the words the parser reads an objective by.
bool states_an_objective(const std::string& sentence) {
  const std::string s = lower(sentence);
  for (const char* w : {"minimize", "minimise", "maximize", "maximise", "the objective", "minimum ", "the cost"})
    if (s.rfind(w, 0) == 0) return true;
  return false;
}

// A spec without what a boundary changes: the objective, the final time, the source file.
json without_objective_and_time(json spec) {
  spec.erase("objective");
  spec.erase("producer");
  spec["problem"].erase("source_file");
  json& t = spec["time"];
  for (const char* k : {"final_time", "tof_days", "tof_min_days", "tof_max_days"}) t.erase(k);
  return spec;
}

}  // namespace

std::string boundary_name(double departure_mjd2000) {
  return "b" + number_text(departure_mjd2000);
}

std::string boundary_problem(const SweepGrid& grid, const std::string& template_text,
                             const std::string& template_source, double departure_mjd2000) {
  const std::string where = template_source + ": the sweep's boundary (its minimum-time form): ";
  std::vector<std::pair<std::size_t, std::size_t>> tof, objective;
  for (const auto& span : sentence_spans(template_text)) {
    const std::string sentence = template_text.substr(span.first, span.second - span.first);
    if (sentence.find(kTofPlaceholder) != std::string::npos) tof.push_back(span);
    if (states_an_objective(sentence)) objective.push_back(span);
  }
  if (tof.size() != 1)
    throw input_error(where + "the template must hold " + kTofPlaceholder + " in exactly one sentence (it does in " +
                      std::to_string(tof.size()) + ")");
  if (objective.size() != 1)
    throw input_error(where + "the template must state its objective in exactly one sentence (found " +
                      std::to_string(objective.size()) + "); or set \"boundary\": false in sweep.json");
  std::string text = template_text;
  std::vector<std::pair<std::pair<std::size_t, std::size_t>, std::string>> edits = {
      {tof[0], "The time of flight is free, between " + number_text(grid.boundary_tof_min_days) + " days and " +
                   number_text(grid.boundary_tof_max_days) + " days."},
      {objective[0], "Minimize the time of flight."}};
  std::sort(edits.begin(), edits.end(), [](const auto& a, const auto& b) { return a.first.first > b.first.first; });
  for (const auto& [span, with] : edits) text.replace(span.first, span.second - span.first, with);
  for (std::size_t at = 0; (at = text.find(kDeparturePlaceholder, at)) != std::string::npos;)
    text.replace(at, std::string(kDeparturePlaceholder).size(), number_text(departure_mjd2000));

  // The boundary must be its row's cells' problem (the first one's, which must state its own
  // values) but for its objective and time of flight, at the row's epoch.
  const double first_tof = grid.tofs_days.front();
  const json cell = spec::parse_problem_text(cell_problem(template_text, template_source, departure_mjd2000, first_tof),
                                             template_source);
  check_cell_problem(cell, template_source, cell_name(departure_mjd2000, first_tof), departure_mjd2000, first_tof);
  const json boundary = spec::parse_problem_text(text, template_source + " (boundary form)");
  check_cell_problem(boundary, template_source, boundary_name(departure_mjd2000), departure_mjd2000, std::nullopt);
  if (boundary.at("objective").value("kind", "") != "minimum_time" ||
      boundary.at("time").value("final_time", "") != "free" ||
      without_objective_and_time(boundary) != without_objective_and_time(cell))
    throw input_error(where + "replacing the objective sentence and the time of flight changed more than those: " +
                      "set \"boundary\": false in sweep.json");
  return text;
}

json boundary_settings(const json& sweep_settings) {
  json s = sweep_settings;
  s.erase("search_starts");
  s.erase("max_attempts");
  return s;
}

std::string write_sweep_boundary(const SweepGrid& grid, const std::string& template_text,
                                 const std::string& template_source, const json& sweep_settings,
                                 const std::string& dir) {
  std::string fragment =
      "# Written by helios-score --sweep-boundary from " + template_source + "'s sweep: do not edit.\n";
  fragment += "SWEEP_BOUNDARY :=";
  if (grid.boundary) {
    const std::string settings = boundary_settings(sweep_settings).dump(2) + "\n";
    for (const double d : grid.departures_mjd2000) {
      const std::string problem = boundary_problem(grid, template_text, template_source, d);
      io::write_text_if_changed((fs::path(dir) / boundary_name(d) / "problem.txt").string(), problem);
      io::write_text_if_changed((fs::path(dir) / boundary_name(d) / "settings.json").string(), settings);
      fragment += " " + boundary_name(d);
    }
  }
  return fragment + "\n";
}

Boundary read_boundary(const SweepGrid& grid, const std::string& dir, double departure_mjd2000) {
  Boundary b;
  if (!grid.boundary) return b;
  const fs::path path = fs::path(dir) / boundary_name(departure_mjd2000) / "solution.json";
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    b.status = "missing";
    return b;
  }
  const json s = checked_solution(path.string(), boundary_name(departure_mjd2000), departure_mjd2000, std::nullopt);
  b.status = s.value("status", "unknown");
  if (b.status != "converged") return b;
  if (!s.contains("tof_days") || !s.at("tof_days").is_number())
    throw input_error(path.string() + ": field /tof_days: missing in a converged solution");
  b.t_min_days = s.at("tof_days").get<double>();
  if (s.contains("search") && s.at("search").is_object()) {
    const json& search = s.at("search");
    b.saturated = search.value("saturated", false);
    b.starts = search.value("starts", 0);
    if (search.contains("extremals") && search.at("extremals").is_array())
      b.extremals = static_cast<int>(search.at("extremals").size());
  }
  return b;
}

bool below_boundary(const Boundary& b, double tof_days) {
  return b.status == "converged" && solve::beyond_bound(b.t_min_days, tof_days);
}

}  // namespace helios::sweep

// The catalogue of terms (helios/pmp/catalogue.hpp): the entries of every file of pmp/terms, and
// what the schemas and the derivation prompt make of them.
#include "helios/pmp/catalogue.hpp"

#include <algorithm>

namespace helios::pmp {

namespace catalogue {
// Every file's entries, in no order: defined by the list the build generates from pmp/terms/*.cpp.
std::vector<TermEntry> all_files();
}  // namespace catalogue

const std::vector<TermEntry>& term_catalogue() {
  static const std::vector<TermEntry> entries = [] {
    std::vector<TermEntry> out = catalogue::all_files();
    std::stable_sort(out.begin(), out.end(), [](const TermEntry& a, const TermEntry& b) {
      if (a.kind != b.kind) return a.kind == "force";
      return a.order < b.order;
    });
    return out;
  }();
  return entries;
}

const TermEntry* find_term(const std::string& name) {
  for (const auto& e : term_catalogue())
    if (e.name == name) return &e;
  return nullptr;
}

const TermEntry* find_perturbation(const std::string& spec_kind) {
  for (const auto& e : term_catalogue())
    if (!e.spec_kind.empty() && e.spec_kind == spec_kind) return &e;
  return nullptr;
}

const TermParameter* find_typeset_parameter(const std::string& name) {
  for (const auto& e : term_catalogue())
    for (const auto& q : e.parameters)
      if (q.name == name && !q.symbol_base.empty()) return &q;
  return nullptr;
}

std::vector<std::size_t> parameter_counts(const TermEntry& entry) {
  if (entry.required == entry.parameters.size()) return {entry.required};
  return {entry.required, entry.parameters.size()};
}

io::json perturbation_schema() {
  io::json kinds = io::json::array(), branches = io::json::array();
  for (const auto& e : term_catalogue()) {
    if (e.spec_kind.empty()) continue;
    kinds.push_back(e.spec_kind);
    branches.push_back({{"if", {{"required", {"kind"}}, {"properties", {{"kind", {{"const", e.spec_kind}}}}}}},
                        {"then", e.spec_schema}});
  }
  return {{"type", "object"},
          {"description", "a force beyond the central body's gravity and the propulsion, one term of the catalogue"},
          {"required", {"kind"}},
          {"properties", {{"kind", {{"enum", kinds}}}}},
          {"allOf", branches}};
}

io::json term_name_enum() {
  io::json names = io::json::array();
  for (const auto& e : term_catalogue()) names.push_back(e.name);
  return {{"enum", names}};
}

std::string term_catalogue_text() {
  std::string out;
  for (const auto& e : term_catalogue()) {
    std::string list;
    for (std::size_t i = 0; i < e.parameters.size(); ++i) {
      if (i == e.required) list += "[";
      list += (i ? ", " : "") + e.parameters[i].name;
    }
    if (e.required < e.parameters.size()) list += "]";
    out += "- " + e.name + " [" + list + "] (" + e.kind + "): " + e.summary + "\n";
  }
  return out;
}

}  // namespace helios::pmp

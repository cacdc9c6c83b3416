// Reads the derivation's "terms" listing into typed entries, refusing what a reader cannot use.
#include "helios/derivation/terms.hpp"

#include "helios/io/error.hpp"
#include "helios/pmp/catalogue.hpp"

namespace helios::derivation {
namespace {

using io::json;

// The names, separated by ", ".
std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The strings of the array field `key` of `entry` (empty when it is absent).
std::vector<std::string> strings(const json& entry, const std::string& key, const std::string& at) {
  std::vector<std::string> out;
  if (!entry.contains(key)) return out;
  if (!entry[key].is_array()) throw helios::input_error(at + "." + key + ": not an array");
  for (const auto& s : entry[key]) {
    if (!s.is_string()) throw helios::input_error(at + "." + key + ": " + s.dump() + " is not a string");
    out.push_back(s.get<std::string>());
  }
  return out;
}

Term read_term(const json& entry, const std::string& at) {
  if (!entry.is_object()) throw helios::input_error(at + ": not an object");
  const auto text = [&](const std::string& key) {
    if (!entry.contains(key)) return std::string();
    if (!entry[key].is_string())
      throw helios::input_error(at + "." + key + ": " + entry[key].dump() + " is not a string");
    return entry[key].get<std::string>();
  };
  Term t;
  t.name = text("name");
  t.kind = text("kind");
  const pmp::TermEntry* known = pmp::find_term(t.name);
  if (!known)
    throw helios::input_error(at + ".name: unknown term '" + t.name + "' (known: " + join(force_term_names()) + ", " +
                              join(cost_term_names()) + ")");
  if (t.kind != known->kind)
    throw helios::input_error(at + ".kind: '" + t.kind + "', but " + t.name + " is a " + known->kind);
  t.parameters = strings(entry, "parameters", at);
  t.label = text("label");
  t.acceleration = strings(entry, "acceleration", at);
  t.body = text("body");
  for (const auto& field : known->details)
    if (!entry.contains(field))
      throw helios::input_error(at + "." + field + ": a " + t.name + " term lists its " + field);
  if (entry.contains("acceleration") && t.acceleration.size() != 3)
    throw helios::input_error(at + ".acceleration: a user acceleration needs its three normalized components");
  return t;
}

// The names of the catalogue's terms of `kind`.
std::vector<std::string> names_of(const std::string& kind) {
  std::vector<std::string> out;
  for (const auto& e : pmp::term_catalogue())
    if (e.kind == kind) out.push_back(e.name);
  return out;
}

}  // namespace

const std::vector<std::string>& force_term_names() {
  static const std::vector<std::string> names = names_of("force");
  return names;
}

const std::vector<std::string>& cost_term_names() {
  static const std::vector<std::string> names = names_of("cost");
  return names;
}

std::optional<std::vector<Term>> read_terms(const json& derivation, const std::string& where) {
  if (!derivation.is_object() || !derivation.contains("terms")) return std::nullopt;
  const json& list = derivation["terms"];
  if (!list.is_array()) throw helios::input_error(where + ": field terms: not an array");
  std::vector<Term> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(read_term(list[i], where + ": field terms[" + std::to_string(i) + "]"));
  return out;
}

std::string term_names(const std::vector<Term>& terms) {
  std::vector<std::string> names;
  for (const auto& t : terms) names.push_back(t.name);
  return join(names);
}

}  // namespace helios::derivation

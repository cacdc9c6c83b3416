// The catalogue of terms (helios/pmp/catalogue.hpp) is the one description of every term: the
// schemas, the derivation prompt and the verifier are held to it here. With HELIOS_WRITE_CATALOGUE=1
// (`make catalogue`) the schema test rewrites the schemas' catalogue parts instead of comparing them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <string>

#include "../../tools/lib/src/verify/terms/recompute.hpp"  // the verifier's recomputations (internal)
#include "helios/derivation/terms.hpp"
#include "helios/io/json_io.hpp"
#include "helios/pmp/catalogue.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/spec/parse.hpp"
#include "helios/verify/verify.hpp"

namespace {

using helios::io::json;
using helios::pmp::term_catalogue;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The end of the JSON value that starts at `begin` of `text` (an object or an array).
std::size_t value_end(const std::string& text, std::size_t begin) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = begin; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\')
        ++i;
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '{' || ch == '[') {
      ++depth;
    } else if ((ch == '}' || ch == ']') && --depth == 0) {
      return i + 1;
    }
  }
  throw std::runtime_error("unbalanced JSON");
}

// `value` printed compactly, with a space after each separator as the schemas write it.
std::string compact(const json& value) {
  const std::string printed = value.dump();
  std::string out;
  bool in_string = false;
  for (std::size_t i = 0; i < printed.size(); ++i) {
    const char ch = printed[i];
    out += ch;
    if (in_string) {
      if (ch == '\\')
        out += printed[++i];
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == ':' || ch == ',') {
      out += ' ';
    }
  }
  return out;
}

// An object over lines indented by `indent`, one key a line, an array of objects one element a line.
std::string over_lines(const json& object, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string out = "{";
  bool first = true;
  for (const auto& [key, value] : object.items()) {
    out += std::string(first ? "" : ",") + "\n" + pad + "  " + compact(key) + ": ";
    first = false;
    if (value.is_array() && !value.empty() && value[0].is_object()) {
      out += "[";
      for (std::size_t i = 0; i < value.size(); ++i)
        out += std::string(i ? "," : "") + "\n" + pad + "    " + compact(value[i]);
      out += "\n" + pad + "  ]";
    } else {
      out += compact(value);
    }
  }
  return out + "\n" + pad + "}";
}

// `text` with the value after the one occurrence of `key` replaced by `value`, printed compactly
// (`indent` < 0) or over lines indented by `indent`.
std::string spliced(const std::string& text, const std::string& key, const json& value, int indent) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos || text.find(key, at + 1) != std::string::npos)
    throw std::runtime_error("the key " + key + " is not in the schema exactly once");
  const std::size_t begin = at + key.size(), end = value_end(text, begin);
  return text.substr(0, begin) + (indent < 0 ? compact(value) : over_lines(value, indent)) + text.substr(end);
}

// The schema `file` as the catalogue makes its part at `key`; rewritten in place with
// HELIOS_WRITE_CATALOGUE=1.
void expect_catalogue_part(const std::string& file, const std::string& key, const json& value, int indent) {
  const std::string path = HELIOS_SOURCE_DIR "/" + file;
  const std::string text = helios::io::read_text(path), wanted = spliced(text, key, value, indent);
  const char* write = std::getenv("HELIOS_WRITE_CATALOGUE");
  if (write && std::string(write) == "1") {
    if (wanted != text) helios::io::write_text_atomic(path, wanted);
    return;
  }
  EXPECT_EQ(text, wanted) << file << " is not the catalogue's: run `make catalogue` to rewrite its part " << key;
}

TEST(Catalogue, TheSchemasAreWrittenFromIt) {
  expect_catalogue_part("schemas/spec.schema.json", "\n    \"perturbation\": ", helios::pmp::perturbation_schema(), 4);
  expect_catalogue_part("schemas/derivation.schema.json", "\n          \"name\": ", helios::pmp::term_name_enum(), -1);
}

TEST(Catalogue, NamesAreUniqueAndEveryForceHasItsRecomputationAndBuilder) {
  std::set<std::string> names, kinds, files_building;
  for (const auto& e : term_catalogue()) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name << " is in the catalogue twice";
    EXPECT_TRUE(e.kind == "force" || e.kind == "cost") << e.name;
    EXPECT_FALSE(e.summary.empty()) << e.name;
    EXPECT_LE(e.required, e.parameters.size()) << e.name;
    if (e.kind != "force") continue;
    EXPECT_NE(helios::verify::detail::recompute::find(e.name), nullptr)
        << "the force " << e.name << " has no recomputation in tools/lib/src/verify/terms/";
    if (!e.spec_kind.empty()) {
      EXPECT_TRUE(kinds.insert(e.spec_kind).second) << "two terms are built from the perturbation " << e.spec_kind;
      EXPECT_EQ(e.spec_schema["properties"]["kind"]["const"], e.spec_kind) << e.name;
      EXPECT_NE(e.build, nullptr) << e.name << " is built from the spec's perturbations but has no builder";
    }
  }
  // The derivation's reader knows exactly the catalogue's names.
  std::set<std::string> read(helios::derivation::force_term_names().begin(),
                             helios::derivation::force_term_names().end());
  read.insert(helios::derivation::cost_term_names().begin(), helios::derivation::cost_term_names().end());
  EXPECT_EQ(read, names);
}

// The derivation prompt lists the catalogue where it says {{TERM_CATALOGUE}}: every term with its
// parameters; verify's feedback to a derivation that lists none names them all.
TEST(Catalogue, ThePromptAndVerifyNameEveryTerm) {
  const std::string prompt = helios::io::read_text(HELIOS_SOURCE_DIR "/prompts/pmp_derive.txt");
  EXPECT_TRUE(contains(prompt, "{{TERM_CATALOGUE}}"));
  const std::string text = helios::pmp::term_catalogue_text();
  json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
      helios::io::read_text(HELIOS_SOURCE_DIR "/scenarios/S01/problem.txt"), "problem.txt"));
  d.erase("terms");
  std::string told;
  const json report = helios::verify::verify_derivation(d, {});
  for (const auto& c : report["checks"])
    if (c["id"] == "dynamics_terms") told = c.value("feedback", "");
  for (const auto& e : term_catalogue()) {
    std::string listed = "- " + e.name + " [";
    if (!e.parameters.empty() && e.required > 0) listed += e.parameters[0].name;
    EXPECT_TRUE(contains(text, listed)) << text;
    EXPECT_TRUE(contains(told, e.name)) << "verify's feedback does not name the term " << e.name;
  }
  EXPECT_TRUE(contains(text, "- solar_electric_thrust [P0, Pbus, eta, c[, Pmax, Pw]] (force)")) << text;
}

// The derivation lists each force's parameters as the catalogue counts them, with their roles.
TEST(Catalogue, TheBuiltinDerivationsListTheCataloguesParameters) {
  for (const char* scenario : {"S01", "S05", "S10", "S15"}) {
    const json d = helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
        helios::io::read_text(HELIOS_SOURCE_DIR "/scenarios/" + std::string(scenario) + "/problem.txt"),
        "problem.txt"));
    for (const auto& t : d["terms"]) {
      const auto* e = helios::pmp::find_term(t["name"]);
      ASSERT_NE(e, nullptr) << t.dump();
      if (e->kind != "force") continue;
      const auto counts = helios::pmp::parameter_counts(*e);
      EXPECT_TRUE(std::find(counts.begin(), counts.end(), t["parameters"].size()) != counts.end()) << t.dump();
      for (std::size_t i = 0; i < t["parameters"].size(); ++i) {
        const std::string role = e->parameters[i].role;
        if (role.empty()) continue;
        bool found = false;
        for (const auto& q : d["parameters"])
          if (q["name"] == t["parameters"][i]) found = q.value("role", "") == role;
        EXPECT_TRUE(found) << scenario << ": " << t["parameters"][i] << " is not the " << role;
      }
    }
  }
}

}  // namespace

#include "helios/io/schema.hpp"

#include <map>
#include <memory>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "helios/io/embedded.hpp"
#include "helios/io/error.hpp"

namespace helios::io {
namespace {

const valijson::Schema& schema_for(const std::string& kind) {
  static std::map<std::string, std::unique_ptr<valijson::Schema>> cache;
  auto& slot = cache[kind];
  if (!slot) {
    // valijson's adapter wants nlohmann::json (unordered); key order is irrelevant to a schema.
    static std::map<std::string, nlohmann::json> documents;
    nlohmann::json& doc = documents[kind] = nlohmann::json::parse(embedded::file("schemas/" + kind + ".schema.json"));
    slot = std::make_unique<valijson::Schema>();
    valijson::SchemaParser parser;
    valijson::adapters::NlohmannJsonAdapter adapter(doc);
    parser.populateSchema(adapter, *slot);
  }
  return *slot;
}

}  // namespace

const std::vector<std::string>& artifact_kinds() {
  static const std::vector<std::string> kinds = {"spec",  "derivation", "verify",    "solution",
                                                 "score", "compile",    "transcript"};
  return kinds;
}

void validate(const std::string& kind, const json& doc, const std::string& source) {
  const nlohmann::json plain = nlohmann::json::parse(doc.dump());
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter target(plain);
  if (validator.validate(schema_for(kind), target, &results)) return;
  // The deepest error is the most specific; at equal depth, an error saying what is wrong beats
  // one that only reports a failed combinator (if/then/else, oneOf).
  const auto generic = [](const std::string& d) { return d.rfind("Failed to validate against", 0) == 0; };
  valijson::ValidationResults::Error error, last;
  bool have = false;
  while (results.popError(error)) {
    const bool deeper = !have || error.context.size() > last.context.size();
    const bool better_same_depth =
        have && error.context.size() == last.context.size() && generic(last.description) && !generic(error.description);
    if (deeper || better_same_depth) last = error;
    have = true;
  }
  // valijson names the location as "<root>", "[constraints]", "[1]", ...: print a JSON pointer.
  std::string where;
  for (const auto& part : last.context) {
    if (part == "<root>") continue;
    const bool bracketed = part.size() >= 2 && part.front() == '[' && part.back() == ']';
    where += "/" + (bracketed ? part.substr(1, part.size() - 2) : part);
  }
  // A missing property is named by its own path, so the message points at the field to add.
  const std::string missing = "Missing required property '";
  if (last.description.rfind(missing, 0) == 0) {
    const std::string key =
        last.description.substr(missing.size(), last.description.find('\'', missing.size()) - missing.size());
    throw input_error(source + ": " + kind + " schema violation at " + where + "/" + key +
                      ": required field is missing");
  }
  if (where.empty()) where = "/";
  throw input_error(source + ": " + kind + " schema violation at " + where + ": " + last.description);
}

std::vector<std::string> schema_properties(const std::string& kind) {
  // ordered_json keeps the schema's own order, so error messages list the keys as documented.
  const auto doc = nlohmann::ordered_json::parse(embedded::file("schemas/" + kind + ".schema.json"));
  std::vector<std::string> names;
  for (const auto& [name, property] : doc.at("properties").items()) names.push_back(name);
  return names;
}

namespace {

// A JSON value as an error message shows it: one line, at most 80 characters.
std::string printable_json(const json& value) {
  const std::string text = value.dump(-1, ' ', true, json::error_handler_t::replace);
  return text.size() > 80 ? text.substr(0, 80) + "..." : text;
}

}  // namespace

json read_artifact(const std::string& kind, const std::string& path) {
  return parse_artifact(kind, read_text(path), path == "-" ? "<stdin>" : path);
}

json parse_artifact(const std::string& kind, const std::string& text, const std::string& name) {
  json doc = parse_json_text(text, name);
  const auto field = [&](const char* key) -> const json* {
    if (!doc.is_object()) return nullptr;
    const auto it = doc.find(key);
    return it == doc.end() ? nullptr : &*it;
  };
  const auto shown = [](const json* value) { return value ? printable_json(*value) : std::string("missing"); };
  const json* schema = field("schema");
  if (!doc.is_object() || !schema || *schema != "helios/" + kind)
    throw input_error(name + ": field /schema is " + (doc.is_object() ? shown(schema) : "absent (not a JSON object)") +
                      ", expected \"helios/" + kind + "\" (wrong artifact for this tool?)");
  const json* version = field("schema_version");
  if (!version || *version != kSchemaVersion)
    throw input_error(name + ": field /schema_version is " + shown(version) + ", this build reads version " +
                      std::to_string(kSchemaVersion));
  validate(kind, doc, name);
  return doc;
}

void write_artifact(const std::string& kind, const json& doc, const std::string& path) {
  validate(kind, doc, "output " + kind);
  write_json_atomic(path, doc);
}

json artifact_header(const std::string& kind, const std::string& tool, const std::string& backend) {
  json header = json::object();
  header["schema"] = "helios/" + kind;
  header["schema_version"] = kSchemaVersion;
  header["producer"] = {{"tool", tool}, {"version", HELIOS_VERSION}, {"backend", backend}};
  return header;
}

}  // namespace helios::io

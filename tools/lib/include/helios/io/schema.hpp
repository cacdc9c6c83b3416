#pragma once
// Validation of artifacts against schemas/<kind>.schema.json (embedded at build time).
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::io {

constexpr int kSchemaVersion = 1;

// Every artifact kind the chain knows: spec, derivation, verify, solution, score, compile, transcript.
const std::vector<std::string>& artifact_kinds();

// Validates `doc` against the schema of `kind`. On failure throws input_error
// "<source>: <kind> schema violation at <json path>: <reason>". `source` names the file.
void validate(const std::string& kind, const json& doc, const std::string& source);

// The property names of the schema of `kind` (its top-level "properties"), in the schema's order:
// for a kind whose schema is the one list of its keys (settings).
std::vector<std::string> schema_properties(const std::string& kind);

// Reads `path`, validates it as `kind` (including schema name and version) and returns it.
json read_artifact(const std::string& kind, const std::string& path);
// The same for the text of a document, `name` naming it in errors (read_artifact's reading).
json parse_artifact(const std::string& kind, const std::string& text, const std::string& name);

// Validates `doc` as `kind` and writes it atomically to `path`.
void write_artifact(const std::string& kind, const json& doc, const std::string& path);

// The self-description every artifact starts with: schema, schema_version, producer.
json artifact_header(const std::string& kind, const std::string& tool, const std::string& backend);

}  // namespace helios::io

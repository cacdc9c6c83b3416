#include "helios/llm/backend.hpp"

#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "helios/codegen/generate.hpp"
#include "helios/io/embedded.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/pmp/catalogue.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/pmp/model.hpp"
#include "helios/verify/verify.hpp"

namespace helios::llm {
namespace {

using io::json;

const char* const kModules[] = {"DYNAMICS", "SWITCH", "RESIDUAL", "SOLVE"};
const std::string kModuleMarker = "// ===== HELIOS LLM MODULE: ";
const std::string kModulesEnd = "// ===== HELIOS LLM MODULES END =====";
const std::string kOpen = "namespace helios_rt {\n";
const std::string kClose = "\n}  // namespace helios_rt\n";

Message system_message(const std::string& role) {
  return {"system", "You are the " + role +
                        " of HELIOS, a tool chain for low-thrust trajectory optimization by the indirect method "
                        "(Pontryagin's minimum principle). Follow the instructions exactly. Reply with JSON only, in "
                        "one ```json fence."};
}

// The artifact's own keys: header first, then `body` without any header keys the model wrote.
json with_header(const std::string& kind, const std::string& tool, const std::string& model, const json& body) {
  json doc = io::artifact_header(kind, tool, "llm");
  doc["producer"]["model"] = model;
  for (auto it = body.begin(); it != body.end(); ++it)
    if (it.key() != "schema" && it.key() != "schema_version" && it.key() != "producer") doc[it.key()] = it.value();
  return doc;
}

json reply_object(const std::string& content) {
  json reply = parse_reply_json(content);
  if (!reply.is_object()) throw reply_error("your reply is JSON but not an object; reply with one JSON object");
  return reply;
}

// Schema and readability problems of a candidate artifact become the sentence fed back.
void validate_reply(const std::string& kind, const json& doc) {
  try {
    io::validate(kind, doc, "your reply");
  } catch (const input_error& e) {
    throw reply_error(e.what());
  }
}

void remove_stale(const std::string& path) {
  std::error_code ec;
  if (!path.empty()) std::filesystem::remove(path, ec);
}

std::string pretty(const json& doc) {
  return doc.dump(2);
}

// The derivation as the model wrote it: without the tool's parts.
json model_part(const json& derivation) {
  json out = json::object();
  for (auto it = derivation.begin(); it != derivation.end(); ++it)
    if (it.key() != "schema" && it.key() != "schema_version" && it.key() != "producer" && it.key() != "units" &&
        it.key() != "times" && it.key() != "parameters")
      out[it.key()] = it.value();
  return out;
}

std::string feedback_section(const DeriveRequest& r, int round) {
  if (!r.feedback) return "";
  std::ostringstream out;
  out << "\n## Round " << round << ": the checker rejected your previous derivation\n"
      << "These checks failed. Fix each one, keep what passed, and return the complete corrected derivation:\n";
  for (const auto& c : r.feedback->at("checks"))
    if (c.value("verdict", "") == "fail") out << "- " << c.value("id", "?") << ": " << c.value("feedback", "") << "\n";
  if (r.previous) out << "\nYour previous derivation:\n```json\n" << pretty(model_part(*r.previous)) << "\n```\n";
  return out.str();
}

std::string compiler_errors(const json& report) {
  const std::string all = report.value("diagnostics", "");
  if (all.size() <= 8000) return all;
  // Long output: the error lines carry what a repair needs.
  std::istringstream in(all);
  std::string line, out;
  while (std::getline(in, line) && out.size() < 8000)
    if (line.find("error") != std::string::npos) out += line.substr(0, 500) + "\n";
  return out.empty() ? all.substr(0, 8000) : out;
}

json modules_reply(const std::string& content) {
  json reply = reply_object(content);
  if (!reply.contains("modules") || !reply["modules"].is_object())
    throw reply_error(
        "your reply has no object \"modules\"; reply with {\"modules\": {\"DYNAMICS\": ..., "
        "\"SWITCH\": ..., \"RESIDUAL\": ..., \"SOLVE\": ...}}");
  json modules = json::object();
  for (const char* name : kModules) {
    const json& m = reply["modules"].contains(name) ? reply["modules"][name] : json();
    if (!m.is_string() || m.get<std::string>().find_first_not_of(" \t\r\n") == std::string::npos)
      throw reply_error(std::string("module ") + name + " is missing or empty; give all four modules as JSON strings");
    modules[name] = m;
  }
  for (auto it = reply["modules"].begin(); it != reply["modules"].end(); ++it)
    if (!modules.contains(it.key()))
      throw reply_error("unknown module \"" + it.key() + "\"; the modules are DYNAMICS, SWITCH, RESIDUAL and SOLVE");
  return modules;
}

std::string modules_source(const json& modules) {
  std::string out;
  for (const char* name : kModules)
    out += kModuleMarker + name + " =====\n" + kOpen + modules[name].get<std::string>() + kClose + "\n";
  return out + kModulesEnd + "\n\n";
}

}  // namespace

std::filesystem::path prompts_dir() {
  if (const char* dir = std::getenv("HELIOS_PROMPTS_DIR"); dir && *dir) return dir;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw input_error("cannot locate the llm prompts (/proc/self/exe: " + ec.message() +
                      "); set HELIOS_PROMPTS_DIR to the project's prompts/ folder");
  return exe.parent_path().parent_path() / "share" / "helios" / "prompts";
}

std::string prompt(const std::string& name) {
  const std::filesystem::path path = prompts_dir() / name;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw input_error(path.string() +
                      ": no such prompt (the llm backend reads prompts/ from share/helios/prompts beside "
                      "the tools, or from HELIOS_PROMPTS_DIR)");
  return io::read_text(path.string());
}

std::string fill(std::string text, const std::vector<std::pair<std::string, std::string>>& values) {
  // One pass over the template, so a value that happens to contain "{{X}}" is never expanded.
  std::map<std::string, const std::string*> by_key;
  for (const auto& [key, value] : values) by_key[key] = &value;
  std::set<std::string> used;
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const auto open = text.find("{{", pos);
    const auto close = open == std::string::npos ? std::string::npos : text.find("}}", open + 2);
    if (close == std::string::npos) break;
    const std::string key = text.substr(open + 2, close - open - 2);
    const bool is_key = !key.empty() && key.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ_") == std::string::npos;
    out += text.substr(pos, open - pos);
    if (is_key) {
      const auto it = by_key.find(key);
      if (it == by_key.end()) throw std::logic_error("prompt placeholder {{" + key + "}} has no value");
      out += *it->second;
      used.insert(key);
    } else {
      out += text.substr(open, close + 2 - open);
    }
    pos = close + 2;
  }
  out += text.substr(pos);
  for (const auto& [key, value] : values)
    if (!used.count(key)) throw std::logic_error("prompt has no placeholder {{" + key + "}}");
  return out;
}

CallInfo call_info(const std::string& output, const std::string& transcript, int round) {
  CallInfo c;
  c.round = round;
  if (output == "-" && transcript.empty())
    throw usage_error("--backend llm writing to stdout needs --transcript FILE (every exchange is kept)");
  c.transcript_path = transcript.empty() ? transcript_path_for(output) : transcript;
  c.artifact = output == "-" ? "-" : std::filesystem::path(output).filename().string();
  return c;
}

json parse_problem(const std::string& text, const std::string& source, const CallInfo& call) {
  Client client(Config::from_env());
  Conversation conv(client, {call.transcript_path, "helios-parse", "parse", call.artifact, call.round});
  const std::string user = fill(
      prompt("parse.txt"),
      {{"SPEC_SCHEMA", embedded::file("schemas/spec.schema.json")}, {"SOURCE_FILE", source}, {"PROBLEM_TEXT", text}});
  return conv.ask({system_message("parser"), {"user", user}}, [&](const std::string& content) {
    json spec = with_header("spec", "helios-parse", conv.model(), reply_object(content));
    if (spec.contains("problem") && spec["problem"].is_object()) spec["problem"]["source_file"] = source;
    validate_reply("spec", spec);
    try {
      pmp::build_problem(spec);
    } catch (const std::exception& e) {
      throw reply_error(std::string("the spec cannot be formulated as an optimal control problem: ") + e.what());
    }
    return spec;
  });
}

json normalization(const json& spec) {
  const pmp::Problem p = pmp::build_problem(spec);
  json out;
  out["units"] = pmp::units_of(p);
  out["times"] = pmp::times_of(p);
  json params = json::array();
  for (const auto& n : p.parameters) {
    json e = {{"name", n.name}, {"meaning", n.meaning}, {"unit", n.unit}, {"value", n.value}};
    if (!n.source.empty()) e["source"] = n.source;
    params.push_back(e);
  }
  out["parameters"] = params;
  return out;
}

bool derive_round_done(const DeriveRequest& r) {
  return r.previous && r.feedback && r.feedback->value("verdict", "") == "pass";
}

json derive(const DeriveRequest& r, const CallInfo& call) {
  if (r.feedback && !r.previous) throw usage_error("--feedback needs --previous (the derivation it verified)");
  if (derive_round_done(r)) {
    remove_stale(call.transcript_path);
    return *r.previous;
  }
  const json norm = normalization(r.spec);
  Client client(Config::from_env());
  Conversation conv(client, {call.transcript_path, "helios-derive", "derive", call.artifact, call.round});
  const std::string user =
      fill(prompt("pmp_derive.txt"), {{"DERIVATION_SCHEMA", embedded::file("schemas/derivation.schema.json")},
                                      {"SPEC_JSON", pretty(r.spec)},
                                      {"NORMALIZATION_JSON", pretty(norm)},
                                      {"TERM_CATALOGUE", pmp::term_catalogue_text()},
                                      {"FEEDBACK", feedback_section(r, call.round)}});
  return conv.ask({system_message("deriver"), {"user", user}}, [&](const std::string& content) {
    const json reply = reply_object(content);
    json body = json::object();
    // The schema's order, with the tool's units, times and parameters in their places.
    for (const char* key :
         {"problem", "units", "times", "states", "controls", "parameters", "homotopy", "multiplier", "dynamics",
          "hamiltonian", "state_odes", "costate_odes", "control_law", "initial_values", "constraints", "shooting"}) {
      if (norm.contains(key))
        body[key] = norm[key];
      else if (reply.contains(key))
        body[key] = reply[key];
    }
    for (auto it = reply.begin(); it != reply.end(); ++it)
      if (!body.contains(it.key())) body[it.key()] = it.value();
    json doc = with_header("derivation", "helios-derive", conv.model(), body);
    validate_reply("derivation", doc);
    try {
      verify::verify_derivation(doc, {});
    } catch (const std::exception& e) {
      throw reply_error(std::string("the checker cannot read your derivation: ") + e.what());
    }
    return doc;
  });
}

bool gen_round_done(const GenRequest& r) {
  return r.previous_source && r.compile_report && r.compile_report->value("ok", false);
}

std::string generate(const GenRequest& r, const CallInfo& call) {
  if (r.compile_report && !r.previous_source)
    throw usage_error("--compile-report needs --previous (the program it compiled)");
  if (gen_round_done(r)) {
    remove_stale(call.transcript_path);
    return *r.previous_source;
  }
  const std::string block = codegen::problem_block(r.derivation);
  Client client(Config::from_env());
  const bool repair = r.previous_source.has_value();
  Conversation conv(client,
                    {call.transcript_path, "helios-gen", repair ? "repair" : "codegen", call.artifact, call.round});
  std::vector<Message> messages = {system_message("code generator"),
                                   {"user", fill(prompt("codegen.txt"), {{"DERIVATION_JSON", pretty(r.derivation)},
                                                                         {"PROBLEM_BLOCK", block},
                                                                         {"RUNTIME", codegen::runtime_header()}})}};
  if (repair) {
    if (!r.compile_report) throw usage_error("--previous needs --compile-report (how the previous program compiled)");
    const json previous = modules_of(*r.previous_source);
    messages.push_back({"assistant", "```json\n" + json{{"modules", previous}}.dump(2) + "\n```"});
    messages.push_back({"user", fill(prompt("repair.txt"), {{"ROUND", std::to_string(call.round - 1)},
                                                            {"COMMAND", r.compile_report->value("command", "")},
                                                            {"COMPILER_ERRORS", compiler_errors(*r.compile_report)}})});
  }
  const json modules = conv.ask(messages, [&](const std::string& content) { return modules_reply(content); });
  return codegen::assemble(r.derivation, modules_source(modules), "llm, model " + conv.model());
}

json modules_of(const std::string& source) {
  json out = json::object();
  for (const char* name : kModules) {
    const std::string head = kModuleMarker + name + " =====\n" + kOpen;
    const auto start = source.find(head);
    if (start == std::string::npos)
      throw input_error(std::string("the program has no module ") + name +
                        " marked by this backend; --previous must be a shoot.cpp written by helios-gen --backend llm");
    const auto body = start + head.size();
    const auto end = source.find(kClose + "\n" + kModuleMarker, body);
    const auto last = source.find(kClose + "\n" + kModulesEnd, body);
    const auto stop = std::min(end, last);
    if (stop == std::string::npos) throw input_error(std::string("the program's module ") + name + " is not closed");
    out[name] = source.substr(body, stop - body);
  }
  return out;
}

}  // namespace helios::llm

#pragma once
// The llm backend of helios-parse, helios-derive and helios-gen: prompts
// from prompts/, a conversation per artifact with its transcript, replies schema-checked, and the
// refinement rounds (derive <-> verify, gen <-> compile) one round per call.
#include <filesystem>
#include <optional>
#include <string>

#include "helios/io/json_io.hpp"
#include "helios/llm/conversation.hpp"

namespace helios::llm {

// Where the prompts are read from: HELIOS_PROMPTS_DIR when set, else share/helios/prompts beside
// the tools' bin/ (the build copies prompts/ there). They are data, not compiled in, so editing a
// prompt changes no tool's bytes and re-runs only the llm backend's rules.
std::filesystem::path prompts_dir();

// The text of the prompt NAME (e.g. "parse.txt") in prompts_dir(); input_error when it is missing.
std::string prompt(const std::string& name);

// Replaces every {{KEY}} of `text`; throws std::logic_error for a key the text lacks or a
// placeholder left unfilled.
std::string fill(std::string text, const std::vector<std::pair<std::string, std::string>>& values);

// Where a call's transcript goes and which round it is.
struct CallInfo {
  std::string transcript_path;  // empty: none
  std::string artifact;         // file name of the artifact
  int round = 1;
};

// The call of a tool writing `output` (- = stdout): the transcript goes to `transcript` if given,
// else next to the output (transcript_path_for). Throws usage_error for -o - without a transcript.
CallInfo call_info(const std::string& output, const std::string& transcript, int round);

// helios-parse --backend llm: problem text -> spec artifact (header with producer.model).
io::json parse_problem(const std::string& text, const std::string& source, const CallInfo& call);

struct DeriveRequest {
  io::json spec;
  std::optional<io::json> previous;  // derivation of the round before
  std::optional<io::json> feedback;  // its verify report
};

// True when a round needs no model call: the previous round passed verification (its
// derivation is then the answer, unchanged).
bool derive_round_done(const DeriveRequest& request);

// The normalized units, times and parameters of a spec (the tool's part of a derivation).
io::json normalization(const io::json& spec);

// helios-derive --backend llm, one round: spec (+ previous derivation and its verify feedback)
// -> derivation artifact. The previous derivation when derive_round_done().
io::json derive(const DeriveRequest& request, const CallInfo& call);

struct GenRequest {
  io::json derivation;
  std::optional<std::string> previous_source;  // shoot.cpp of the round before
  std::optional<io::json> compile_report;      // its compile report
};

bool gen_round_done(const GenRequest& request);

// helios-gen --backend llm, one round: derivation (+ the previous program and its compile report)
// -> shoot.cpp. The previous program, unchanged, when gen_round_done().
std::string generate(const GenRequest& request, const CallInfo& call);

// The four modules of a program this backend assembled, as {"DYNAMICS": ..., ...}; throws
// input_error when the markers are missing.
io::json modules_of(const std::string& source);

}  // namespace helios::llm

#include "helios/llm/conversation.hpp"

#include <filesystem>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"

namespace helios::llm {
namespace {

using io::json;

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// Text of the first fence opened by `opener` (e.g. "```json"), or npos-marked empty optional.
bool fenced(const std::string& content, const std::string& opener, std::string& out) {
  std::size_t pos = 0;
  while ((pos = content.find(opener, pos)) != std::string::npos) {
    const std::size_t line_end = content.find('\n', pos);
    if (line_end == std::string::npos) return false;
    // "```json" must end the opener line (not "```jsonc" etc. when opener is "```json").
    const std::string rest = trimmed(content.substr(pos + opener.size(), line_end - pos - opener.size()));
    if (!rest.empty() && opener != "```") {
      pos = line_end;
      continue;
    }
    const std::size_t close = content.find("```", line_end + 1);
    out = content.substr(line_end + 1, close == std::string::npos ? std::string::npos : close - line_end - 1);
    return true;
  }
  return false;
}

// What is sent back of a reply that could not be used: all of it up to kMaxEchoBytes, else its
// start (cut between characters) and a note. The same reply gives the same text, so a replay asks
// what was asked.
std::string echo_of(const std::string& content) {
  if (content.size() <= kMaxEchoBytes) return content;
  const std::string note =
      "\n[... the rest of this reply is not repeated: " + std::to_string(content.size()) + " bytes in all]";
  std::size_t cut = kMaxEchoBytes - note.size();
  while (cut > 0 && (static_cast<unsigned char>(content[cut]) & 0xC0) == 0x80) --cut;
  return content.substr(0, cut) + note;
}

json usage_json(const Usage& u) {
  return {
      {"prompt_tokens", u.prompt_tokens}, {"completion_tokens", u.completion_tokens}, {"total_tokens", u.total_tokens}};
}

json turn_json(const Exchange& x, const std::string& outcome, const std::string& error) {
  json t;
  t["request"] = x.request;
  t["request_sha256"] = x.request_sha256;
  if (x.http_status == 200)
    t["reply"] = {{"content", x.content}, {"model", x.reply_model}, {"finish_reason", x.finish_reason}};
  else
    t["reply"] = nullptr;
  t["usage"] = usage_json(x.usage);
  t["latency_s"] = x.latency_s;
  t["http_status"] = x.http_status;
  json attempts = json::array();
  for (std::size_t i = 0; i < x.attempts.size(); ++i) {
    const Attempt& a = x.attempts[i];
    attempts.push_back({{"attempt", static_cast<int>(i) + 1},
                        {"http_status", a.http_status},
                        {"error", a.error},
                        {"latency_s", a.latency_s},
                        {"wait_s", a.wait_s}});
  }
  t["attempts"] = attempts;
  t["replayed"] = x.replayed;
  t["outcome"] = outcome;
  t["error"] = error;
  return t;
}

}  // namespace

std::string extract_json_text(const std::string& content) {
  std::string out;
  if (fenced(content, "```json", out) || fenced(content, "```JSON", out) || fenced(content, "```", out))
    return trimmed(out);
  const auto open = content.find('{');
  const auto close = content.rfind('}');
  if (open != std::string::npos && close != std::string::npos && close > open)
    return content.substr(open, close - open + 1);
  return trimmed(content);
}

json parse_reply_json(const std::string& content) {
  const std::string text = extract_json_text(content);
  if (text.empty()) throw reply_error("your reply is empty; reply with one JSON object in a ```json fence");
  if (io::json_depth_exceeded_at(text, io::kMaxJsonDepth) != std::string::npos)
    throw reply_error("your reply nests JSON deeper than " + std::to_string(io::kMaxJsonDepth) +
                      " levels; reply with the artifact's JSON object as its schema shapes it");
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw reply_error("your reply is not valid JSON (parse error at byte " + std::to_string(e.byte) +
                      " of the ```json block); reply with one complete JSON object in a ```json fence");
  }
}

Conversation::Conversation(Client& client, TranscriptInfo info)
    : client_(client), info_(std::move(info)), model_(client.config().model) {}

json Conversation::transcript() const {
  const std::string key = client_.config().api_key;
  json doc = io::artifact_header("transcript", info_.tool, "llm");
  doc["producer"]["model"] = model_.empty() ? std::string("unknown") : model_;
  doc["purpose"] = info_.purpose;
  doc["artifact"] = info_.artifact;
  doc["round"] = info_.round;
  doc["endpoint"] = client_.config().replay_dir.empty() ? client_.config().endpoint() : "replay";
  doc["outcome"] = failed_ ? "failed" : "accepted";
  Usage sum;
  double latency = 0;
  for (const auto& t : turns_) {
    sum.prompt_tokens += t["usage"]["prompt_tokens"].get<long>();
    sum.completion_tokens += t["usage"]["completion_tokens"].get<long>();
    sum.total_tokens += t["usage"]["total_tokens"].get<long>();
    latency += t["latency_s"].get<double>();
  }
  doc["usage"] = usage_json(sum);
  doc["latency_s"] = latency;
  doc["turns"] = turns_;
  // NOTE: the key is never put into a transcript; this guards against an endpoint echoing it.
  if (!key.empty()) doc = json::parse(redact(doc.dump(), key));
  return doc;
}

void Conversation::write() const {
  if (info_.path.empty()) return;
  io::write_artifact("transcript", transcript(), info_.path);
}

json Conversation::ask(std::vector<Message> messages, const ReplyCheck& check) {
  const int max_turns = client_.config().max_turns;
  std::string last_error;
  for (int turn = 1; turn <= max_turns; ++turn) {
    Exchange x;
    try {
      x = client_.chat(messages, &x, client_.config().reply_limit_bytes - received_);
    } catch (const std::exception&) {
      turns_.push_back(turn_json(x, "failed", "no reply"));
      failed_ = true;
      write();
      throw;
    }
    received_ += x.reply_bytes;
    if (!x.reply_model.empty()) model_ = x.reply_model;
    try {
      json accepted = check(x.content);
      turns_.push_back(turn_json(x, "accepted", ""));
      failed_ = false;
      write();
      return accepted;
    } catch (const reply_error& e) {
      last_error = e.what();
      turns_.push_back(turn_json(x, "rejected", last_error));
      messages.push_back({"assistant", echo_of(x.content)});
      messages.push_back({"user", "Your reply could not be used: " + last_error +
                                      ". Reply again with the complete corrected JSON object only, in one ```json "
                                      "fence."});
    }
  }
  failed_ = true;
  write();
  throw input_error("no usable reply from model " + model_ + " in " + std::to_string(max_turns) +
                    " turns (HELIOS_LLM_MAX_TURNS), last: " + last_error +
                    (info_.path.empty() ? std::string() : ", see " + info_.path));
}

std::string transcript_path_for(const std::string& artifact_path) {
  const std::filesystem::path p(artifact_path);
  return (p.parent_path() / (p.stem().string() + ".transcript.json")).string();
}

}  // namespace helios::llm

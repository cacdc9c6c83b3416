#pragma once
// A conversation with the model about one artifact: ask, check the reply, feed a malformed reply
// back with the error, and keep every exchange in a transcript (schemas/transcript.schema.json)
// written next to the artifact, with token usage and latency and never the API key.
#include <functional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/llm/client.hpp"

namespace helios::llm {

// A reply that cannot be used; what() is the sentence fed back to the model.
struct reply_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The most of a reply that could not be used that is sent back to the model with the error (and
// so into each later request): its start and a note beyond it (tools/lib/src/llm/README.md, "Limits").
inline constexpr std::size_t kMaxEchoBytes = std::size_t{256} << 10;

// The JSON text of a reply: the first ```json fence, else the first ``` fence, else the text from
// the first '{' to the last '}', else the whole reply.
std::string extract_json_text(const std::string& content);

// extract_json_text + parse; throws reply_error "your reply is not valid JSON: ..." otherwise.
io::json parse_reply_json(const std::string& content);

// Takes the reply text and returns the accepted value, or throws reply_error.
using ReplyCheck = std::function<io::json(const std::string& content)>;

struct TranscriptInfo {
  std::string path;      // where to write it; empty: no transcript
  std::string tool;      // helios-derive
  std::string purpose;   // parse | derive | codegen | repair
  std::string artifact;  // file name of the artifact it belongs to
  int round = 1;
};

class Conversation {
 public:
  Conversation(Client& client, TranscriptInfo info);
  // Sends `messages`; while a reply fails `check`, appends it (at most kMaxEchoBytes of it) and the
  // error and asks again, up to config.max_turns replies. The replies' bodies together are read up
  // to config.reply_limit_bytes. Writes the transcript whatever happens. Throws input_error when no reply
  // was usable or the replies are beyond that limit, llm_error when the endpoint failed.
  io::json ask(std::vector<Message> messages, const ReplyCheck& check);
  // The model that answered (the configured one before any reply).
  std::string model() const { return model_; }
  io::json transcript() const;

 private:
  void write() const;
  Client& client_;
  TranscriptInfo info_;
  std::string model_;
  io::json turns_ = io::json::array();
  std::size_t received_ = 0;  // bytes of the replies so far
  bool failed_ = false;
};

// The transcript path of an artifact: derivation.r1.json -> derivation.r1.transcript.json,
// shoot.r2.cpp -> shoot.r2.transcript.json.
std::string transcript_path_for(const std::string& artifact_path);

}  // namespace helios::llm

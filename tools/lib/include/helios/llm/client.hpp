#pragma once
// The OpenAI-compatible chat-completions client of the llm backend:
// POST {base}/chat/completions over libcurl with bounded retries, or answers replayed from
// recorded transcripts. The API key is read from the environment, sent as a header and never
// kept in any value this API returns (requests, replies, errors, transcripts).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::llm {

// A request or transport failure the client gave up on (HTTP 401/404, retries exhausted, no
// replay). The message is one line and never contains the API key.
struct llm_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Config {
  std::string base_url;           // HELIOS_LLM_BASE_URL, e.g. https://api.example.com/v1
  std::string model;              // HELIOS_LLM_MODEL
  std::string api_key;            // HELIOS_LLM_API_KEY (may be empty for local servers)
  double temperature = 0.1;       // HELIOS_LLM_TEMPERATURE
  double timeout_s = 300;         // HELIOS_LLM_TIMEOUT_S: whole request
  double connect_timeout_s = 10;  // min(10, timeout_s)
  int max_retries = 4;            // HELIOS_LLM_MAX_RETRIES: extra attempts after the first
  double backoff_s = 2;           // HELIOS_LLM_BACKOFF_S: first wait; doubles per retry
  double backoff_max_s = 60;      // HELIOS_LLM_BACKOFF_MAX_S: cap of a wait and of Retry-After
  int max_turns = 3;              // HELIOS_LLM_MAX_TURNS: replies per artifact until one is usable
  std::string replay_dir;         // HELIOS_LLM_REPLAY: answer from transcripts under this folder
  // Not a variable: the limit of the reply bodies for one artifact together (README "Limits").
  std::size_t reply_limit_bytes = io::kMaxJsonBytes;

  // Reads the variables above. Throws usage_error naming a variable that is missing (base URL
  // and model, unless replaying), malformed or out of its range (tools/lib/src/llm/README.md).
  static Config from_env();
  // base_url + "/chat/completions" without user:password@ (safe to print).
  std::string endpoint() const;
};

struct Message {
  std::string role;  // system | user | assistant
  std::string content;
};

struct Usage {
  long prompt_tokens = 0, completion_tokens = 0, total_tokens = 0;
};

// One HTTP try of a request.
struct Attempt {
  int http_status = 0;  // 0: no HTTP answer (timeout, connection error)
  std::string error;    // empty when the attempt produced a usable reply
  double latency_s = 0;
  double wait_s = 0;  // back-off slept after this attempt
};

// One request and the reply that answered it.
struct Exchange {
  io::json request;            // {model, messages, temperature}: exactly what was posted, minus headers
  std::string request_sha256;  // sha256 of the messages (the replay key)
  std::string content;         // choices[0].message.content
  std::string reply_model;     // "model" of the reply (the configured model if absent)
  std::string finish_reason;
  Usage usage;
  double latency_s = 0;         // of the successful attempt
  std::size_t reply_bytes = 0;  // of the reply's body (replayed: of its content)
  int http_status = 0;
  std::vector<Attempt> attempts;
  bool replayed = false;
};

// The replay key of a conversation: SHA-256 of its messages as compact JSON.
std::string request_hash(const std::vector<Message>& messages);

// Parses Retry-After (delta-seconds only); nullopt when absent or an HTTP date.
std::optional<double> parse_retry_after(const std::string& value);

// Wait before retry number `retry` (1-based): backoff_s * 2^(retry-1), or Retry-After, capped.
double backoff_seconds(const Config& config, int retry, std::optional<double> retry_after);

// Replaces every occurrence of `secret` in `text` (no-op when secret is empty).
std::string redact(std::string text, const std::string& secret);

class Client {
 public:
  explicit Client(Config config);
  // Sends the conversation and returns the first usable reply. Retries timeouts, connection
  // errors, 429 and 5xx up to config.max_retries times with exponential back-off; fails at once
  // on other statuses. In replay mode answers from the recorded transcripts, without network.
  // On failure throws llm_error; `failed` (if given) receives the attempts made. The reply's body
  // is read up to `bytes_left` of config.reply_limit_bytes (all of it by default): one byte beyond,
  // reading stops and input_error is thrown at once, without a retry.
  Exchange chat(const std::vector<Message>& messages, Exchange* failed = nullptr,
                std::optional<std::size_t> bytes_left = std::nullopt);
  const Config& config() const { return config_; }

 private:
  Exchange replay(const std::vector<Message>& messages);
  Config config_;
  bool replay_loaded_ = false;
  std::map<std::string, io::json> recorded_;  // request_sha256 -> recorded turn
};

}  // namespace helios::llm

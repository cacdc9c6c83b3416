#include "helios/llm/client.hpp"

#include <curl/curl.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/sha256.hpp"

namespace helios::llm {
namespace {

using io::json;

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

// A variable's number in [min, max] (or `fallback` when unset); anything else is refused in one
// line naming it, before it could overflow what it sets (a count, a time in milliseconds).
double env_number(const char* name, double fallback, double min, double max) {
  const std::string text = env(name);
  if (text.empty()) return fallback;
  std::size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(value >= min && value <= max))
    throw usage_error(std::string(name) + "=" + text + " is not a number in [" + io::short_number(min) + ", " +
                      io::short_number(max) + "], fix or unset it");
  return value;
}

// A variable's whole number in [min, max] (digits only: no sign, point or exponent).
int env_integer(const char* name, int fallback, int min, int max) {
  const std::string text = env(name);
  if (text.empty()) return fallback;
  const bool digits = text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
  const int value = digits ? std::stoi(text) : -1;
  if (!digits || value < min || value > max)
    throw usage_error(std::string(name) + "=" + text + " is not a whole number in [" + std::to_string(min) + ", " +
                      std::to_string(max) + "], fix or unset it");
  return value;
}

std::string status_words(long status) {
  switch (status) {
    case 400:
      return "bad request";
    case 401:
      return "unauthorized";
    case 403:
      return "forbidden";
    case 404:
      return "not found";
    case 408:
      return "request timeout";
    case 413:
      return "payload too large";
    case 429:
      return "too many requests";
    case 500:
      return "internal server error";
    case 502:
      return "bad gateway";
    case 503:
      return "service unavailable";
    case 504:
      return "gateway timeout";
    default:
      return "unexpected status";
  }
}

struct HttpReply {
  long status = 0;
  std::string body;
  std::size_t limit = 0;   // of the body: reading stops beyond it
  bool too_large = false;  // the body was longer than `limit`
  std::string retry_after;
  CURLcode code = CURLE_OK;
  std::string curl_error;
  double seconds = 0;
};

// Keeps the body while it is within its limit; one byte beyond, the transfer stops (returning less
// than was given aborts it), so a reply never takes more memory than its limit.
std::size_t on_body(char* data, std::size_t size, std::size_t n, void* user) {
  auto& r = *static_cast<HttpReply*>(user);
  if (size * n > r.limit - r.body.size()) {
    r.too_large = true;
    return 0;
  }
  r.body.append(data, size * n);
  return size * n;
}

std::size_t on_header(char* data, std::size_t size, std::size_t n, void* user) {
  const std::string line(data, size * n);
  const std::string name = "retry-after:";
  if (line.size() > name.size()) {
    std::string head = line.substr(0, name.size());
    for (auto& ch : head) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (head == name) {
      std::string value = line.substr(name.size());
      const auto b = value.find_first_not_of(" \t");
      const auto e = value.find_last_not_of(" \t\r\n");
      *static_cast<std::string*>(user) = b == std::string::npos ? "" : value.substr(b, e - b + 1);
    }
  }
  return size * n;
}

HttpReply post(const Config& c, const std::string& body, std::size_t limit) {
  static const bool initialized = [] { return curl_global_init(CURL_GLOBAL_DEFAULT) == CURLE_OK; }();
  if (!initialized) throw llm_error("libcurl could not be initialized");
  HttpReply r;
  r.limit = limit;
  CURL* curl = curl_easy_init();
  if (!curl) throw llm_error("libcurl could not create a handle");
  curl_slist* headers = nullptr;
  headers = curl_slist_append(headers, "Content-Type: application/json");
  headers = curl_slist_append(headers, "Accept: application/json");
  // NOTE: the key lives only in this header list, which is freed below; nothing logs it.
  std::string auth;
  if (!c.api_key.empty()) {
    auth = "Authorization: Bearer " + c.api_key;
    headers = curl_slist_append(headers, auth.c_str());
  }
  const std::string url = c.base_url + "/chat/completions";
  char error[CURL_ERROR_SIZE] = {0};
  curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
  curl_easy_setopt(curl, CURLOPT_HTTPHEADER, headers);
  curl_easy_setopt(curl, CURLOPT_POST, 1L);
  curl_easy_setopt(curl, CURLOPT_POSTFIELDS, body.c_str());
  curl_easy_setopt(curl, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(body.size()));
  curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, on_body);
  curl_easy_setopt(curl, CURLOPT_WRITEDATA, &r);
  // A Content-Length beyond the limit is refused before the body is read.
  curl_easy_setopt(curl, CURLOPT_MAXFILESIZE_LARGE, static_cast<curl_off_t>(limit));
  curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, on_header);
  curl_easy_setopt(curl, CURLOPT_HEADERDATA, &r.retry_after);
  curl_easy_setopt(curl, CURLOPT_TIMEOUT_MS, static_cast<long>(c.timeout_s * 1000));
  curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT_MS, static_cast<long>(c.connect_timeout_s * 1000));
  curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
  curl_easy_setopt(curl, CURLOPT_ERRORBUFFER, error);
  curl_easy_setopt(curl, CURLOPT_USERAGENT, "helios/" HELIOS_VERSION);
  const auto start = std::chrono::steady_clock::now();
  r.code = curl_easy_perform(curl);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.too_large = r.too_large || r.code == CURLE_FILESIZE_EXCEEDED;
  if (r.code == CURLE_OK) curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &r.status);
  r.curl_error = error[0] ? error : curl_easy_strerror(r.code);
  curl_slist_free_all(headers);
  curl_easy_cleanup(curl);
  std::fill(auth.begin(), auth.end(), '\0');
  return r;
}

// Removes user:password@ from a URL, so it can be printed.
std::string without_userinfo(const std::string& url) {
  const auto scheme = url.find("://");
  const std::size_t start = scheme == std::string::npos ? 0 : scheme + 3;
  const auto at = url.find('@', start);
  const auto slash = url.find('/', start);
  if (at == std::string::npos || (slash != std::string::npos && at > slash)) return url;
  return url.substr(0, start) + url.substr(at + 1);
}

json messages_json(const std::vector<Message>& messages) {
  json out = json::array();
  for (const auto& m : messages) out.push_back({{"role", m.role}, {"content", m.content}});
  return out;
}

}  // namespace

Config Config::from_env() {
  Config c;
  c.base_url = env("HELIOS_LLM_BASE_URL");
  while (!c.base_url.empty() && c.base_url.back() == '/') c.base_url.pop_back();
  c.model = env("HELIOS_LLM_MODEL");
  c.api_key = env("HELIOS_LLM_API_KEY");
  c.replay_dir = env("HELIOS_LLM_REPLAY");
  c.temperature = env_number("HELIOS_LLM_TEMPERATURE", c.temperature, 0, 2);
  c.timeout_s = env_number("HELIOS_LLM_TIMEOUT_S", c.timeout_s, 0.001, 86400);
  c.connect_timeout_s = std::min(c.connect_timeout_s, c.timeout_s);
  c.max_retries = env_integer("HELIOS_LLM_MAX_RETRIES", c.max_retries, 0, 100);
  c.backoff_s = env_number("HELIOS_LLM_BACKOFF_S", c.backoff_s, 0, 3600);
  c.backoff_max_s = env_number("HELIOS_LLM_BACKOFF_MAX_S", c.backoff_max_s, 0, 3600);
  c.max_turns = env_integer("HELIOS_LLM_MAX_TURNS", c.max_turns, 1, 100);
  if (!c.replay_dir.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_directory(c.replay_dir, ec))
      throw usage_error("HELIOS_LLM_REPLAY=" + c.replay_dir + " is not a folder, name a folder of *.transcript.json");
    return c;
  }
  if (c.base_url.empty())
    throw usage_error(
        "HELIOS_LLM_BASE_URL is not set, set it to an OpenAI-compatible endpoint such as https://api.example.com/v1 "
        "(or HELIOS_LLM_REPLAY to a folder of transcripts)");
  if (c.base_url.rfind("http://", 0) != 0 && c.base_url.rfind("https://", 0) != 0)
    throw usage_error("HELIOS_LLM_BASE_URL=" + without_userinfo(c.base_url) +
                      " is not an http:// or https:// URL, e.g. https://api.example.com/v1");
  if (c.model.empty()) throw usage_error("HELIOS_LLM_MODEL is not set, set it to the model name the endpoint serves");
  return c;
}

std::string Config::endpoint() const {
  return without_userinfo(base_url) + "/chat/completions";
}

std::string request_hash(const std::vector<Message>& messages) {
  return io::sha256_hex(messages_json(messages).dump());
}

std::optional<double> parse_retry_after(const std::string& value) {
  if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  try {
    return std::stod(value);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

double backoff_seconds(const Config& config, int retry, std::optional<double> retry_after) {
  const double exponential = config.backoff_s * std::pow(2.0, std::max(0, retry - 1));
  return std::min(config.backoff_max_s, retry_after ? *retry_after : exponential);
}

std::string redact(std::string text, const std::string& secret) {
  if (secret.empty()) return text;
  for (std::size_t i = 0; (i = text.find(secret, i)) != std::string::npos; i += 10)
    text.replace(i, secret.size(), "[redacted]");
  return text;
}

Client::Client(Config config) : config_(std::move(config)) {}

Exchange Client::chat(const std::vector<Message>& messages, Exchange* failed, std::optional<std::size_t> bytes_left) {
  if (!config_.replay_dir.empty()) return replay(messages);
  const std::size_t reply_limit = bytes_left.value_or(config_.reply_limit_bytes);
  Exchange x;
  x.request = {{"model", config_.model}, {"messages", messages_json(messages)}, {"temperature", config_.temperature}};
  x.request_sha256 = request_hash(messages);
  const std::string body = x.request.dump();
  const std::string where = "POST " + config_.endpoint();
  std::string last;
  for (int attempt = 1; attempt <= config_.max_retries + 1; ++attempt) {
    const HttpReply r = post(config_, body, reply_limit);
    Attempt a;
    a.http_status = static_cast<int>(r.status);
    a.latency_s = r.seconds;
    if (r.too_large) {
      // Not retried: the same request would bring the same flood.
      a.error = "the reply was larger than " + std::to_string(reply_limit) + " bytes; reading stopped there";
      x.attempts.push_back(a);
      if (failed) *failed = x;
      throw input_error(where + ": the reply is larger than the limit of an llm reply (" +
                        std::to_string(config_.reply_limit_bytes) +
                        " bytes, the replies for one artifact together), check HELIOS_LLM_BASE_URL and "
                        "HELIOS_LLM_MODEL");
    }
    if (r.code != CURLE_OK) {
      const bool timeout = r.code == CURLE_OPERATION_TIMEDOUT;
      a.error = timeout
                    ? "timed out after " + std::to_string(config_.timeout_s).substr(0, 6) + " s (HELIOS_LLM_TIMEOUT_S)"
                    : redact(r.curl_error, config_.api_key);
    } else if (r.status == 200) {
      try {
        const json reply = json::parse(r.body);
        const json& choice = reply.at("choices").at(0);
        x.content = choice.at("message").at("content").get<std::string>();
        x.finish_reason = choice.value("finish_reason", "");
        if (choice.contains("finish_reason") && !choice["finish_reason"].is_string()) x.finish_reason = "";
        x.reply_model = reply.value("model", config_.model);
        if (reply.contains("usage") && reply["usage"].is_object()) {
          const json& u = reply["usage"];
          x.usage.prompt_tokens = u.value("prompt_tokens", 0L);
          x.usage.completion_tokens = u.value("completion_tokens", 0L);
          x.usage.total_tokens = u.value("total_tokens", x.usage.prompt_tokens + x.usage.completion_tokens);
        }
      } catch (const std::exception&) {
        a.error = "HTTP 200 but the body is not a chat completion with choices[0].message.content";
        x.attempts.push_back(a);
        if (failed) *failed = x;
        throw llm_error(where + " answered HTTP 200 with a body that is not a chat completion (" +
                        std::to_string(r.body.size()) +
                        " bytes), check HELIOS_LLM_BASE_URL points at an "
                        "OpenAI-compatible API");
      }
      x.http_status = 200;
      x.latency_s = r.seconds;
      x.reply_bytes = r.body.size();
      x.attempts.push_back(a);
      return x;
    } else if (r.status == 429 || r.status >= 500) {
      a.error = "HTTP " + std::to_string(r.status) + " (" + status_words(r.status) + ")";
    } else {
      a.error = "HTTP " + std::to_string(r.status) + " (" + status_words(r.status) + ")";
      x.attempts.push_back(a);
      if (failed) *failed = x;
      std::string fix = "check the endpoint and the model";
      if (r.status == 401 || r.status == 403) fix = "check HELIOS_LLM_API_KEY";
      if (r.status == 404)
        fix =
            "check HELIOS_LLM_BASE_URL (the part before /chat/completions, e.g. https://api.example.com/v1) and "
            "HELIOS_LLM_MODEL=" +
            config_.model;
      throw llm_error(where + " returned " + a.error + ", " + fix);
    }
    last = a.error;
    if (attempt <= config_.max_retries) {
      a.wait_s = backoff_seconds(config_, attempt,
                                 r.status == 429 || r.status == 503 ? parse_retry_after(r.retry_after) : std::nullopt);
      x.attempts.push_back(a);
      std::this_thread::sleep_for(std::chrono::duration<double>(a.wait_s));
    } else {
      x.attempts.push_back(a);
    }
  }
  if (failed) *failed = x;
  throw llm_error(where + " failed " + std::to_string(config_.max_retries + 1) + " times, last: " + last +
                  ", try later or raise HELIOS_LLM_MAX_RETRIES / HELIOS_LLM_TIMEOUT_S");
}

Exchange Client::replay(const std::vector<Message>& messages) {
  namespace fs = std::filesystem;
  if (!replay_loaded_) {
    replay_loaded_ = true;
    std::error_code ec;
    std::vector<fs::path> files;
    for (auto it = fs::recursive_directory_iterator(config_.replay_dir, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (it->is_regular_file(ec) && name.size() > 16 && name.substr(name.size() - 16) == ".transcript.json")
        files.push_back(it->path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      json t;
      try {
        t = io::read_json(f.string());
      } catch (const std::exception&) {
        continue;
      }
      if (!t.is_object() || t.value("schema", "") != "helios/transcript" || !t.contains("turns")) continue;
      for (const auto& turn : t["turns"])
        if (turn.contains("reply") && turn["reply"].is_object() && turn.contains("request_sha256"))
          recorded_.emplace(turn["request_sha256"].get<std::string>(), turn);
    }
  }
  Exchange x;
  x.request_sha256 = request_hash(messages);
  const auto it = recorded_.find(x.request_sha256);
  if (it == recorded_.end())
    throw llm_error("HELIOS_LLM_REPLAY=" + config_.replay_dir + " has no recorded reply to request sha256 " +
                    x.request_sha256.substr(0, 16) +
                    "..., record it first (unset HELIOS_LLM_REPLAY) or replay the "
                    "folder of the run that made it");
  const json& turn = it->second;
  x.request = turn.at("request");
  x.request["messages"] = messages_json(messages);
  x.content = turn.at("reply").at("content").get<std::string>();
  x.reply_model = turn.at("reply").value("model", "");
  x.finish_reason = turn.at("reply").value("finish_reason", "");
  if (turn.contains("usage")) {
    x.usage.prompt_tokens = turn["usage"].value("prompt_tokens", 0L);
    x.usage.completion_tokens = turn["usage"].value("completion_tokens", 0L);
    x.usage.total_tokens = turn["usage"].value("total_tokens", 0L);
  }
  x.http_status = turn.value("http_status", 200);
  x.replayed = true;
  x.reply_bytes = x.content.size();
  x.attempts.push_back(Attempt{x.http_status, "", 0, 0});
  return x;
}

}  // namespace helios::llm

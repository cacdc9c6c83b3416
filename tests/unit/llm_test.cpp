// The llm backend's client pieces in-process: reply extraction, prompt filling, back-off,
// redaction, and the HTTP client against a scripted cpp-httplib server on 127.0.0.1.
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/schema.hpp"
#include "helios/llm/backend.hpp"
#include "helios/llm/client.hpp"
#include "helios/llm/conversation.hpp"

namespace {

namespace fs = std::filesystem;
using helios::io::json;
using namespace helios::llm;

// This executable lives in build/, not build/bin/, so the prompts beside the tools are not where
// prompts_dir() looks by default: read the project's own prompts/.
const bool kPromptsFromSource = setenv("HELIOS_PROMPTS_DIR", HELIOS_SOURCE_DIR "/prompts", 1) == 0;

// A chat-completions server whose n-th request (0-based) is answered by handlers[n].
class ScriptedServer {
 public:
  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;
  explicit ScriptedServer(std::vector<Handler> handlers) : handlers_(std::move(handlers)) {
    server_.Post(R"(.*/chat/completions)", [this](const httplib::Request& req, httplib::Response& res) {
      const int n = count_++;
      requests_.push_back(req.body);
      authorization_.push_back(req.get_header_value("Authorization"));
      if (n < static_cast<int>(handlers_.size()))
        handlers_[n](req, res);
      else
        res.status = 400;
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~ScriptedServer() {
    server_.stop();
    thread_.join();
  }
  std::string base() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  int count() const { return count_; }
  const std::vector<std::string>& authorization() const { return authorization_; }
  const std::vector<std::string>& requests() const { return requests_; }

 private:
  httplib::Server server_;
  std::vector<Handler> handlers_;
  std::atomic<int> count_{0};
  std::vector<std::string> requests_, authorization_;
  int port_ = 0;
  std::thread thread_;
};

ScriptedServer::Handler reply(const std::string& content, long prompt = 10, long completion = 5) {
  return [=](const httplib::Request&, httplib::Response& res) {
    const json body = {
        {"model", "scripted-1"},
        {"choices",
         json::array({{{"message", {{"role", "assistant"}, {"content", content}}}, {"finish_reason", "stop"}}})},
        {"usage",
         {{"prompt_tokens", prompt}, {"completion_tokens", completion}, {"total_tokens", prompt + completion}}}};
    res.set_content(body.dump(), "application/json");
  };
}

ScriptedServer::Handler status(int code, const std::string& retry_after = "") {
  return [=](const httplib::Request&, httplib::Response& res) {
    res.status = code;
    if (!retry_after.empty()) res.set_header("Retry-After", retry_after);
    res.set_content("{}", "application/json");
  };
}

Config config_for(const ScriptedServer& s) {
  Config c;
  c.base_url = s.base();
  c.model = "test-model";
  c.api_key = "sk-unit-test-key";
  c.backoff_s = 0.001;
  c.timeout_s = 5;
  return c;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("helios-llm-test-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(LlmReply, ExtractsTheJsonFenceThenAnyFenceThenBraces) {
  EXPECT_EQ(extract_json_text("Sure.\n```json\n{\"a\": 1}\n```\nDone."), "{\"a\": 1}");
  EXPECT_EQ(extract_json_text("```cpp\nint x;\n```\n```json\n{\"b\": 2}\n```"), "{\"b\": 2}");
  EXPECT_EQ(extract_json_text("```\n{\"c\": 3}\n```"), "{\"c\": 3}");
  EXPECT_EQ(extract_json_text("The answer is {\"d\": {\"e\": 4}} as asked."), "{\"d\": {\"e\": 4}}");
  EXPECT_EQ(extract_json_text("  [1, 2]  "), "[1, 2]");
  EXPECT_EQ(parse_reply_json("```json\n{\"a\": [1, 2]}\n```")["a"][1], 2);
}

TEST(LlmReply, MalformedJsonIsAReplyErrorToFeedBack) {
  try {
    parse_reply_json("```json\n{\"a\": 1,,}\n```");
    FAIL() << "no reply_error";
  } catch (const reply_error& e) {
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_reply_json("   "), reply_error);
}

TEST(LlmPrompt, FillsEveryPlaceholderOnceAndNeverExpandsValues) {
  EXPECT_EQ(fill("a {{X}} b {{Y}} {json}", {{"X", "{{Y}}"}, {"Y", "2"}}), "a {{Y}} b 2 {json}");
  EXPECT_THROW(fill("a {{X}}", {}), std::logic_error);
  EXPECT_THROW(fill("a", {{"X", "1"}}), std::logic_error);
}

TEST(LlmPrompt, EveryShippedPromptHasItsPlaceholders) {
  EXPECT_NO_THROW(fill(prompt("parse.txt"), {{"SPEC_SCHEMA", "s"}, {"SOURCE_FILE", "f"}, {"PROBLEM_TEXT", "t"}}));
  EXPECT_NO_THROW(fill(prompt("pmp_derive.txt"), {{"DERIVATION_SCHEMA", "s"},
                                                  {"SPEC_JSON", "j"},
                                                  {"NORMALIZATION_JSON", "n"},
                                                  {"TERM_CATALOGUE", "c"},
                                                  {"FEEDBACK", ""}}));
  EXPECT_NO_THROW(fill(prompt("codegen.txt"), {{"DERIVATION_JSON", "d"}, {"PROBLEM_BLOCK", "p"}, {"RUNTIME", "r"}}));
  EXPECT_NO_THROW(fill(prompt("repair.txt"), {{"ROUND", "1"}, {"COMMAND", "c"}, {"COMPILER_ERRORS", "e"}}));
  for (const char* rule :
       {"Rule 0", "Rule B ", "Rule B2", "Rule G1", "Rule G2", "Rule G3", "Rule G4", "Rule G5", "Rule G6"})
    EXPECT_NE(prompt("pmp_derive.txt").find(rule), std::string::npos) << rule;
}

TEST(LlmPrompt, AMissingPromptNamesItsPathAndWhereThePromptsAreRead) {
  ASSERT_TRUE(kPromptsFromSource);
  EXPECT_EQ(prompts_dir(), fs::path(HELIOS_SOURCE_DIR "/prompts"));
  try {
    prompt("no-such-prompt.txt");
    FAIL() << "no error";
  } catch (const helios::input_error& e) {
    EXPECT_NE(std::string(e.what()).find(HELIOS_SOURCE_DIR "/prompts/no-such-prompt.txt: no such prompt"),
              std::string::npos)
        << e.what();
  }
}

TEST(LlmClient, BackoffDoublesAndRetryAfterIsHonouredWithinTheCap) {
  Config c;
  c.backoff_s = 2;
  c.backoff_max_s = 60;
  EXPECT_DOUBLE_EQ(backoff_seconds(c, 1, std::nullopt), 2);
  EXPECT_DOUBLE_EQ(backoff_seconds(c, 3, std::nullopt), 8);
  EXPECT_DOUBLE_EQ(backoff_seconds(c, 10, std::nullopt), 60);
  EXPECT_DOUBLE_EQ(backoff_seconds(c, 1, 7.0), 7);
  EXPECT_DOUBLE_EQ(backoff_seconds(c, 1, 3600.0), 60);
  EXPECT_EQ(parse_retry_after("12"), 12.0);
  EXPECT_FALSE(parse_retry_after("Wed, 21 Oct 2015 07:28:00 GMT"));
  EXPECT_FALSE(parse_retry_after(""));
}

TEST(LlmClient, RedactsTheKeyAndHashesOnlyTheMessages) {
  EXPECT_EQ(redact("a sk-1 b sk-1", "sk-1"), "a [redacted] b [redacted]");
  EXPECT_EQ(redact("abc", ""), "abc");
  const std::vector<Message> m = {{"user", "hi"}};
  EXPECT_EQ(request_hash(m), request_hash(m));
  EXPECT_NE(request_hash(m), request_hash({{"user", "hi!"}}));
  EXPECT_EQ(transcript_path_for("runs/llm/S01/derivation.r2.json"), "runs/llm/S01/derivation.r2.transcript.json");
  EXPECT_EQ(transcript_path_for("shoot.r1.cpp"), "shoot.r1.transcript.json");
}

TEST(LlmClient, SendsModelMessagesTemperatureAndTheKeyAsABearerHeader) {
  ScriptedServer s({reply("hello", 12, 3)});
  Client client(config_for(s));
  const Exchange x = client.chat({{"system", "sys"}, {"user", "question"}});
  EXPECT_EQ(x.content, "hello");
  EXPECT_EQ(x.reply_model, "scripted-1");
  EXPECT_EQ(x.usage.prompt_tokens, 12);
  EXPECT_EQ(x.usage.total_tokens, 15);
  ASSERT_EQ(s.count(), 1);
  EXPECT_EQ(s.authorization()[0], "Bearer sk-unit-test-key");
  const json sent = json::parse(s.requests()[0]);
  EXPECT_EQ(sent["model"], "test-model");
  EXPECT_DOUBLE_EQ(sent["temperature"].get<double>(), 0.1);
  EXPECT_EQ(sent["messages"][1]["content"], "question");
  EXPECT_EQ(x.request.dump().find("sk-unit-test-key"), std::string::npos);
}

TEST(LlmClient, Retries429And5xxThenSucceeds) {
  ScriptedServer s({status(429, "0"), status(502), reply("ok")});
  Client client(config_for(s));
  const Exchange x = client.chat({{"user", "q"}});
  EXPECT_EQ(x.content, "ok");
  ASSERT_EQ(x.attempts.size(), 3u);
  EXPECT_EQ(x.attempts[0].http_status, 429);
  EXPECT_EQ(x.attempts[1].http_status, 502);
  EXPECT_EQ(x.attempts[2].http_status, 200);
}

TEST(LlmClient, RetriesAreBounded) {
  ScriptedServer s({status(500), status(500), status(500), reply("late")});
  Config c = config_for(s);
  c.max_retries = 2;
  Client client(c);
  Exchange failed;
  try {
    client.chat({{"user", "q"}}, &failed);
    FAIL() << "no llm_error";
  } catch (const llm_error& e) {
    EXPECT_NE(std::string(e.what()).find("failed 3 times"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.count(), 3);
  EXPECT_EQ(failed.attempts.size(), 3u);
}

TEST(LlmClient, A401FailsAtOnceNamingTheUrlAndTheVariableNotTheKey) {
  ScriptedServer s({status(401), reply("never")});
  Client client(config_for(s));
  try {
    client.chat({{"user", "q"}});
    FAIL() << "no llm_error";
  } catch (const llm_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(s.base() + "/chat/completions returned HTTP 401 (unauthorized)"), std::string::npos) << what;
    EXPECT_NE(what.find("HELIOS_LLM_API_KEY"), std::string::npos) << what;
    EXPECT_EQ(what.find("sk-unit-test-key"), std::string::npos) << what;
  }
  EXPECT_EQ(s.count(), 1);
}

TEST(LlmClient, ATimeoutIsRetried) {
  ScriptedServer s({[](const httplib::Request&, httplib::Response& res) {
                      std::this_thread::sleep_for(std::chrono::milliseconds(800));
                      res.set_content("{}", "application/json");
                    },
                    reply("fast")});
  Config c = config_for(s);
  c.timeout_s = 0.2;
  Client client(c);
  const Exchange x = client.chat({{"user", "q"}});
  EXPECT_EQ(x.content, "fast");
  ASSERT_EQ(x.attempts.size(), 2u);
  EXPECT_EQ(x.attempts[0].http_status, 0);
  EXPECT_NE(x.attempts[0].error.find("timed out"), std::string::npos);
}

// A reply is read only up to its limit: an endless body (no Content-Length) and one whose declared
// length is beyond it both stop the request at once, as invalid input, without a retry.
TEST(LlmClient, AReplyIsReadOnlyUpToItsLimitAndNotRetried) {
  std::atomic<std::size_t> streamed{0};
  const auto endless = [&](const httplib::Request&, httplib::Response& res) {
    res.set_chunked_content_provider("application/json", [&](std::size_t, httplib::DataSink& sink) {
      const std::string chunk(65536, 'x');
      streamed += chunk.size();
      return sink.write(chunk.data(), chunk.size());
    });
  };
  const auto declared = [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(3 << 20, 'x'), "application/json");
  };
  ScriptedServer s({endless, declared, reply("never")});
  Config c = config_for(s);
  c.reply_limit_bytes = 1 << 20;
  Client client(c);
  for (int request = 0; request < 2; ++request) {
    Exchange failed;
    try {
      client.chat({{"user", "q"}}, &failed);
      FAIL() << "no input_error";
    } catch (const helios::input_error& e) {
      EXPECT_EQ(std::string(e.what()), "POST " + s.base() +
                                           "/chat/completions: the reply is larger than the limit of an llm reply "
                                           "(1048576 bytes, the replies for one artifact together), check "
                                           "HELIOS_LLM_BASE_URL and HELIOS_LLM_MODEL");
    }
    ASSERT_EQ(failed.attempts.size(), 1u);
    EXPECT_NE(failed.attempts[0].error.find("larger than 1048576 bytes"), std::string::npos);
  }
  EXPECT_EQ(s.count(), 2);
  // The endless body was stopped near the limit (what the sockets buffer aside), not read on.
  EXPECT_LT(streamed.load(), std::size_t{64} << 20);
}

// The replies for one artifact share the limit, and what goes back of a reply that could not be
// used is at most kMaxEchoBytes of it, cut between characters, in the request and the transcript.
TEST(LlmConversation, RepliesShareTheLimitAndAnUnusableOneGoesBackCut) {
  // One byte, then two-byte characters (e acute): a character starts at each odd offset, and the
  // echo's cut (kMaxEchoBytes less its note, an even offset here) would split one.
  std::string long_reply = "a";
  while (long_reply.size() < kMaxEchoBytes + 1000) long_reply += "\xc3\xa9";
  ScriptedServer s({reply(long_reply), reply(std::string(500000, 'y')), reply("```json\n{\"answer\": 1}\n```")});
  Config c = config_for(s);
  c.reply_limit_bytes = 700000;
  c.max_turns = 3;
  Client client(c);
  const fs::path dir = fresh_dir("bounded");
  const std::string path = (dir / "x.transcript.json").string();
  Conversation conv(client, {path, "helios-test", "parse", "x.json", 1});
  const auto check = [](const std::string& content) {
    const json j = parse_reply_json(content);
    if (!j.contains("answer")) throw reply_error("no answer");
    return j;
  };
  EXPECT_THROW(conv.ask({{"user", "give me JSON"}}, check), helios::input_error);
  ASSERT_EQ(s.count(), 2);
  const json second = json::parse(s.requests()[1]);
  const std::string echo = second["messages"][1]["content"].get<std::string>();
  EXPECT_LE(echo.size(), kMaxEchoBytes);
  EXPECT_NE(
      echo.find("[... the rest of this reply is not repeated: " + std::to_string(long_reply.size()) + " bytes in all]"),
      std::string::npos);
  const std::size_t cut = echo.find("\n[...");
  EXPECT_EQ(cut % 2, 1u);  // before a character, not inside one
  EXPECT_EQ(long_reply.compare(0, cut, echo, 0, cut), 0);
  // The transcript: the first reply once, the second stopped at the limit and not kept.
  const json t = helios::io::read_artifact("transcript", path);
  ASSERT_EQ(t["turns"].size(), 2u);
  EXPECT_EQ(t["turns"][0]["outcome"], "rejected");
  EXPECT_EQ(t["turns"][1]["outcome"], "failed");
  EXPECT_TRUE(t["turns"][1]["reply"].is_null());
  EXPECT_LT(fs::file_size(path), long_reply.size() + kMaxEchoBytes + 100000);
  fs::remove_all(dir);
}

// Numeric variables are read whole and within their range, or refused in one line naming them.
TEST(LlmClient, NumericVariablesOutsideTheirRangeAreRefused) {
  setenv("HELIOS_LLM_BASE_URL", "http://127.0.0.1:9/v1", 1);
  setenv("HELIOS_LLM_MODEL", "m", 1);
  const auto refused = [](const char* name, const char* value) {
    setenv(name, value, 1);
    std::string what;
    try {
      Config::from_env();
    } catch (const helios::usage_error& e) {
      what = e.what();
    }
    unsetenv(name);
    return what;
  };
  EXPECT_EQ(refused("HELIOS_LLM_MAX_RETRIES", "1e10"),
            "HELIOS_LLM_MAX_RETRIES=1e10 is not a whole number in [0, 100], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_MAX_RETRIES", "99999999999999999999"),
            "HELIOS_LLM_MAX_RETRIES=99999999999999999999 is not a whole number in [0, 100], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_MAX_TURNS", "0"),
            "HELIOS_LLM_MAX_TURNS=0 is not a whole number in [1, 100], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_MAX_TURNS", "-3"),
            "HELIOS_LLM_MAX_TURNS=-3 is not a whole number in [1, 100], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_TIMEOUT_S", "1e300"),
            "HELIOS_LLM_TIMEOUT_S=1e300 is not a number in [0.001, 86400], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_TEMPERATURE", "nan"),
            "HELIOS_LLM_TEMPERATURE=nan is not a number in [0, 2], fix or unset it");
  EXPECT_EQ(refused("HELIOS_LLM_BACKOFF_S", "1e400"),
            "HELIOS_LLM_BACKOFF_S=1e400 is not a number in [0, 3600], fix or unset it");
  setenv("HELIOS_LLM_MAX_RETRIES", "100", 1);
  setenv("HELIOS_LLM_TIMEOUT_S", "0.5", 1);
  const Config c = Config::from_env();
  EXPECT_EQ(c.max_retries, 100);
  EXPECT_DOUBLE_EQ(c.timeout_s, 0.5);
  for (const char* name : {"HELIOS_LLM_MAX_RETRIES", "HELIOS_LLM_TIMEOUT_S", "HELIOS_LLM_BASE_URL", "HELIOS_LLM_MODEL"})
    unsetenv(name);
}

TEST(LlmConversation, AMalformedReplyIsFedBackAndTheTranscriptRecordsBoth) {
  ScriptedServer s({reply("not json at all"), reply("```json\n{\"answer\": 42}\n```", 30, 7)});
  Client client(config_for(s));
  const fs::path dir = fresh_dir("conversation");
  const std::string path = (dir / "x.transcript.json").string();
  Conversation conv(client, {path, "helios-test", "parse", "x.json", 1});
  const json got = conv.ask({{"user", "give me JSON"}}, [](const std::string& content) {
    const json j = parse_reply_json(content);
    if (!j.contains("answer")) throw reply_error("no answer");
    return j;
  });
  EXPECT_EQ(got["answer"], 42);
  const json second = json::parse(s.requests()[1]);
  ASSERT_EQ(second["messages"].size(), 3u);
  EXPECT_EQ(second["messages"][1]["role"], "assistant");
  EXPECT_NE(second["messages"][2]["content"].get<std::string>().find("not valid JSON"), std::string::npos);
  const json t = helios::io::read_artifact("transcript", path);
  EXPECT_EQ(t["turns"].size(), 2u);
  EXPECT_EQ(t["turns"][0]["outcome"], "rejected");
  EXPECT_EQ(t["turns"][1]["outcome"], "accepted");
  EXPECT_EQ(t["usage"]["completion_tokens"], 12);
  EXPECT_EQ(t["producer"]["model"], "scripted-1");
  EXPECT_EQ(helios::io::read_text(path).find("sk-unit-test-key"), std::string::npos);
  fs::remove_all(dir);
}

TEST(LlmConversation, ReplayAnswersFromTranscriptsWithoutNetwork) {
  const fs::path dir = fresh_dir("replay");
  {
    ScriptedServer s({reply("```json\n{\"v\": 1}\n```")});
    Client client(config_for(s));
    Conversation conv(client, {(dir / "a.transcript.json").string(), "helios-test", "parse", "a.json", 1});
    conv.ask({{"user", "same question"}}, [](const std::string& c) { return parse_reply_json(c); });
  }
  Config c;
  c.replay_dir = dir.string();
  Client replay(c);
  const Exchange x = replay.chat({{"user", "same question"}});
  EXPECT_TRUE(x.replayed);
  EXPECT_EQ(x.content, "```json\n{\"v\": 1}\n```");
  EXPECT_THROW(replay.chat({{"user", "another question"}}), llm_error);
  fs::remove_all(dir);
}

TEST(LlmBackend, ModulesSurviveTheRoundTripThroughTheProgram) {
  const std::string source =
      "// ===== HELIOS LLM MODULE: DYNAMICS =====\nnamespace helios_rt {\nvoid a() {}\n}  // namespace helios_rt\n\n"
      "// ===== HELIOS LLM MODULE: SWITCH =====\nnamespace helios_rt {\nvoid b() {}\n}  // namespace helios_rt\n\n"
      "// ===== HELIOS LLM MODULE: RESIDUAL =====\nnamespace helios_rt {\nvoid c() {}\n}  // namespace helios_rt\n\n"
      "// ===== HELIOS LLM MODULE: SOLVE =====\nnamespace helios_rt {\nvoid d() {}\n}  // namespace helios_rt\n\n"
      "// ===== HELIOS LLM MODULES END =====\n";
  const json m = modules_of(source);
  EXPECT_EQ(m["DYNAMICS"], "void a() {}");
  EXPECT_EQ(m["SOLVE"], "void d() {}");
  EXPECT_THROW(modules_of("int main() {}"), helios::input_error);
}

}  // namespace

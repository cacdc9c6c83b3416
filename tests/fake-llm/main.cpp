// fake-llm: an OpenAI-compatible chat-completions server for the llm backend's tests.
//
// usage: fake-llm --script SCRIPT.json --port-file FILE [--log REQUESTS.jsonl] [--require-key KEY]
//                 [--lifetime SECONDS]
//
// Binds 127.0.0.1 on an ephemeral port, writes the port to --port-file (atomically) and stdout,
// and answers POST .../chat/completions from the script, one entry per request, in order:
//   {"replies": [{"status": 200, "content": "...", "content_file": "relative/to/script",
//                 "body": "raw body instead of a completion", "delay_s": 0, "retry_after": "1",
//                 "model": "fake-model", "usage": {"prompt_tokens": 1, ...}, "match": "substring",
//                 "content_bytes": N, "flood_bytes": N}]}
// An entry with "match" is used only for a request whose body contains that text. "content_bytes"
// is a content of N letters x; "flood_bytes" a completion whose content is N letters x, streamed
// as it is made (no Content-Length), for a client that must stop reading. Every request
// is appended to --log as one JSON line (path, authorization header, body, entry used). A request
// with no entry left gets HTTP 400. The server exits after --lifetime seconds (default 900) so a
// test that dies cannot leave it running.
#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using json = nlohmann::ordered_json;

httplib::Server* g_server = nullptr;

void on_signal(int) {
  if (g_server) g_server->stop();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

int main(int argc, char** argv) {
  std::string script_path, port_file, log_path, require_key;
  double lifetime = 900;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--script")
      script_path = argv[i + 1];
    else if (a == "--port-file")
      port_file = argv[i + 1];
    else if (a == "--log")
      log_path = argv[i + 1];
    else if (a == "--require-key")
      require_key = argv[i + 1];
    else if (a == "--lifetime")
      lifetime = std::stod(argv[i + 1]);
    else {
      std::cerr << "fake-llm: error: unknown option " << a << "\n";
      return 2;
    }
  }
  if (script_path.empty() || port_file.empty()) {
    std::cerr << "fake-llm: error: usage: fake-llm --script SCRIPT.json --port-file FILE [--log FILE]\n";
    return 2;
  }
  json script;
  try {
    script = json::parse(read_file(script_path));
    for (auto& r : script.at("replies"))
      if (r.contains("content_file"))
        r["content"] = read_file(dir_of(script_path) + "/" + r["content_file"].get<std::string>());
  } catch (const std::exception& e) {
    std::cerr << "fake-llm: error: " << script_path << ": " << e.what() << "\n";
    return 3;
  }
  std::vector<bool> used(script["replies"].size(), false);
  std::mutex mutex;
  int served = 0;

  httplib::Server server;
  g_server = &server;
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);

  server.Post(R"(.*/chat/completions)", [&](const httplib::Request& req, httplib::Response& res) {
    json entry;
    int index = -1;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      const auto& replies = script["replies"];
      for (std::size_t i = 0; i < replies.size(); ++i) {
        if (used[i]) continue;
        const std::string match = replies[i].value("match", "");
        if (!match.empty() && req.body.find(match) == std::string::npos) continue;
        used[i] = true;
        index = static_cast<int>(i);
        entry = replies[i];
        break;
      }
      ++served;
      if (!log_path.empty()) {
        std::ofstream log(log_path, std::ios::app);
        log << json{{"n", served},
                    {"path", req.path},
                    {"authorization", req.get_header_value("Authorization")},
                    {"entry", index},
                    {"body", req.body}}
                   .dump()
            << "\n";
      }
    }
    if (index < 0) {
      res.status = 400;
      res.set_content(R"({"error": {"message": "fake-llm: no scripted reply left"}})", "application/json");
      return;
    }
    if (entry.value("delay_s", 0.0) > 0)
      std::this_thread::sleep_for(std::chrono::duration<double>(entry["delay_s"].get<double>()));
    if (!require_key.empty() && req.get_header_value("Authorization") != "Bearer " + require_key) {
      res.status = 401;
      res.set_content(R"({"error": {"message": "invalid api key"}})", "application/json");
      return;
    }
    res.status = entry.value("status", 200);
    if (entry.contains("retry_after")) res.set_header("Retry-After", entry["retry_after"].get<std::string>());
    if (entry.contains("flood_bytes")) {
      const std::string head = R"({"model": "fake-model", "choices": [{"message": {"role": "assistant", "content": ")";
      const std::string tail = R"("}, "finish_reason": "stop"}]})";
      const std::size_t total = entry["flood_bytes"].get<std::size_t>();
      res.set_chunked_content_provider("application/json",
                                       [head, tail, total, sent = std::size_t{0}, chunk = std::string(65536, 'x')](
                                           std::size_t, httplib::DataSink& sink) mutable {
                                         if (sent == 0 && !sink.write(head.data(), head.size())) return false;
                                         const std::size_t n = std::min(chunk.size(), total - sent);
                                         if (n > 0 && !sink.write(chunk.data(), n)) return false;
                                         sent += n;
                                         if (sent == total) {
                                           sink.write(tail.data(), tail.size());
                                           sink.done();
                                         }
                                         return true;
                                       });
      return;
    }
    if (entry.contains("body")) {
      res.set_content(entry["body"].get<std::string>(), "application/json");
      return;
    }
    if (res.status != 200) {
      res.set_content(R"({"error": {"message": "scripted error"}})", "application/json");
      return;
    }
    const std::string content = entry.contains("content_bytes")
                                    ? std::string(entry["content_bytes"].get<std::size_t>(), 'x')
                                    : entry.value("content", "");
    json usage = entry.value("usage", json::object());
    // Deterministic token counts when the script gives none: about 4 characters per token.
    const long prompt = usage.value("prompt_tokens", static_cast<long>(req.body.size() / 4 + 1));
    const long completion = usage.value("completion_tokens", static_cast<long>(content.size() / 4 + 1));
    const json reply = {
        {"id", "chatcmpl-fake-" + std::to_string(index)},
        {"object", "chat.completion"},
        {"created", 0},
        {"model", entry.value("model", "fake-model")},
        {"choices",
         json::array(
             {{{"index", 0}, {"message", {{"role", "assistant"}, {"content", content}}}, {"finish_reason", "stop"}}})},
        {"usage",
         {{"prompt_tokens", prompt},
          {"completion_tokens", completion},
          {"total_tokens", usage.value("total_tokens", prompt + completion)}}}};
    res.set_content(reply.dump(), "application/json");
  });

  const int port = server.bind_to_any_port("127.0.0.1");
  if (port <= 0) {
    std::cerr << "fake-llm: error: cannot bind 127.0.0.1\n";
    return 1;
  }
  {
    const std::string tmp = port_file + ".tmp";
    std::ofstream(tmp) << port << "\n";
    std::rename(tmp.c_str(), port_file.c_str());
  }
  std::cout << port << std::endl;
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(lifetime);
    while (!done) {
      if (std::chrono::steady_clock::now() >= end) {
        server.stop();
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  server.listen_after_bind();
  done = true;
  watchdog.join();
  return 0;
}

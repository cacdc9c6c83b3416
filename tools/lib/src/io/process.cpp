#include "helios/io/process.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <utility>

namespace helios::io {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ExecArgv::ExecArgv(std::vector<std::string> argv) : strings_(std::move(argv)) {
  if (strings_.empty()) throw std::invalid_argument("a command needs at least its program's name");
  for (auto& a : strings_) pointers_.push_back(a.data());
  pointers_.push_back(nullptr);
}

void ExecArgv::exec_or_exit(bool search_path) const {
  if (search_path)
    ::execvp(pointers_[0], pointers_.data());
  else
    ::execv(pointers_[0], pointers_.data());
  _exit(127);
}

std::string on_path(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, end - start);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return name;
}

std::string capture(const std::vector<std::string>& argv) {
  int pipefd[2];
  const ExecArgv command(argv);
  if (::pipe(pipefd) != 0) return "";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(pipefd[1], 1);
    ::dup2(pipefd[1], 2);
    ::close(pipefd[0]);
    command.exec_or_exit(true);
  }
  ::close(pipefd[1]);
  std::string out;
  char buf[4096];
  ssize_t n;
  while ((n = ::read(pipefd[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  ::close(pipefd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return out;
}

std::vector<int> run_all(const std::vector<std::vector<std::string>>& commands, int jobs) {
  std::vector<int> codes(commands.size(), -1);
  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  bool fork_failed = false;
  while ((!fork_failed && next < commands.size()) || !running.empty()) {
    while (!fork_failed && next < commands.size() && static_cast<int>(running.size()) < std::max(1, jobs)) {
      const ExecArgv command(commands[next]);
      const pid_t pid = ::fork();
      if (pid < 0) {
        fork_failed = true;
        break;
      }
      if (pid == 0) command.exec_or_exit(true);
      running[pid] = next++;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) break;
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    codes[it->second] = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    running.erase(it);
  }
  if (fork_failed) throw std::runtime_error("cannot start a process (fork failed)");
  return codes;
}

std::string first_line(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

std::string printable_line(std::string text, std::size_t max_bytes) {
  if (text.size() > max_bytes) text = text.substr(0, max_bytes) + "...";
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  return text;
}

std::string limit_text(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", seconds);
  return buf;
}

}  // namespace helios::io

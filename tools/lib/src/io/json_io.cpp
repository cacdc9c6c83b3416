#include "helios/io/json_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>

#include "helios/io/error.hpp"

namespace helios::io {
namespace {

// Fixed storage so the signal handler never allocates.
constexpr std::size_t kMaxTemps = 16;
constexpr std::size_t kMaxPath = 4096;
std::array<std::array<char, kMaxPath>, kMaxTemps> g_temps{};
volatile std::sig_atomic_t g_temp_used[kMaxTemps] = {};

void cleanup_and_reraise(int sig) {
  remove_registered_temps();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

std::string temp_name_for(const std::string& path) {
  std::random_device rd;
  std::ostringstream name;
  const auto slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  name << dir << '.' << base << ".tmp." << ::getpid() << '.' << std::hex << rd();
  return name.str();
}

void check_finite(const json& doc) {
  for_each_scalar(doc, [](const json& value, const std::string& where) {
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
      throw numerical_error("refusing to write a non-finite number at " + (where.empty() ? "/" : where));
  });
}

}  // namespace

void for_each_scalar(const json& doc, const std::function<void(const json&, const std::string&)>& visit,
                     const std::string& where) {
  if (doc.is_object())
    for (auto it = doc.begin(); it != doc.end(); ++it) for_each_scalar(it.value(), visit, where + "/" + it.key());
  else if (doc.is_array())
    for (std::size_t i = 0; i < doc.size(); ++i) for_each_scalar(doc[i], visit, where + "/" + std::to_string(i));
  else
    visit(doc, where);
}

void remove_registered_temps() {
  for (std::size_t i = 0; i < kMaxTemps; ++i)
    if (g_temp_used[i]) ::unlink(g_temps[i].data());
}

void install_cleanup_handlers() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) std::signal(sig, cleanup_and_reraise);
}

static void register_temp(const std::string& path) {
  if (path.size() >= kMaxPath) return;
  for (std::size_t i = 0; i < kMaxTemps; ++i) {
    if (g_temp_used[i]) continue;
    std::memcpy(g_temps[i].data(), path.c_str(), path.size() + 1);
    g_temp_used[i] = 1;
    return;
  }
}

static void unregister_temp(const std::string& path) {
  for (std::size_t i = 0; i < kMaxTemps; ++i)
    if (g_temp_used[i] && path == g_temps[i].data()) g_temp_used[i] = 0;
}

TempFiles::TempFiles(std::vector<std::string> paths) : paths_(std::move(paths)) {
  install_cleanup_handlers();
  for (const auto& p : paths_) register_temp(p);
}

TempFiles::~TempFiles() {
  for (const auto& p : paths_) {
    ::unlink(p.c_str());
    unregister_temp(p);
  }
}

namespace {

// Reads `fd` to its end, or throws once it holds more than `limit` bytes.
std::string read_bounded(int fd, std::size_t limit, const std::string& name) {
  std::string out;
  char buf[65536];
  while (true) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n == 0) return out;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw input_error(name + ": read error: " + std::strerror(errno));
    }
    out.append(buf, static_cast<std::size_t>(n));
    if (out.size() > limit) throw input_error(name + ": larger than the limit of " + std::to_string(limit) + " bytes");
  }
}

// Closes a descriptor when it goes out of scope.
struct Descriptor {
  explicit Descriptor(int f) : fd(f) {}
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int fd;
};

}  // namespace

std::string read_text(const std::string& path, std::size_t limit) {
  if (path == "-") return read_bounded(0, limit, "<stdin>");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw input_error(path + ": is a directory, expected a file");
  const Descriptor in(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (in.fd < 0) throw input_error(path + ": cannot read: " + std::strerror(errno));
  return read_bounded(in.fd, limit, path);
}

std::string read_program_file(const std::string& path, std::size_t limit) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer that never comes.
  const Descriptor in(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK));
  if (in.fd < 0)
    throw std::runtime_error(path + ": cannot open" + (errno == ELOOP ? " a symbolic link" : "") + ": " +
                             std::strerror(errno));
  struct stat st;
  if (::fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1)
    throw std::runtime_error(path + ": not a regular file with one link");
  return read_bounded(in.fd, limit, path);
}

std::string short_number(double value) {
  return significant(value, 10);
}

std::string significant(double value, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

bool is_program_file(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_nlink == 1;
}

std::string TempFiles::create_beside(const std::string& path) {
  const std::string tmp = temp_name_for(path);
  register_temp(tmp);  // before it exists: a signal between the two leaves nothing behind
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    unregister_temp(tmp);  // what is there is not ours to delete
    throw std::runtime_error(path + ": cannot create a temp file beside it: " + std::strerror(error));
  }
  ::close(fd);
  paths_.push_back(tmp);
  return tmp;
}

std::size_t json_depth_exceeded_at(const std::string& text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

json parse_json_text(const std::string& text, const std::string& name) {
  if (text.size() > kMaxJsonBytes)
    throw input_error(name + ": the JSON document is " + std::to_string(text.size()) + " bytes; the limit is " +
                      std::to_string(kMaxJsonBytes));
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw input_error(name + ": empty input, expected JSON");
  if (const std::size_t at = json_depth_exceeded_at(text, kMaxJsonDepth); at != std::string::npos)
    throw input_error(name + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels at byte " +
                      std::to_string(at + 1) + "; the limit is " + std::to_string(kMaxJsonDepth));
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw input_error(name + ": malformed JSON at byte " + std::to_string(e.byte) + ", fix the file or regenerate it");
  } catch (const json::out_of_range& e) {
    // The parser's one range error (406): a number literal beyond a double, "... parsing '1e400'".
    const std::string what = e.what();
    const std::size_t open = what.find('\''), close = what.rfind('\'');
    const std::string number = open < close ? what.substr(open + 1, close - open - 1) : "";
    throw input_error(name + ": malformed JSON: the number " + number +
                      " is outside the range of a double (magnitudes up to 1.8e308), fix the file or regenerate it");
  }
}

json read_json(const std::string& path) {
  return parse_json_text(read_text(path), path == "-" ? "<stdin>" : path);
}

void write_text_if_changed(const std::string& path, const std::string& text) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && read_text(path) == text) return;
  if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty())
    std::filesystem::create_directories(parent);
  write_text_atomic(path, text);
}

namespace {

// Writes all of `text` to `fd`; false on an error.
bool write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// Whether `path` (its links followed) is a stream to write into rather than a file to replace: a
// character device (/dev/null, a terminal) or a FIFO. A regular file, or nothing, is replaced; any
// other kind is refused, as renaming over it would replace it.
bool is_stream_target(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return false;
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return true;
  const std::string kind = S_ISDIR(st.st_mode) ? "a directory" : S_ISBLK(st.st_mode) ? "a block device" : "a socket";
  throw std::runtime_error(path + ": is " + kind +
                           ", not a file to write, name a file (or a character device such as /dev/null, or a FIFO)");
}

// Writes `text` into the stream `path` as it is (no temp file, no rename, no truncation).
void write_into_stream(const std::string& path, const std::string& text) {
  const Descriptor out(::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
  if (out.fd < 0 || !write_all(out.fd, text))
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

}  // namespace

void write_text_atomic(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::cout << text << std::flush;
    return;
  }
  if (is_stream_target(path)) return write_into_stream(path, text);
  const std::string tmp = temp_name_for(path);
  const TempFiles guard({tmp});
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) throw std::runtime_error(path + ": cannot create temp file: " + std::strerror(errno));
  bool ok = write_all(fd, text) && ::fsync(fd) == 0;
  ok = (::close(fd) == 0) && ok;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

void move_into_place(const std::string& from, const std::string& path) {
  if (is_stream_target(path)) {
    write_into_stream(path, read_text(from, std::numeric_limits<std::size_t>::max()));
    ::unlink(from.c_str());
    return;
  }
  if (std::rename(from.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
}

void write_json_atomic(const std::string& path, const json& doc) {
  check_finite(doc);
  write_text_atomic(path, doc.dump(2) + "\n");
}

const json& require(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.is_object() || !obj.contains(key)) throw std::invalid_argument("field " + where + "/" + key + " is missing");
  return obj.at(key);
}

double require_number(const json& obj, const std::string& key, const std::string& where) {
  const json& v = require(obj, key, where);
  if (!v.is_number()) throw std::invalid_argument("field " + where + "/" + key + " must be a number, got " + v.dump());
  return v.get<double>();
}

std::string require_string(const json& obj, const std::string& key, const std::string& where) {
  const json& v = require(obj, key, where);
  if (!v.is_string()) throw std::invalid_argument("field " + where + "/" + key + " must be a string, got " + v.dump());
  return v.get<std::string>();
}

}  // namespace helios::io

#pragma once
// Reading and atomic writing of JSON artifacts.
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace helios::io {

using json = nlohmann::ordered_json;

// Bounds of every JSON document the tools read (README "Limits"): checked before parsing, since a
// deep nesting exhausts the stack of the recursive code that walks a document afterwards.
inline constexpr std::size_t kMaxJsonBytes = std::size_t{64} << 20;
inline constexpr int kMaxJsonDepth = 256;

// Whole text of `path` ("-" reads stdin), of at most `limit` bytes: at most limit + 1 bytes are
// read, so /dev/zero or an endless pipe is refused at the limit, not when memory runs out. Throws
// input_error naming the file.
std::string read_text(const std::string& path, std::size_t limit = kMaxJsonBytes);

// A file an untrusted program left behind, read on the host: refused unless it is a regular file
// reached without following a symbolic link (so neither a link to a host file nor a FIFO that would
// block the read), with one link and at most `limit` bytes. Throws std::runtime_error saying why.
std::string read_program_file(const std::string& path, std::size_t limit = kMaxJsonBytes);

// A number as messages and documents quote it: at most 10 significant digits, an exponent where
// that is shorter (1e+300, not its 301 digits).
std::string short_number(double value);

// `value` to `digits` significant digits (printf %.*g): for a value a program computed, in a message.
std::string significant(double value, int digits);

// Whether `path` is such a file (a regular file, not a symbolic link, one link).
bool is_program_file(const std::string& path);

// The first byte offset at which `text` nests arrays and objects deeper than `limit` (strings
// skipped), or std::string::npos.
std::size_t json_depth_exceeded_at(const std::string& text, int limit);

// Parses `text` as JSON, `name` naming it in errors. Throws input_error "NAME: ..." for a document
// beyond the bounds above or malformed JSON.
json parse_json_text(const std::string& text, const std::string& name);

// Parses `path` ("-" = stdin) as JSON. Throws input_error "FILE: malformed JSON at byte N: ...".
json read_json(const std::string& path);

// Writes `text` to `path` atomically: a temp file in the same folder, fsync, rename. "-" writes
// to stdout. The temp file is removed if the process is interrupted (SIGINT/SIGTERM/SIGHUP).
// An existing `path` that is (through its links) a character device such as /dev/null, or a FIFO,
// is written into directly, never renamed over (a FIFO waits for its reader, as a shell's `>`
// does); a directory, block device or socket is refused (std::runtime_error naming it).
void write_text_atomic(const std::string& path, const std::string& text);

// Puts the finished file `from` at `path` by the same rule: renamed over a regular file (or none),
// copied into a character device or FIFO (and then removed), refused for another kind.
void move_into_place(const std::string& from, const std::string& path);

// write_text_atomic unless `path` already holds `text` (its time stamp then stays: make does not
// redo what depends on it), creating the parent folders.
void write_text_if_changed(const std::string& path, const std::string& text);

// Calls visit(value, pointer) for every value of `doc` that is neither an object nor an array,
// with its JSON pointer below `where` ("/constraints/0/id"; "" for a scalar document).
void for_each_scalar(const json& doc, const std::function<void(const json&, const std::string&)>& visit,
                     const std::string& where = "");

// Refuses NaN/Inf anywhere in `doc` (throws numerical_error naming the JSON path), then writes
// it pretty-printed and atomically.
void write_json_atomic(const std::string& path, const json& doc);

// Temporary paths that are deleted when the guard goes out of scope (normal return or exception)
// or when a fatal signal (SIGINT/SIGTERM/SIGHUP/SIGPIPE) arrives first. A path renamed away
// before then is simply gone; deleting it is a no-op.
class TempFiles {
 public:
  explicit TempFiles(std::vector<std::string> paths = {});
  ~TempFiles();
  // A new empty file beside `path` (same folder, a random name starting with '.'), created with
  // O_EXCL | O_NOFOLLOW so that nothing planted there is followed or reused, and guarded by this
  // from before it exists; returns its path.
  std::string create_beside(const std::string& path);
  TempFiles(const TempFiles&) = delete;
  TempFiles& operator=(const TempFiles&) = delete;

 private:
  std::vector<std::string> paths_;
};
// Deletes the registered temp paths now (async-signal-safe: for a signal handler that exits).
void remove_registered_temps();
// Installs the signal handlers that delete registered temp paths (idempotent).
void install_cleanup_handlers();

// Required-field accessors that throw std::invalid_argument "field X: ..." on a wrong shape.
const json& require(const json& obj, const std::string& key, const std::string& where);
double require_number(const json& obj, const std::string& key, const std::string& where);
std::string require_string(const json& obj, const std::string& key, const std::string& where);

}  // namespace helios::io

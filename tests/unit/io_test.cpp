#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "helios/io/cli.hpp"
#include "helios/io/embedded.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/process.hpp"
#include "helios/io/schema.hpp"
#include "helios/io/sha256.hpp"

namespace {

namespace fs = std::filesystem;
using helios::io::json;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("helios-io-test-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(Io, Sha256KnownVectors) {
  EXPECT_EQ(helios::io::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(helios::io::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(helios::io::sha256_hex(std::string(1000, 'a')),
            "41edece42d63e8d9bf515a9ba6932e1c20cbc9f5a5d134645adb5db1b9737ea3");
  // FIPS 180-4's two-block message and its million a's; bytes that are not text.
  EXPECT_EQ(helios::io::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(helios::io::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(helios::io::sha256_hex(std::string(1, '\0')),
            "6e340b9cffb37a989ca544e6bb780a2c78901d3fb33738768511a30617afa01d");
  std::string bytes;
  for (int k = 0; k < 3 * 256; ++k) bytes.push_back(static_cast<char>(k % 256));
  EXPECT_EQ(helios::io::sha256_hex(bytes), "f3a25aa93aa2fbba28d79260535bbd6a5eb0fc1c24a8b0f04e12b484c1dfe363");
}

TEST(Io, AtomicWriteLeavesOnlyTheTarget) {
  const fs::path dir = fresh_dir("atomic");
  helios::io::write_json_atomic((dir / "a.json").string(), json{{"x", 1}});
  helios::io::write_json_atomic((dir / "a.json").string(), json{{"x", 2}});
  EXPECT_EQ(helios::io::read_json((dir / "a.json").string())["x"], 2);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

// An output that is a stream is written into, never renamed over (as root a rename replaced the
// system's /dev/null with a regular file): a FIFO, a link to one, and a private character device
// like /dev/null (root only: mknod) keep their node and get the text; a directory is refused.
TEST(Io, AnOutputThatIsAFifoOrADeviceIsWrittenIntoNeverReplaced) {
  const fs::path dir = fresh_dir("stream");
  const std::string fifo = (dir / "fifo").string(), link = (dir / "link").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(fifo, link);
  const auto node = [](const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? std::to_string(st.st_mode & S_IFMT) + ":" + std::to_string(st.st_ino) : "";
  };
  const std::string fifo_node = node(fifo);
  // A reader is there first (a non-blocking open), so the writer's open does not wait.
  const auto received = [&](const std::function<void()>& write) {
    const int in = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    if (in < 0) return std::string("no reader");
    write();
    std::string got(4096, '\0');
    const ssize_t n = ::read(in, got.data(), got.size());
    ::close(in);
    got.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    return got;
  };
  EXPECT_EQ(received([&] { helios::io::write_json_atomic(fifo, json{{"x", 1}}); }), "{\n  \"x\": 1\n}\n");
  EXPECT_EQ(received([&] { helios::io::write_text_atomic(link, "through the link\n"); }), "through the link\n");
  const std::string finished = (dir / "finished.csv").string();
  helios::io::write_text_atomic(finished, "t,x\n");
  EXPECT_EQ(received([&] { helios::io::move_into_place(finished, fifo); }), "t,x\n");
  EXPECT_FALSE(fs::exists(finished));
  EXPECT_EQ(node(fifo), fifo_node);
  EXPECT_TRUE(fs::is_symlink(link));
  std::set<std::string> expected = {"fifo", "folder", "link"};
  if (::geteuid() == 0) {
    expected.insert("null");
    const std::string null = (dir / "null").string();
    ASSERT_EQ(::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
    const std::string null_node = node(null);
    helios::io::write_text_atomic(null, "discarded\n");
    helios::io::write_text_atomic(finished, "t,x\n");
    helios::io::move_into_place(finished, null);
    EXPECT_EQ(node(null), null_node);
    EXPECT_TRUE(fs::is_character_file(null));
  }
  fs::create_directory(dir / "folder");
  try {
    helios::io::write_text_atomic((dir / "folder").string(), "x");
    ADD_FAILURE() << "a directory was written";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "folder").string() +
                                         ": is a directory, not a file to write, name a file (or a character device "
                                         "such as /dev/null, or a FIFO)");
  }
  // Nothing else was left: no temp file beside the streams.
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, expected);
  fs::remove_all(dir);
}

// Readers stop at their limit: at most limit + 1 bytes are read, from a file or an endless device.
TEST(Io, ReadTextStopsAtItsLimit) {
  const fs::path dir = fresh_dir("limit");
  helios::io::write_text_atomic((dir / "ten.txt").string(), "0123456789");
  EXPECT_EQ(helios::io::read_text((dir / "ten.txt").string(), 10), "0123456789");
  EXPECT_THROW(helios::io::read_text((dir / "ten.txt").string(), 9), helios::input_error);
  try {
    helios::io::read_text("/dev/zero", 1000);
    ADD_FAILURE() << "/dev/zero was read";
  } catch (const helios::input_error& e) {
    EXPECT_STREQ(e.what(), "/dev/zero: larger than the limit of 1000 bytes");
  }
  fs::remove_all(dir);
}

// What an untrusted program left is read only as a regular file of its own: a link to a host file,
// a FIFO (which would block the reader), a hard link to a host file and an oversized file are refused.
TEST(Io, AProgramsFileIsReadOnlyWhenItIsARegularFileOfItsOwn) {
  const fs::path dir = fresh_dir("program-file");
  const std::string plain = (dir / "plain.json").string(), link = (dir / "link.json").string(),
                    fifo = (dir / "fifo.json").string(), hard = (dir / "hard.json").string();
  helios::io::write_text_atomic(plain, "{}");
  fs::create_symlink("/etc/passwd", link);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_hard_link(plain, hard);
  EXPECT_FALSE(helios::io::is_program_file(link));
  EXPECT_FALSE(helios::io::is_program_file(fifo));
  EXPECT_FALSE(helios::io::is_program_file(plain)) << "two links";
  EXPECT_THROW(helios::io::read_program_file(link), std::runtime_error);
  EXPECT_THROW(helios::io::read_program_file(fifo), std::runtime_error);  // at once, not blocked
  EXPECT_THROW(helios::io::read_program_file(hard), std::runtime_error);
  fs::remove(hard);
  EXPECT_TRUE(helios::io::is_program_file(plain));
  EXPECT_EQ(helios::io::read_program_file(plain), "{}");
  EXPECT_THROW(helios::io::read_program_file(plain, 1), std::runtime_error);
  fs::remove_all(dir);
}

// A temporary file beside a target is new: a link planted under any name is never opened.
TEST(Io, ATempFileBesideATargetIsAlwaysNew) {
  const fs::path dir = fresh_dir("temp-beside");
  const std::string target = (dir / "plot.png").string();
  {
    helios::io::TempFiles temps;
    const std::string a = temps.create_beside(target), b = temps.create_beside(target);
    EXPECT_NE(a, b);
    EXPECT_EQ(fs::path(a).parent_path(), dir);
    EXPECT_TRUE(fs::is_regular_file(a) && !fs::is_symlink(a) && fs::file_size(a) == 0);
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "the guard removes what it created";
  fs::remove_all(dir);
}

TEST(Io, NonFiniteNumbersAreRefusedAndNothingIsWritten) {
  const fs::path dir = fresh_dir("nan");
  const json doc = {{"a", {{"b", json::array({1.0, NAN})}}}};
  try {
    helios::io::write_json_atomic((dir / "x.json").string(), doc);
    FAIL() << "NaN was written";
  } catch (const helios::numerical_error& e) {
    EXPECT_STREQ(e.what(), "refusing to write a non-finite number at /a/b/1");
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(Io, MalformedJsonNamesTheFileAndByte) {
  const fs::path dir = fresh_dir("malformed");
  const std::string path = (dir / "bad.json").string();
  helios::io::write_text_atomic(path, "{\"a\": }");
  try {
    helios::io::read_json(path);
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": malformed JSON at byte 7, fix the file or regenerate it");
  }
  fs::remove_all(dir);
}

// Found by the json_settings fuzz target: nlohmann's out_of_range (406) reached the user raw.
TEST(Io, JsonNumberBeyondADoubleIsInvalidInput) {
  try {
    helios::io::parse_json_text(R"({"seed": 1e3083})", "x.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_STREQ(e.what(),
                 "x.json: malformed JSON: the number 1e3083 is outside the range of a double (magnitudes up to "
                 "1.8e308), fix the file or regenerate it");
  }
}

TEST(Io, JsonBeyondItsDepthIsRefusedBeforeParsingStringsAside) {
  using helios::io::json_depth_exceeded_at;
  using helios::io::kMaxJsonDepth;
  // 58,000 levels overflowed the stack; brackets inside strings are not nesting.
  const std::string deep = std::string(58000, '[') + std::string(58000, ']');
  EXPECT_EQ(json_depth_exceeded_at(deep, kMaxJsonDepth), std::size_t(kMaxJsonDepth));
  const std::string at_limit = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_EQ(json_depth_exceeded_at(at_limit, kMaxJsonDepth), std::string::npos);
  EXPECT_EQ(json_depth_exceeded_at(R"({"a": "[[[[\"[[[", "b": [1]})", 2), std::string::npos);
  EXPECT_NO_THROW(helios::io::parse_json_text(at_limit, "x.json"));
  try {
    helios::io::parse_json_text(deep, "x.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_STREQ(e.what(), "x.json: JSON nested deeper than 256 levels at byte 257; the limit is 256");
  }
}

// Found by the json_spec fuzz target: a schema or schema_version of another type than expected
// made json::value() throw nlohmann's type_error 302, which reached the user raw.
TEST(Io, ArtifactHeaderOfAnotherTypeIsInvalidInput) {
  try {
    helios::io::parse_artifact("spec", R"({"schema": {"name": "Earth"}})", "x.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_STREQ(
        e.what(),
        "x.json: field /schema is {\"name\":\"Earth\"}, expected \"helios/spec\" (wrong artifact for this tool?)");
  }
  try {
    helios::io::parse_artifact("spec", R"({"schema": "helios/spec", "schema_version": "1"})", "x.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_STREQ(e.what(), "x.json: field /schema_version is \"1\", this build reads version 1");
  }
}

TEST(Io, ReadArtifactChecksKindAndVersion) {
  const fs::path dir = fresh_dir("kind");
  const std::string path = (dir / "x.json").string();
  helios::io::write_json_atomic(path, helios::io::artifact_header("spec", "t", "builtin"));
  EXPECT_THROW(helios::io::read_artifact("derivation", path), helios::input_error);
  json doc = helios::io::artifact_header("spec", "t", "builtin");
  doc["schema_version"] = 99;
  helios::io::write_json_atomic(path, doc);
  try {
    helios::io::read_artifact("spec", path);
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": field /schema_version is 99, this build reads version 1");
  }
  // A header field of the wrong type gave nlohmann's "type_error.302"; not an object, .316.
  const auto error_of = [&](const std::string& text) {
    helios::io::write_text_atomic(path, text);
    try {
      helios::io::read_artifact("spec", path);
    } catch (const helios::input_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of(R"({"schema": "helios/spec", "schema_version": "1"})"),
            path + ": field /schema_version is \"1\", this build reads version 1");
  EXPECT_EQ(error_of(R"({"schema": ["helios/spec"]})"),
            path + ": field /schema is [\"helios/spec\"], expected \"helios/spec\" (wrong artifact for this tool?)");
  EXPECT_EQ(error_of("[1]"), path +
                                 ": field /schema is absent (not a JSON object), expected \"helios/spec\" (wrong "
                                 "artifact for this tool?)");
  EXPECT_EQ(
      error_of(R"({"schema": "helios/spec\u001b[2J"})"),
      path + R"(: field /schema is "helios/spec\u001b[2J", expected "helios/spec" (wrong artifact for this tool?))");
  fs::remove_all(dir);
}

TEST(Io, SchemaViolationNamesThePath) {
  json doc = helios::io::artifact_header("spec", "t", "builtin");
  doc["problem"] = {{"id", "S01"}, {"title", "x"}};
  doc["central_body"] = {{"name", "Sun"}, {"mu_km3_s2", -1.0}};
  try {
    helios::io::validate("spec", doc, "spec.json");
    FAIL();
  } catch (const helios::input_error& e) {
    EXPECT_NE(std::string(e.what()).find("spec.json: spec schema violation at "), std::string::npos) << e.what();
  }
}

// The settings schema is the one list of solver settings: exactly the keys the runtime reads.
TEST(Io, SettingsSchemaListsExactlyTheKeysTheRuntimeReads) {
  const std::string runtime = helios::io::read_text(HELIOS_SOURCE_DIR "/templates/runtime/report.hpp");
  std::set<std::string> read;
  const std::regex key(R"re(j\.value\("([a-z_0-9]+)")re");
  for (auto it = std::sregex_iterator(runtime.begin(), runtime.end(), key); it != std::sregex_iterator(); ++it)
    read.insert((*it)[1]);
  const auto listed = helios::io::schema_properties("settings");
  EXPECT_EQ(read, std::set<std::string>(listed.begin(), listed.end()));
  EXPECT_GE(listed.size(), 18u);
}

// Types and ranges: a seed beyond 32 bits, a ratio of 0 (an eps continuation that never moves)
// and a fractional count are refused naming the field.
TEST(Io, SettingsOutOfRangeAreRefusedNamingTheField) {
  const auto refused = [](const json& settings) -> std::string {
    try {
      helios::io::validate("settings", settings, "settings.json");
    } catch (const helios::input_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refused(json::parse(R"({"seed": 7, "search_starts": 64, "threads": 0, "eps_first_ratio": 0.5})")), "");
  EXPECT_NE(refused(json::parse(R"({"seed": 1e30})")).find("settings.json: settings schema violation at /seed"),
            std::string::npos);
  EXPECT_NE(refused(json::parse(R"({"eps_first_ratio": 0})")).find("at /eps_first_ratio"), std::string::npos);
  EXPECT_NE(refused(json::parse(R"({"max_attempts": 2.5})")).find("at /max_attempts"), std::string::npos);
  EXPECT_NE(refused(json::parse(R"({"max_attempts": 1e12})")).find("at /max_attempts"), std::string::npos);
  EXPECT_NE(refused(json::parse(R"({"seed": "1"})")).find("at /seed"), std::string::npos);
  // the search's integrator tolerance: 0 (the integrator's own) up to 1e-3
  EXPECT_EQ(refused(json::parse(R"({"search_integrator_tol": 0})")), "");
  EXPECT_EQ(refused(json::parse(R"({"search_integrator_tol": 1e-9})")), "");
  EXPECT_NE(refused(json::parse(R"({"search_integrator_tol": -1e-10})")).find("at /search_integrator_tol"),
            std::string::npos);
  EXPECT_NE(refused(json::parse(R"({"search_integrator_tol": 0.1})")).find("at /search_integrator_tol"),
            std::string::npos);
}

TEST(Io, CliRejectsUnknownOptionsAndCountsInputs) {
  const helios::cli::ToolInfo info{"helios-x", "test", "IN",         {{"flag", "", "", "a flag", ""}},
                                   {"IN"},     "",     "helios-x in"};
  helios::cli::Args args;
  const char* bad[] = {"helios-x", "--nope", "in"};
  EXPECT_THROW(helios::cli::parse_args(info, 3, const_cast<char**>(bad), args), helios::usage_error);
  const char* none[] = {"helios-x"};
  EXPECT_THROW(helios::cli::parse_args(info, 1, const_cast<char**>(none), args), helios::usage_error);
  const char* good[] = {"helios-x", "--flag", "-o", "out.json", "-"};
  helios::cli::Args ok;
  ASSERT_TRUE(helios::cli::parse_args(info, 5, const_cast<char**>(good), ok));
  EXPECT_EQ(ok.output, "out.json");
  EXPECT_EQ(ok.positionals.at(0), "-");
  EXPECT_TRUE(ok.has("flag"));
  EXPECT_NE(helios::cli::help_text(info).find("\ne.g.: helios-x in\n"), std::string::npos);
}

}  // namespace

// A library's "field /x: ..." about a tool's input names the file; a message that names it
// already, and any other error, pass unchanged.
// A folder option (--cache-dir) that names a file, or a path through one, is a one-line usage
// error naming the option and its value; a missing folder (made later) or an existing one is taken.
TEST(Cli, AFolderOptionNamingAFileIsRefusedNamingTheOption) {
  const fs::path dir = fresh_dir("folder-option");
  helios::io::write_text_atomic((dir / "file").string(), "x");
  const auto error_of = [](const std::string& value) {
    helios::cli::Args args;
    args.values["cache-dir"] = value;
    try {
      EXPECT_EQ(helios::cli::folder_option(args, "cache-dir"), value);
    } catch (const helios::usage_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string file = (dir / "file").string();
  EXPECT_EQ(error_of(file), "--cache-dir " + file + ": is not a folder, name a folder (it is made when missing)");
  EXPECT_EQ(error_of(file + "/sub/deeper"), "--cache-dir " + file + "/sub/deeper: " + file +
                                                " is not a folder, name a folder (it is made when missing)");
  EXPECT_EQ(error_of("/dev/null"), "--cache-dir /dev/null: is not a folder, name a folder (it is made when missing)");
  EXPECT_EQ(error_of((dir / "new" / "cache").string()), "");
  EXPECT_EQ(error_of(dir.string()), "");
  EXPECT_EQ(error_of("relative-and-new"), "");
  fs::remove_all(dir);
}

TEST(Cli, NamingInputPrefixesTheFileOnce) {
  const auto error_of = [](const std::string& source, const std::function<void()>& work) {
    try {
      helios::cli::naming_input(source, work);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of("d.json", [] { throw std::invalid_argument("field /hamiltonian: bad"); }),
            "d.json: field /hamiltonian: bad");
  EXPECT_EQ(error_of("-", [] { throw std::domain_error("mu is not finite"); }), "<stdin>: mu is not finite");
  EXPECT_EQ(error_of("d.json", [] { throw helios::input_error("d.json: malformed JSON"); }), "d.json: malformed JSON");
  EXPECT_EQ(error_of("d.json", [] { throw std::runtime_error("disk full"); }), "disk full");
  EXPECT_THROW(helios::cli::naming_input("d.json", [] { throw std::invalid_argument("x"); }), helios::input_error);
}

// A tool of several jobs: the flag given selects one, which refuses the options of the others and
// names a missing one; with no flag, the default job.
TEST(Cli, SelectModeRefusesTheOptionsOfOtherJobs) {
  helios::cli::ToolInfo info;
  info.name = "helios-x";
  info.options = {{"in", "", "FILE", "", ""},  {"report", "", "", "", ""}, {"problem", "", "FILE", "", ""},
                  {"level", "", "N", "", "3"}, {"oem", "", "", "", ""},    {"track", "", "FILE", "", ""}};
  const std::vector<helios::cli::Mode> modes = {{"", {"in"}, {"level"}, [](const auto&) { return 0; }},
                                                {"report", {"problem"}, {"level"}, [](const auto&) { return 1; }},
                                                {"oem", {"track"}, {}, [](const auto&) { return 2; }}};
  const auto args_of = [](std::map<std::string, std::string> values) {
    helios::cli::Args a;
    a.values = std::move(values);
    a.values.emplace("level", "3");  // a default is not an option given
    return a;
  };
  const auto error_of = [&](const helios::cli::Args& a) {
    try {
      helios::cli::select_mode(info, a, modes);
    } catch (const helios::usage_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(helios::cli::select_mode(info, args_of({{"in", "f"}}), modes).run({}), 0);
  EXPECT_EQ(helios::cli::select_mode(info, args_of({{"report", "1"}, {"problem", "p"}}), modes).run({}), 1);
  EXPECT_EQ(helios::cli::select_mode(info, args_of({{"oem", "1"}, {"track", "t"}}), modes).run({}), 2);
  EXPECT_EQ(error_of(args_of({{"report", "1"}, {"oem", "1"}})),
            "--report and --oem are two jobs: give one, see helios-x --help");
  EXPECT_EQ(error_of(args_of({{"report", "1"}})), "--report needs --problem FILE, see helios-x --help");
  EXPECT_EQ(error_of(args_of({})), "missing --in FILE, see helios-x --help");
  EXPECT_EQ(error_of(args_of({{"in", "f"}, {"problem", "p"}})), "--problem goes with --report, see helios-x --help");
  EXPECT_EQ(error_of(args_of({{"report", "1"}, {"problem", "p"}, {"track", "t"}})),
            "--report takes no --track (it goes with --oem), see helios-x --help");
  EXPECT_EQ(error_of(args_of({{"oem", "1"}, {"track", "t"}, {"level", "4"}})),
            "--oem takes no --level (it goes with --report), see helios-x --help");
}

// run_all: each command's exit code in the order given, whatever order they end in.
TEST(Process, RunAllGivesEachExitCodeInOrder) {
  using helios::io::run_all;
  EXPECT_EQ(run_all({{"sh", "-c", "exit 3"}, {"sh", "-c", "exit 0"}, {"sh", "-c", "exit 5"}}, 2),
            (std::vector<int>{3, 0, 5}));
  // The first ends last: its code stays first.
  EXPECT_EQ(run_all({{"sh", "-c", "sleep 0.3; exit 4"}, {"sh", "-c", "exit 1"}, {"sh", "-c", "exit 2"}}, 2),
            (std::vector<int>{4, 1, 2}));
  // A program that cannot be executed is 127, one a signal ends is -1; jobs below 1 is one at a time.
  EXPECT_EQ(run_all({{"helios-no-such-program"}, {"sh", "-c", "kill -KILL $$"}}, 0), (std::vector<int>{127, -1}));
  EXPECT_TRUE(run_all({}, 2).empty());
}

// run_all with two jobs runs two at once: each command waits (5 s at most) for the other's file.
TEST(Process, RunAllRunsJobsAtATime) {
  const fs::path dir = fresh_dir("run-all");
  const auto waits_for = [&](const std::string& mine, const std::string& other) {
    const std::string theirs = "'" + (dir / other).string() + "'";
    return std::vector<std::string>{"sh", "-c",
                                    "touch '" + (dir / mine).string() + "'; i=0; while [ ! -e " + theirs +
                                        " ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i+1)); done; [ -e " + theirs + " ]"};
  };
  EXPECT_EQ(helios::io::run_all({waits_for("a", "b"), waits_for("b", "a")}, 2), (std::vector<int>{0, 0}));
  fs::remove_all(dir);
}

TEST(Process, CaptureOnPathAndTheTextOfALine) {
  EXPECT_EQ(helios::io::capture({"sh", "-c", "echo out; echo err >&2"}), "out\nerr\n");
  const std::string sh = helios::io::on_path("sh");
  EXPECT_EQ(fs::path(sh).filename(), "sh");
  EXPECT_EQ(::access(sh.c_str(), X_OK), 0);
  EXPECT_EQ(helios::io::on_path("./x"), "./x");
  EXPECT_EQ(helios::io::first_line("one\ntwo"), "one");
  EXPECT_EQ(helios::io::printable_line("a\nb\x1b[1m", 500), "a?b?[1m");
  EXPECT_EQ(helios::io::printable_line(std::string(10, 'x'), 4), "xxxx...");
  EXPECT_EQ(helios::io::limit_text(900), "900");
  EXPECT_EQ(helios::io::limit_text(0.5), "0.5");
}

// helios-solve's child limits for untrusted programs: wall clock, working directory, and no
// process left behind (process group + child subreaper).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "helios/codegen/generate.hpp"
#include "helios/io/error.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/solve/runtime_files.hpp"
#include "helios/solve/solve.hpp"
#include "helios/spec/parse.hpp"

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("helios-sandbox-test-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(Sandbox, RunsInTheGivenWorkingDirectory) {
  const fs::path dir = fresh_dir("cwd");
  const auto r = helios::solve::run_limited({"/bin/sh", "-c", "pwd > where.txt"}, 10, 512, dir.string());
  EXPECT_EQ(r.exit_code, 0);
  std::ifstream in(dir / "where.txt");
  std::string where;
  std::getline(in, where);
  EXPECT_EQ(fs::canonical(where), fs::canonical(dir));
  fs::remove_all(dir);
}

// The search's progress: each stderr line reaches the caller while the program still runs, its
// control bytes replaced (a program cannot drive the user's terminal), and the text is kept too.
TEST(Sandbox, StderrLinesAreForwardedAsTheyComeCleaned) {
  const fs::path dir = fresh_dir("lines");
  std::vector<std::string> lines;
  std::vector<double> arrived;
  const auto start = std::chrono::steady_clock::now();
  const auto r = helios::solve::run_limited(
      {"/bin/sh", "-c", "printf 'one\\n' >&2; sleep 0.5; printf '\\033[31mtwo\\nthree' >&2"}, 10, 512, dir.string(),
      [&](const std::string& line) {
        lines.push_back(line);
        arrived.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      });
  EXPECT_EQ(r.exit_code, 0);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "one");
  EXPECT_EQ(lines[1], "?[31mtwo");
  EXPECT_EQ(lines[2], "three");  // the last line without its newline, at the end
  EXPECT_LT(arrived[0], arrived[1] - 0.3) << "the first line came while the program slept";
  EXPECT_EQ(r.output_text, "one\n\033[31mtwo\nthree");
  fs::remove_all(dir);
}

// What a program prints on stdout joins its stderr in the capped collector (never the tool's own
// stdout), and the line quoted as the failure is the last one naming an error.
TEST(Sandbox, StdoutIsCollectedAndTheErrorLineIsTheOneNamingAnError) {
  const fs::path dir = fresh_dir("stdout");
  std::vector<std::string> lines;
  const auto r =
      helios::solve::run_limited({"/bin/sh", "-c",
                                  "echo '{\"schema\": \"fake\"}'; echo 'shoot: error: the settings are unusable' >&2; "
                                  "echo 'progress 3 of 4' >&2; head -c 200000 /dev/zero | tr '\\0' x; exit 3"},
                                 10, 512, dir.string(), [&](const std::string& line) { lines.push_back(line); });
  EXPECT_EQ(r.exit_code, 3);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[0], "{\"schema\": \"fake\"}");
  EXPECT_EQ(r.error_line, "shoot: error: the settings are unusable");
  EXPECT_EQ(r.output_text.size(), 64u * 1024u) << "capped";
  fs::remove_all(dir);
}

// Titles and file names reach gnuplot as its ARG1.. data: quotes, system() and backquotes in them
// run nothing.
TEST(Gnuplot, ArgumentsAreDataNotCommands) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  const fs::path dir = fresh_dir("gnuplot");
  const std::string marker = (dir / "PWNED").string();
  const std::string png = (dir / "t.png").string();
  for (const std::string& title : {"x'.system('touch " + marker + "').'", "`touch " + marker + "`",
                                   "@ARG9 \"; system(\"touch " + marker + "\")"}) {
    helios::solve::run_gnuplot("set terminal pngcairo noenhanced\nset output ARG1\nset title ARG2\nplot x\n",
                               {png, title});
    EXPECT_FALSE(fs::exists(marker)) << title;
    EXPECT_GT(fs::file_size(png), 0u) << title;
  }
  fs::remove_all(dir);
}

TEST(Sandbox, ALoopingProgramIsKilledAtTheWallClockAndLeavesNothingRunning) {
  const fs::path dir = fresh_dir("loop");
  // Children in the group, and one that left it with setsid; their pids go to a file.
  const std::string script = "sleep 300 & echo $! >> pids; setsid sleep 300 & echo $! >> pids; while :; do :; done";
  const auto r = helios::solve::run_limited({"/bin/sh", "-c", script}, 1.0, 512, dir.string());
  EXPECT_TRUE(r.timed_out);
  EXPECT_GE(r.seconds, 1.0);
  EXPECT_LT(r.seconds, 5.0);
  std::ifstream pids(dir / "pids");
  int pid = 0, n = 0;
  while (pids >> pid) {
    ++n;
    EXPECT_NE(::kill(pid, 0), 0) << "process " << pid << " is still alive";
  }
  EXPECT_EQ(n, 2);
  fs::remove_all(dir);
}

TEST(Sandbox, AProgramThatExitsButLeavesADaemonHasItKilled) {
  const fs::path dir = fresh_dir("daemon");
  const auto r =
      helios::solve::run_limited({"/bin/sh", "-c", "setsid sleep 300 & echo $! > pid; exit 0"}, 10, 512, dir.string());
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.leftover_processes, 1);
  std::ifstream in(dir / "pid");
  int pid = 0;
  in >> pid;
  ASSERT_GT(pid, 0);
  EXPECT_NE(::kill(pid, 0), 0);
  fs::remove_all(dir);
}

TEST(RunFolders, AnEndedRunsFolderGoesARunningOnesStaysAndAZombieHasEnded) {
  const fs::path dir = fresh_dir("stale");
  // A zombie: a child that has exited and is not yet reaped, as a killed helios-solve stays under
  // an init that reaps slowly; kill(pid, 0) still finds it.
  const pid_t zombie = ::fork();
  ASSERT_GE(zombie, 0);
  if (zombie == 0) _exit(0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const pid_t running = ::fork();
  ASSERT_GE(running, 0);
  if (running == 0) {
    ::pause();
    _exit(0);
  }
  const auto folder = [&](pid_t pid) {
    const fs::path p = dir / (".run." + std::to_string(pid) + ".Ab3xYz");
    fs::create_directories(p);
    std::ofstream(p / "outcome.json.part") << "{";
    return p;
  };
  const fs::path of_zombie = folder(zombie), of_running = folder(running), mine = folder(::getpid());
  const fs::path not_a_run_folder = dir / (".run." + std::to_string(zombie) + ".toolongname");
  fs::create_directories(not_a_run_folder);
  ASSERT_EQ(::kill(zombie, 0), 0);
  helios::solve::remove_stale_run_folders(dir.string());
  EXPECT_FALSE(fs::exists(of_zombie));
  EXPECT_TRUE(fs::exists(of_running));
  EXPECT_TRUE(fs::exists(mine));
  EXPECT_TRUE(fs::exists(not_a_run_folder));
  ::kill(running, SIGKILL);
  ::waitpid(running, nullptr, 0);
  ::waitpid(zombie, nullptr, 0);
  helios::solve::remove_stale_run_folders(dir.string());
  EXPECT_FALSE(fs::exists(of_running));
  fs::remove_all(dir);
}

TEST(Sandbox, AnUnboundedAllocationIsStoppedByTheAddressSpaceLimit) {
  const auto r =
      helios::solve::run_limited({"/usr/bin/perl", "-e", "my @a; push @a, 'x' x 1_000_000 while 1"}, 20, 64, "");
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.exit_code, 0);
}

// The compile cache's key covers the prebuilt runtime: the same source and command against a
// rebuilt runtime (another SHA-256) is another program, so a cached binary is not reused. A text
// keyed as a whole source and the same text keyed as a structure are two keys, and no two lists of
// fields hash the same bytes.
TEST(Compile, TheCacheKeyChangesWithTheRuntimeAndKeyKindsAreApart) {
  using helios::solve::compile_key;
  using helios::solve::KeyKind;
  const std::string source = "int main() {}\n", command = "g++ -O2 shoot.cpp", version = "g++ 12";
  const std::string a(64, 'a'), b(64, 'b');
  EXPECT_EQ(compile_key(KeyKind::Structure, source, command, version, a),
            compile_key(KeyKind::Structure, source, command, version, a));
  EXPECT_NE(compile_key(KeyKind::Structure, source, command, version, a),
            compile_key(KeyKind::Structure, source, command, version, b));
  EXPECT_NE(compile_key(KeyKind::Structure, source, command, version, a),
            compile_key(KeyKind::Structure, source + " ", command, version, a));
  EXPECT_NE(compile_key(KeyKind::Source, source, command, version, a),
            compile_key(KeyKind::Structure, source, command, version, a));
  EXPECT_NE(compile_key(KeyKind::Source, "x\ny", "z", version, a),
            compile_key(KeyKind::Source, "x", "y\nz", version, a));
}

// The compiler's identity and the runtime's hash are kept by the stamps of their files: computed
// once while the files stay as they were, again when one changes, never kept for a file changed in
// the last two seconds (its stamp could repeat within one tick of the clock), and not taken from a
// memo that others may write or that is not one.
TEST(Compile, AValueKeptByItsFilesStampsIsComputedAgainOnlyWhenOneChanges) {
  const fs::path dir = fresh_dir("memo");
  const std::string file = (dir / "compiler").string(), memo = (dir / "memo.json").string();
  const auto an_hour_ago = fs::file_time_type::clock::now() - std::chrono::hours(1);
  std::ofstream(file) << "version 1";
  fs::last_write_time(file, an_hour_ago);
  int computed = 0;
  const auto value = [&] {
    return helios::solve::memo_by_stamps(memo, {file}, [&] {
      ++computed;
      return helios::io::read_text(file);
    });
  };
  EXPECT_EQ(value(), "version 1");
  EXPECT_EQ(value(), "version 1");
  EXPECT_EQ(computed, 1);
  std::ofstream(file) << "version 2";  // the same size, another time
  fs::last_write_time(file, an_hour_ago + std::chrono::seconds(1));
  EXPECT_EQ(value(), "version 2");
  EXPECT_EQ(value(), "version 2");
  EXPECT_EQ(computed, 2);
  std::ofstream(file) << "version 3";  // just now: not kept
  EXPECT_EQ(value(), "version 3");
  EXPECT_EQ(value(), "version 3");
  EXPECT_EQ(computed, 4);
  fs::last_write_time(file, an_hour_ago);
  EXPECT_EQ(value(), "version 3");
  fs::permissions(memo, fs::perms::group_write, fs::perm_options::add);
  EXPECT_EQ(value(), "version 3");
  EXPECT_EQ(computed, 6) << "a memo others may write is not read";
  std::ofstream(memo) << "{\"stamps\": 1}";
  EXPECT_EQ(value(), "version 3");
  EXPECT_EQ(value(), "version 3");
  EXPECT_EQ(computed, 7) << "a malformed memo is replaced";
  fs::remove_all(dir);
}

// A compile against the runtime found beside this executable records a command that rebuilds the
// program by hand: the header's folder and the library by absolute path.
TEST(Compile, TheCommandNamesTheRuntimeByAbsolutePath) {
  const helios::solve::RuntimeFiles& runtime = helios::solve::runtime_files();
  ASSERT_TRUE(fs::path(runtime.library).is_absolute());
  EXPECT_TRUE(fs::is_regular_file(runtime.library));
  EXPECT_TRUE(fs::is_regular_file(fs::path(runtime.include_dir) / "helios_runtime.hpp"));
  EXPECT_EQ(helios::solve::runtime_sha256().size(), 64u);
  const fs::path dir = fresh_dir("compile");
  helios::solve::SolveOptions o;
  o.cache_dir = dir.string();
  o.sandbox = false;
  const auto c = helios::solve::compile_cached("#include \"helios_runtime.hpp\"\nint main() {}\n", o);
  EXPECT_NE(c.command.find(" -I" + runtime.include_dir + " "), std::string::npos) << c.command;
  EXPECT_NE(c.command.find(" " + runtime.library + " "), std::string::npos) << c.command;
  fs::remove_all(dir);
}

// Two solves of one structure at once (a sweep's rows under make -j): one compiles, the other waits
// for it and takes the program from the cache.
TEST(Compile, ConcurrentCompilesOfOneStructureCompileOnce) {
  const fs::path dir = fresh_dir("compile-once");
  helios::solve::SolveOptions o;
  o.cache_dir = dir.string();
  o.sandbox = false;
  const std::string source = "#include \"helios_runtime.hpp\"\nint main() {}\n";
  helios::solve::CompileResult first, second;
  std::thread other([&] { second = helios::solve::compile_cached(source, o); });
  first = helios::solve::compile_cached(source, o);
  other.join();
  ASSERT_TRUE(first.ok && second.ok);
  EXPECT_NE(first.cached, second.cached) << "both compiled, or neither";
  EXPECT_EQ(first.binary, second.binary);
  fs::remove_all(dir);
}

// A text that is another source's structure (its numbers masked, so it cannot compile) is keyed as
// a whole source: it is never served the program compiled under that structure.
TEST(Compile, AMaskedTextIsNotServedTheProgramOfItsStructure) {
  const fs::path dir = fresh_dir("key-kinds");
  helios::solve::SolveOptions o;
  o.cache_dir = dir.string();
  o.sandbox = false;
  const std::string source =
      helios::codegen::generate(helios::pmp::derive_from_spec(helios::spec::parse_problem_text(
                                    helios::io::read_text(HELIOS_SOURCE_DIR "/scenarios/S01/problem.txt"), "S01")),
                                {})
          .source;
  const auto compiled = helios::solve::compile_cached(source, o);
  ASSERT_TRUE(compiled.ok && compiled.parameters.readable);
  const auto masked = helios::solve::compile_cached(compiled.parameters.structure, o);
  EXPECT_FALSE(masked.parameters.readable);
  EXPECT_NE(masked.structure_sha256, compiled.structure_sha256);
  EXPECT_FALSE(masked.cached);
  EXPECT_FALSE(masked.ok);
  fs::remove_all(dir);
}

// A cache entry is used only when it is this user's alone and whole: a program that does not
// match its stored hash, a compile.log planted as a link, a program others may write are
// compiled anew (the link not followed); an entry folder that is a link is refused.
TEST(Compile, ACacheEntryIsUsedOnlyWhenPrivateAndWhole) {
  const fs::path dir = fresh_dir("entries");
  helios::solve::SolveOptions o;
  o.cache_dir = (dir / "cache").string();
  o.sandbox = false;
  const std::string source = "#include \"helios_runtime.hpp\"\nint main() {}\n";
  const auto first = helios::solve::compile_cached(source, o);
  ASSERT_TRUE(first.ok);
  EXPECT_EQ(first.binary_sha256.size(), 64u);
  const fs::path entry = fs::path(first.binary).parent_path();
  const auto again = [&] { return helios::solve::compile_cached(source, o); };
  EXPECT_TRUE(again().cached);
  {  // another program in its place: not the hash stored
    std::ofstream(entry / "shoot", std::ios::binary | std::ios::trunc) << "#!/bin/sh\necho planted\n";
    const auto c = again();
    EXPECT_FALSE(c.cached);
    EXPECT_EQ(c.program, first.program);
  }
  {  // compile.log a link to a secret
    std::ofstream(dir / "secret") << "SECRET-TEXT";
    fs::remove(entry / "compile.log");
    fs::create_symlink(dir / "secret", entry / "compile.log");
    const auto c = again();
    EXPECT_FALSE(c.cached);
    EXPECT_EQ(c.diagnostics.find("SECRET-TEXT"), std::string::npos);
    EXPECT_FALSE(fs::is_symlink(entry / "compile.log"));
  }
  {  // a program others may write
    fs::permissions(entry / "shoot", fs::perms::group_write, fs::perm_options::add);
    EXPECT_FALSE(again().cached);
    EXPECT_TRUE(again().cached);
  }
  {  // the entry folder a link to a copy of itself
    fs::rename(entry, dir / "copy");
    fs::create_directory_symlink(dir / "copy", entry);
    EXPECT_THROW(again(), std::runtime_error);
  }
  fs::remove_all(dir);
}

// The thread count a scheduler's task is given: srun -c1 cells of a sweep must not each run a
// search on every core of the node. A settings file's own nonzero `threads` wins.
TEST(SolveSettings, TheSearchThreadsFollowSlurmCpusPerTaskUnlessTheSettingsSayOtherwise) {
  const fs::path dir = fresh_dir("threads");
  helios::solve::SolveOptions o;
  ::unsetenv("SLURM_CPUS_PER_TASK");
  EXPECT_EQ(helios::solve::scheduler_cpus_per_task(), 0);
  EXPECT_FALSE(helios::solve::run_settings(o).contains("threads"));
  ::setenv("SLURM_CPUS_PER_TASK", "1", 1);
  EXPECT_EQ(helios::solve::run_settings(o).at("threads"), 1);
  o.settings_path = (dir / "settings.json").string();
  std::ofstream(o.settings_path) << R"({"threads": 3})";
  EXPECT_EQ(helios::solve::run_settings(o).at("threads"), 3);
  std::ofstream(o.settings_path) << R"({"threads": 0})";
  EXPECT_EQ(helios::solve::run_settings(o).at("threads"), 1);
  for (const char* bad : {"0", "65", "2(x3)", "-1", "x"}) {
    ::setenv("SLURM_CPUS_PER_TASK", bad, 1);
    try {
      helios::solve::scheduler_cpus_per_task();
      ADD_FAILURE() << bad << " was accepted";
    } catch (const helios::input_error& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("SLURM_CPUS_PER_TASK: '") + bad + "' is not a CPU count (a whole number from 1 to 64)");
    }
  }
  ::unsetenv("SLURM_CPUS_PER_TASK");
  fs::remove_all(dir);
}

}  // namespace

// The line helios-solve ends a run with says the flight in the user's units and what it cost.
TEST(UserUnits, TheOutcomeLineSaysTheTimeTheDatesAndTheCost) {
  using helios::io::json;
  json fuel = {{"tof_days", 348.795},
               {"departure_mjd2000", 400.0},
               {"initial_mass_kg", 1000.0},
               {"final_mass_kg", 603.940156},
               {"propellant_kg", 396.059844}};
  EXPECT_EQ(helios::solve::add_user_units(fuel),
            "time of flight 348.7950 days, departure 2001-02-04T00:00:00 TDB (MJD2000 400), arrival "
            "2002-01-18T19:04:48 TDB (MJD2000 748.795), final mass 603.94 kg (propellant 396.06 kg)");
  EXPECT_EQ(fuel.at("arrival_date_tdb"), "2002-01-18T19:04:48");
  json constant_mass = {
      {"tof_days", 20.0 / 24}, {"initial_mass_kg", 2000.0}, {"final_mass_kg", 2000.0}, {"delta_v_m_s", 1587.40796}};
  EXPECT_EQ(helios::solve::add_user_units(constant_mass),
            "time of flight 20.0000 h, delta-v 1587.41 m/s at a constant mass of 2000 kg");
  EXPECT_DOUBLE_EQ(constant_mass.at("tof_hours").get<double>(), 20.0);
}

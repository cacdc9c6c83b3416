// helios-solve's child limits for untrusted programs: wall clock, working directory, and no
// process left behind (process group + child subreaper).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "helios/solve/solve.hpp"

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

TEST(Sandbox, AnUnboundedAllocationIsStoppedByTheAddressSpaceLimit) {
  const auto r =
      helios::solve::run_limited({"/usr/bin/perl", "-e", "my @a; push @a, 'x' x 1_000_000 while 1"}, 20, 64, "");
  EXPECT_FALSE(r.timed_out);
  EXPECT_NE(r.exit_code, 0);
}

}  // namespace

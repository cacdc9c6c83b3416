#!/usr/bin/env bats
# What an untrusted program leaves behind never reaches the host as a command, a followed link, a
# hang or a forged artifact. Each test is an escape attempt that worked before helios-solve and
# helios-score treated the program's files and strings as data; each must now fail cleanly.

load test_helper

setup() {
  common_setup
  require_tool parse derive verify gen solve score
  CACHE="$BATS_TEST_TMPDIR/cache"
  FIXTURE="$ROOT/tests/fixtures/oem"
}

# program FILE MODE [OUTCOME_JQ]: a stand-in for a generated program. It knows the OEM fixture's
# converged outcome (edited by OUTCOME_JQ) and trajectory, compiled in, and leaves them as MODE says:
#   normal   both as regular files        link   the trajectory as a link to /etc/passwd
#   fifo     the outcome as a FIFO        loud   normal, after 10 MB and a JSON document on stdout
#   error    nothing; an error line amid progress, exit 2
#   plant    normal, after writing files into its working folder and the one above
program() {
  local file="$1" mode="$2" edit="${3:-.}" action
  case $mode in
    normal) action='' ;;
    link) action='symlink("/etc/passwd", trajectory.c_str()); std::ofstream(outcome) << kOutcome; return 0;' ;;
    fifo) action='std::ofstream(trajectory) << kTrajectory; mkfifo(outcome.c_str(), 0600); return 0;' ;;
    loud) action='std::cout << "{\"schema\": \"helios/solution\", \"status\": \"converged\", \"forged\": true}\n";
      for (int i = 0; i < 10000; ++i) std::cout << std::string(999, (char)32) << "\n";' ;;
    error) action='std::cerr << "start 1 of 4\nshoot: error: the settings are unusable\nstart 2 of 4\n"; return 2;' ;;
    plant) action='std::ofstream("planted") << "x"; std::ofstream("../planted") << "x";' ;;
  esac
  {
    printf '#include <sys/stat.h>\n#include <unistd.h>\n#include <cstring>\n#include <fstream>\n#include <iostream>\n'
    printf '#include <string>\nstatic const char* kOutcome = R"HELIOS(%s)HELIOS";\n' \
      "$(jq "del(.schema, .schema_version, .producer, .compile, .timings) | $edit" "$FIXTURE/solution.json")"
    printf 'static const char* kTrajectory = R"HELIOS(%s\n)HELIOS";\n' "$(cat "$FIXTURE/trajectory.csv")"
    printf 'int main(int argc, char** argv) {\n  std::string outcome, trajectory;\n'
    printf '  for (int i = 1; i + 1 < argc; ++i) {\n'
    printf '    if (!std::strcmp(argv[i], "--outcome")) outcome = argv[i + 1];\n'
    printf '    if (!std::strcmp(argv[i], "--trajectory")) trajectory = argv[i + 1];\n  }\n'
    printf '  %s\n  std::ofstream(trajectory) << kTrajectory;\n  std::ofstream(outcome) << kOutcome;\n}\n' "$action"
  } >"$file"
}

# solve PROGRAM [ARGS...]: helios-solve on PROGRAM with its trajectory and plots in out/.
solve() {
  local prog="$1"
  shift
  mkdir -p out
  timeout 120 "$BIN/helios-solve" "$prog" --cache-dir "$CACHE" --trajectory out/trajectory.csv --plots out/ "$@"
}

@test "untrusted: a problem id made of gnuplot code is refused as the outcome's; the same program with a plain id is plotted" {
  program hostile.cpp normal '.problem.id = "x'"'"'.system('"'"'id > HOST_ID.txt'"'"').'"'"'"'
  run -0 --separate-stderr solve hostile.cpp -o solution.json
  assert_jq solution.json '.status == "crashed" and .problem.id == "unknown"'
  assert_jq solution.json '.status_detail | test("outcome is unusable: .*/problem/id")'
  [[ -z $(find . "$HOME" -maxdepth 2 -name HOST_ID.txt) ]]
  [[ ! -e out/trajectory.png ]]
  # The control: the harness reaches gnuplot when the id is a plain one.
  program plain.cpp normal
  run -0 --separate-stderr solve plain.cpp -o solution.json
  assert_jq solution.json '.status == "converged" and .problem.id == "S08" and .files.trajectory_plot == "trajectory.png"'
  [[ -s out/trajectory.png && -s out/throttle_mass.png ]]
  [[ -z $(find . -name '.*.tmp*' -o -name '.run.*') ]]
}

@test "untrusted: a trajectory left as a link to /etc/passwd is never followed" {
  program link.cpp link
  run -0 --separate-stderr solve link.cpp -o solution.json
  assert_jq solution.json '.status == "crashed" and .status_detail == "the program'"'"'s trajectory is missing or not a regular file"'
  [[ ! -e out/trajectory.csv && ! -L out/trajectory.csv && ! -e out/trajectory.png ]]
  run grep -rl 'root:' out solution.json
  [[ $status -eq 1 ]]
}

@test "untrusted: an outcome left as a FIFO does not block helios-solve" {
  program fifo.cpp fifo
  run -0 --separate-stderr solve fifo.cpp -o solution.json
  assert_jq solution.json '.status == "crashed" and (.status_detail | test("outcome.json: not a regular file"))'
  [[ -z $(find . -type p) ]]
}

@test "untrusted: a trajectory, plot or -o that is a FIFO or a device is written into, never replaced" {
  program plain.cpp normal
  mkdir out
  mkfifo out/trajectory.csv
  timeout 60 cat out/trajectory.csv >trajectory.got &
  local reader=$! node=""
  # A private device like /dev/null (root only; the real one is never used).
  if ((EUID == 0)); then
    mknod out/trajectory.png c 1 3
    mknod solution.json c 1 3
    node=$(stat -c '%F %i %t:%T' out/trajectory.png solution.json)
  fi
  run -0 --separate-stderr solve plain.cpp -o solution.json
  wait "$reader"
  [[ -p out/trajectory.csv ]]
  cmp trajectory.got "$FIXTURE/trajectory.csv"
  [[ -z $node || $(stat -c '%F %i %t:%T' out/trajectory.png solution.json) == "$node" ]]
  [[ -s out/throttle_mass.png && -z $(find . -name '.*.tmp*' -o -name '.run.*') ]]
  # Any other kind is refused, naming it.
  rm out/trajectory.csv
  mkdir other.json
  run -1 --separate-stderr solve plain.cpp --quiet -o other.json
  assert_one_error_line solve
  [[ $stderr == "helios-solve: error: other.json: is a directory, not a file to write, name a file (or a character device such as /dev/null, or a FIFO)" ]]
}

@test "untrusted: the program's stdout never reaches helios-solve's: with -o - it carries only the solution" {
  program loud.cpp loud
  solve loud.cpp --quiet -o - >stdout.json
  [[ $(jq -s 'length' stdout.json) == 1 ]]
  assert_jq stdout.json '.schema == "helios/solution" and .status == "converged" and (has("forged") | not)'
  [[ $(wc -c <stdout.json) -lt 100000 ]]
}

@test "untrusted: status_detail quotes the program's error line, not its last progress line" {
  program error.cpp error
  run -0 --separate-stderr solve error.cpp -o solution.json
  assert_jq solution.json '.status == "crashed" and .status_detail == "exit code 2, signal 0: shoot: error: the settings are unusable"'
}

@test "untrusted: without --trajectory the program writes only into its private folder, which goes with the run" {
  program plant.cpp plant
  mkdir home
  cd home
  run -0 --separate-stderr timeout 120 "$BIN/helios-solve" ../plant.cpp --cache-dir "$CACHE" -o solution.json
  assert_jq solution.json '.status == "converged"'
  [[ $(ls -A | sort | tr '\n' ' ') == "solution.json trajectory.csv " ]]
  [[ ! -e ../planted ]]
}

@test "untrusted: readers stop at their limit: /dev/zero as settings, warm start or problem text is refused" {
  program plain.cpp normal
  local args
  for args in "--settings /dev/zero" "--warm-start /dev/zero"; do
    # shellcheck disable=SC2086
    run -3 --separate-stderr timeout 60 "$BIN/helios-solve" plain.cpp $args --cache-dir "$CACHE" -o solution.json
    assert_one_error_line solve
    [[ $stderr == "helios-solve: error: /dev/zero: larger than the limit of 67108864 bytes" ]]
  done
  "$BIN/helios-parse" "$S01/problem.txt" -o spec.json
  "$BIN/helios-derive" spec.json -o derivation.json
  run -3 --separate-stderr timeout 60 "$BIN/helios-score" --report --problem /dev/zero --spec spec.json \
    --derivation derivation.json -o report.md
  assert_one_error_line score
  [[ ! -e solution.json && ! -e report.md ]]
}

@test "untrusted: a settings value that would need unbounded memory is refused (node spacing below a day)" {
  program plain.cpp normal
  jq '.node_spacing_days = 0.001' "$S01/settings.json" >settings.json
  run -3 --separate-stderr "$BIN/helios-solve" plain.cpp --settings settings.json --cache-dir "$CACHE" -o solution.json
  [[ $stderr == "helios-solve: error: settings.json: field /node_spacing_days: 0.001 is below 1 day (0 turns the multiple-shooting polish off)" ]]
}

# sweep_in DIR: a 2 x 2 sweep of P01 in DIR, its cells written and its table and porkchop drawn.
sweep_in() {
  mkdir -p "$1"
  cp "$ROOT/scenarios/P01/problem.txt" "$1/"
  echo '{"template": "problem.txt", "departure_mjd2000": {"values": [9700, 9740]}, "tof_days": {"values": [300, 350]}}' \
    >"$1/sweep.json"
  "$BIN/helios-score" --sweep-cells "$1/sweep.json" --cells "$1" -o "$1/cells.mk"
  "$BIN/helios-score" --sweep "$1/sweep.json" --cells "$1" --porkchop "$1/porkchop.png" -o "$1/sweep.csv"
}

@test "untrusted: a sweep's folder name is data to gnuplot: code in it runs nothing, a quote in it works" {
  local name
  for name in "a'.system('touch X').'" "Bob's sweep" 'c`touch X`'; do
    run -0 --separate-stderr sweep_in "$name"
    [[ -s $name/porkchop.png && $(wc -l <"$name/sweep.csv") == 5 ]]
  done
  [[ -z $(find . "$HOME" -maxdepth 2 -name X) ]]
}

@test "untrusted: a sweep grid has a cell cap and plausible epochs and times of flight" {
  cp "$ROOT/scenarios/P01/problem.txt" .
  echo '{"departure_mjd2000": {"start": 0, "stop": 999, "step": 1}, "tof_days": {"start": 1, "stop": 1000, "step": 1}}' >sweep.json
  run -3 --separate-stderr "$BIN/helios-score" --sweep-cells sweep.json --cells cells -o cells.mk
  [[ $stderr == "helios-score: error: sweep.json: field /tof_days: the grid has 1000000 cells; the limit is 10000" ]]
  echo '{"departure_mjd2000": {"values": [1e300]}, "tof_days": {"values": [300]}}' >sweep.json
  run -3 --separate-stderr "$BIN/helios-score" --sweep-cells sweep.json --cells cells -o cells.mk
  [[ $stderr == "helios-score: error: sweep.json: field /departure_mjd2000: 1e+300 is above 73050" ]]
  [[ ! -e cells && ! -e cells.mk ]]
}

@test "untrusted: the chain runs from a copy of the build tree under /tmp (the sandbox's binds stay visible)" {
  local tree
  tree=$(mktemp -d /tmp/helios-tree.XXXXXX)
  cp -r "$HELIOS_BUILD_DIR/bin" "$HELIOS_BUILD_DIR/lib" "$HELIOS_BUILD_DIR/include" "$tree/"
  local bin="$tree/bin"
  "$bin/helios-parse" "$S01/problem.txt" -o spec.json
  "$bin/helios-derive" spec.json -o derivation.json
  "$bin/helios-gen" derivation.json -o shoot.cpp
  run -0 --separate-stderr "$bin/helios-solve" shoot.cpp --settings "$S01/settings.json" --cache-dir "$tree/cache" \
    --trajectory trajectory.csv -o solution.json
  rm -rf "$tree"
  assert_jq solution.json '.sandbox == "bubblewrap" and .compile.ok == true and .status == "converged"' ||
    { jq -r '.compile.diagnostics' solution.json >&2; false; }
}

#!/usr/bin/env bats
# helios-solve: shoot.cpp -> solution.json (+ trajectory.csv, trajectory.png, throttle_mass.png)
#
# Compiling shoot.cpp (against the prebuilt runtime) takes ~1 s, so setup_file compiles and runs S01 once, into
# $BATS_FILE_TMPDIR/e2e with the compile cache $BATS_FILE_TMPDIR/cache; the other tests reuse
# that cache (a cache hit costs < 1 s).

load test_helper

setup_file() {
  require_tool parse derive gen solve
  export SRC="$BATS_FILE_TMPDIR/s01" CACHE="$BATS_FILE_TMPDIR/cache" E2E="$BATS_FILE_TMPDIR/e2e"
  mkdir -p "$SRC" "$E2E"
  s01_shoot "$SRC"
  cp "$SRC/shoot.cpp" "$E2E/shoot.cpp"
  local rc=0 start end
  start=$(date +%s.%N)
  s01_solve "$E2E" "$CACHE" >"$E2E/stdout" 2>"$E2E/stderr" || rc=$?
  end=$(date +%s.%N)
  echo "$rc" >"$E2E/status"
  echo "$start $end" >"$E2E/wall"
}

setup() {
  common_setup
  require_tool solve
}

# ---- end to end --------------------------------------------------------------------------------

@test "solve: S01 end to end converges to the paper's final mass" {
  [[ $(cat "$E2E/status") == 0 ]] || { cat "$E2E/stderr" >&2; false; }
  # nothing on stdout; on stderr only the tool's progress lines
  [[ ! -s $E2E/stdout ]]
  grep -q '^helios-solve: search: ' "$E2E/stderr"
  ! grep -v '^helios-solve: ' "$E2E/stderr"
  local sol="$E2E/solution.json"
  assert_jq "$sol" '.schema == "helios/solution" and .problem.id == "S01"'
  assert_jq "$sol" '.status == "converged"'
  assert_jq "$sol" '.compile.ok == true and .compile.cached == false'
  assert_jq "$sol" '.max_residual < 1e-10'
  # what F resolves there (x moved by 1-4 doubles): above 0, far below the gate
  assert_jq "$sol" '.residual_noise > 0 and .residual_noise < 1e-11'
  assert_jq "$sol" '(.final_mass_kg - 603.935) | fabs <= 0.01'
  assert_jq "$sol" '.files.trajectory == "trajectory.csv"'
  assert_no_temp_files "$E2E"
}

@test "solve: solution.json records what the integrations cost, and the exact Jacobian's evaluations" {
  local sol="$E2E/solution.json"
  # S01 has no interior events: every solve is of the shooting function, with its exact Jacobian
  assert_jq "$sol" '.integration.jacobian == "exact"'
  assert_jq "$sol" '.integration.exact_jacobian_evaluations > 0'
  assert_jq "$sol" '.integration.jacobian_evaluations == 0 and .integration.jacobian_residual_evaluations == 0'
  assert_jq "$sol" '.integration.integrations > 0 and .integration.integration_s > 0'
  # the integrations are part of the solve: their summed time is at most the wall time on each thread
  assert_jq "$sol" '.integration.integration_s <= .integration.solve_s * .search.threads'
  assert_jq "$sol" '.integration.solve_s <= .timings.run_s'
  # every residual evaluation and every exact Jacobian integrates at least once
  assert_jq "$sol" '.integration.integrations >= .integration.residual_evaluations + .integration.exact_jacobian_evaluations'
}

@test "solve: with settings jacobian = finite-difference, hybrd's differences: n evaluations per Jacobian, same m_f" {
  local sol="$E2E/solution.json" n
  n=$(jq '.x | length' "$sol")
  # without the multiple-shooting polish, whose system has more variables than x (nodes.hpp)
  jq '. + {jacobian: "finite-difference", node_spacing_days: 0}' "$S01/settings.json" > settings.json
  cp "$E2E/shoot.cpp" shoot.cpp
  run -0 "$BIN/helios-solve" shoot.cpp --settings settings.json --cache-dir "$CACHE" --plots "" --quiet -o fd.json
  assert_jq fd.json '.status == "converged" and .integration.jacobian == "finite-difference"'
  assert_jq fd.json '.integration.exact_jacobian_evaluations == 0'
  assert_jq fd.json ".integration.jacobian_evaluations > 0 and .integration.jacobian_residual_evaluations == $n * .integration.jacobian_evaluations"
  assert_jq fd.json '.integration.jacobian_residual_evaluations < .integration.residual_evaluations'
  # the same extremal (1e-8 relative)
  local exact
  exact=$(jq .final_mass_kg "$sol")
  assert_jq fd.json "((.final_mass_kg - $exact) / $exact) | fabs <= 1e-8"
}

@test "solve: trajectory.csv has the t_days, m_kg, u, H and S columns" {
  local csv="$E2E/trajectory.csv"
  [[ -s $csv ]]
  local header
  header="$(head -n 1 "$csv")"
  local col
  for col in t_days m_kg u H S; do
    [[ ",$header," == *",$col,"* ]] || { echo "column $col missing from: $header" >&2; false; }
  done
  # Rows have as many fields as the header; the first row starts at t = 0 with the initial mass.
  [[ $(wc -l <"$csv") -gt 10 ]]
  awk -F, -v n="$(awk -F, 'NR == 1 { print NF }' "$csv")" 'NF != n { exit 1 }' "$csv"
  local m_col
  m_col="$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "m_kg") print i }' "$csv")"
  awk -F, -v c="$m_col" 'NR == 2 { exit !($1 == 0 && $c == 1000) }' "$csv"
}

@test "solve: both plots exist and are PNG files" {
  assert_png "$E2E/trajectory.png"
  assert_png "$E2E/throttle_mass.png"
  assert_jq "$E2E/solution.json" '.files.trajectory_plot == "trajectory.png" and .files.throttle_mass_plot == "throttle_mass.png"'
}

@test "solve: a second run with the same cache reports compile.cached true" {
  cp "$SRC/shoot.cpp" shoot.cpp
  run -0 --separate-stderr s01_solve "$BATS_TEST_TMPDIR" "$CACHE"
  assert_jq solution.json '.compile.cached == true and .compile.ok == true'
  assert_jq solution.json '.status == "converged"'
  jq -e --slurpfile first "$E2E/solution.json" \
    '.compile.source_sha256 == $first[0].compile.source_sha256 and .final_mass_kg == $first[0].final_mass_kg' solution.json
  assert_no_temp_files "$BATS_TEST_TMPDIR"
  assert_no_temp_files "$CACHE"
}

# p01_cell DIR EPOCH TOF [THRUST_N] -> DIR/shoot.cpp: a cell of the P01 sweep (tools/lib/src/sweep/README.md).
p01_cell() {
  local dir="$1"
  mkdir -p "$dir"
  sed -e "s/@DEPARTURE_MJD2000@/$2/g" -e "s/@TOF_DAYS@/$3/g" -e "s/maximum thrust of 0.5 N/maximum thrust of ${4:-0.5} N/" \
    "$ROOT/scenarios/P01/problem.txt" >"$dir/problem.txt"
  "$BIN/helios-parse" "$dir/problem.txt" -o "$dir/spec.json"
  "$BIN/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$BIN/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
}

# p01_solve DIR CACHE: the cell's solution.json (one thread: the same search whatever the machine).
p01_solve() {
  jq '. + {threads: 1}' "$ROOT/scenarios/P01/settings.json" >"$1/settings.json"
  "$BIN/helios-solve" "$1/shoot.cpp" --settings "$1/settings.json" --cache-dir "$2" --plots "" --quiet \
    --trajectory "$1/trajectory.csv" -o "$1/solution.json"
}

@test "solve: two cells of a sweep are one compile, each solved with its own numbers" {
  p01_cell a 9700 350
  p01_cell b 9740 400 0.6
  ! cmp -s a/shoot.cpp b/shoot.cpp
  p01_solve a cache
  p01_solve b cache
  assert_jq a/solution.json '.compile.cached == false and .status == "converged"'
  assert_jq b/solution.json '.compile.cached == true and .status == "converged"'
  jq -e --slurpfile a a/solution.json '.compile.structure_sha256 == $a[0].compile.structure_sha256 and
    .compile.source_sha256 != $a[0].compile.source_sha256' b/solution.json
  # one compile: one entry folder (beside it the compiler's and the runtime's kept identities)
  [[ $(find cache -mindepth 1 -maxdepth 1 -type d | wc -l) == 1 ]]
  # b's program compiled from b's own source gives the same solution, bit for bit
  cp -r b own
  p01_solve own own-cache
  assert_jq own/solution.json '.compile.cached == false and .status == "converged"'
  jq -e --slurpfile own own/solution.json '.propellant_kg == $own[0].propellant_kg and .x == $own[0].x and
    .departure_mjd2000 == 9740 and .tof_days == 400' b/solution.json
  assert_no_temp_files "$BATS_TEST_TMPDIR"
}

# with_thrust_constant DIR: DIR/shoot.cpp with the thrust read once, before main, into a
# namespace-scope constant problem::kThrust that the modules use (as a model writes naturally).
with_thrust_constant() {
  sed -i -e '/^}  \/\/ namespace problem$/a namespace problem {\nconst double kThrust = Tmax;\n}  // namespace problem' \
    -e '/kThrust = Tmax/!s/problem::Tmax/problem::kThrust/g' "$1/shoot.cpp"
  grep -q 'problem::kThrust' "$1/shoot.cpp"
}

# Issue 46: a value computed from a parameter at static initialisation keeps the number the
# program was compiled with; served from the cache, the 0.6 N cell flew the 0.5 N one's thrust.
@test "solve: a value computed from a parameter before main is the source's own, never a cached program's" {
  p01_cell a 9700 350
  p01_cell b 9700 350 0.6
  with_thrust_constant a
  with_thrust_constant b
  p01_solve a cache
  p01_solve b cache
  assert_jq b/solution.json '.compile.cached == false and .compile.cache_key == "source" and .status == "converged"'
  assert_jq b/solution.json '.compile.cache_key_detail | test("kThrust = Tmax") and test("before main")'
  cp -r b own
  rm own/solution.json
  p01_solve own own-cache
  jq -e --slurpfile own own/solution.json --slurpfile a a/solution.json \
    '.propellant_kg == $own[0].propellant_kg and .propellant_kg != $a[0].propellant_kg' b/solution.json
  assert_no_temp_files "$BATS_TEST_TMPDIR"
}

# The parameters file is helios-solve's, but the program refuses a bad one cleanly: exit 1 and one line.
@test "solve: a program refuses a parameters file that is not its own numbers" {
  cp "$SRC/shoot.cpp" shoot.cpp
  eval "$(jq -r .compile.command "$E2E/solution.json")"
  local bad
  for bad in '{"schema": "helios/parameters", "values": {"Tmin": 1}}' '{"schema": "helios/parameters", "values": {' \
    '[1, 2]' ''; do
    printf '%s' "$bad" >parameters.json
    run -1 --separate-stderr ./shoot --parameters parameters.json --outcome outcome.json --trajectory trajectory.csv
    [[ ${#stderr_lines[@]} == 1 && ${stderr_lines[0]} == "shoot: error: parameters parameters.json: "* ]]
    [[ ! -e outcome.json ]]
  done
  run -1 --separate-stderr ./shoot --parameters no-such.json
  [[ $stderr == "shoot: error: cannot read parameters no-such.json" ]]
}

@test "solve: the recorded compile command rebuilds the program by hand, against the prebuilt runtime" {
  cp "$SRC/shoot.cpp" shoot.cpp
  local command
  command=$(jq -r .compile.command "$E2E/solution.json")
  [[ $command == *" -I$HELIOS_BUILD_DIR/include/helios-runtime "* || $command == *" -I$(realpath "$HELIOS_BUILD_DIR")/include/helios-runtime "* ]]
  [[ $command == *" $(realpath "$HELIOS_BUILD_DIR")/lib/libhelios-runtime.a "* ]]
  eval "$command"
  jq '{threads: 1}' -n >settings.json
  ./shoot --settings settings.json --outcome outcome.json --trajectory trajectory.csv 2>/dev/null
  jq -e --slurpfile first "$E2E/solution.json" '.x == $first[0].x and .final_mass_kg == $first[0].final_mass_kg' outcome.json
}

# The runtime's precompiled header (built with the tools) is what the recorded command reads: g++
# -H marks a used one with "!" (an unusable one, e.g. built with other flags, is passed over).
@test "solve: the recorded compile command reads the runtime's precompiled header" {
  cp "$SRC/shoot.cpp" shoot.cpp
  local command
  command=$(jq -r .compile.command "$E2E/solution.json")
  run -0 --separate-stderr bash -c "${command/ -o shoot / -H -Winvalid-pch -fsyntax-only }"
  [[ $stderr == "! "*"/include/helios-runtime/helios_runtime.hpp.gch"* ]]
}

# A module's function can never replace one of the runtime's by its name: the library's only
# external functions are those its public headers declare (helios_runtime.hpp and the three it
# includes; the rest is in unnamed namespaces). No weak one: an optional module is reached through
# the program's module table, not by a symbol that may be absent.
@test "solve: the runtime library defines no external function its header does not declare" {
  local name names header=$HELIOS_BUILD_DIR/include/helios-runtime
  names=$(nm -C --defined-only -g "$HELIOS_BUILD_DIR/lib/libhelios-runtime.a" | sed -n 's/^[0-9a-f]* [TW] //p' |
    grep -E '^helios_rt::[A-Za-z0-9_]+\(' | sed 's/(.*//' | sort -u)
  [[ -n $names ]]
  for name in $names; do
    cat "$header"/{helios_runtime,runtime_records,runtime_calls,module_interface}.hpp |
      grep -qE "[ *&]${name#helios_rt::}\(" ||
      { echo "the library exports $name, which helios_runtime.hpp does not declare" >&2; false; }
  done
  run -1 bash -c "nm -C --undefined-only \"$HELIOS_BUILD_DIR/lib/libhelios-runtime.a\" | grep -E ' [wv] helios_rt::'"
}

@test "solve: reads the program from stdin with -" {
  run -0 --separate-stderr bash -c \
    '"$BIN/helios-solve" - --settings "$S01/settings.json" --cache-dir "$CACHE" --trajectory t.csv --plots "" <"$SRC/shoot.cpp"'
  jq -e '.status == "converged" and .compile.cached == true' <<<"$output"
  [[ -s t.csv ]]
}

@test "solve: a shoot.cpp with a syntax error -> status compile_failed, exit 0" {
  { cat "$SRC/shoot.cpp"; echo 'this is not C++ at all'; } >shoot.cpp
  run -0 --separate-stderr "$BIN/helios-solve" shoot.cpp --settings "$S01/settings.json" --cache-dir "$CACHE" \
    --trajectory trajectory.csv --plots ./ -o solution.json
  assert_jq solution.json '.status == "compile_failed"'
  assert_jq solution.json '.compile.ok == false and .compile.cached == false'
  assert_jq solution.json '.compile.diagnostics | test("error")'
  assert_jq solution.json 'has("final_mass_kg") | not'
  [[ ! -e trajectory.csv && ! -e trajectory.png && ! -e throttle_mass.png ]]
  assert_no_temp_files "$BATS_TEST_TMPDIR"
  assert_no_temp_files "$CACHE"
}

# A stand-in for a generated program: it writes the text $2 as its outcome (--outcome PATH). The text
# is compiled in: the program sees no file but its private run folder.
outcome_writer() {
  {
    printf '#include <cstring>\n#include <fstream>\nint main(int argc, char** argv) {\n'
    printf '  const char* text = R"HELIOS(%s)HELIOS";\n' "$2"
    printf '  for (int i = 1; i + 1 < argc; ++i)\n'
    printf '    if (std::strcmp(argv[i], "--outcome") == 0) std::ofstream(argv[i + 1]) << text;\n}\n'
  } >"$1"
}

@test "solve: a program whose outcome is malformed -> status crashed with the reason, exit 0" {
  local text
  for text in 'not json at all' '[1, 2]' '{"status": "converged", "compile": {}}' \
    '{"problem": {"id": "X"}, "status": "dancing", "seed": 1, "iterations": 0, "function_evaluations": 0}' \
    '{"problem": {"id": "X"}, "status": "converged", "seed": "one", "iterations": 0, "function_evaluations": 0}'; do
    rm -f solution.json
    outcome_writer prog.cpp "$text"
    run -0 --separate-stderr "$BIN/helios-solve" prog.cpp --cache-dir "$CACHE" --trajectory trajectory.csv \
      -o solution.json
    assert_jq solution.json '.status == "crashed" and .compile.ok == true'
    assert_jq solution.json '.status_detail | startswith("the program'"'"'s outcome is unusable: ")'
    assert_no_temp_files "$BATS_TEST_TMPDIR"
  done
}

@test "solve: the folders a killed run left are removed by the next run; a live run's are kept" {
  outcome_writer prog.cpp '{}'
  mkdir .run.4194300.abcdef .run.$$.abcdef .run.notapid.abcdef
  touch .run.4194300.abcdef/outcome.json .run.$$.abcdef/outcome.json
  ln -s /etc .run.4194301.abcdef
  run -0 --separate-stderr "$BIN/helios-solve" prog.cpp --cache-dir "$CACHE" --trajectory trajectory.csv \
    -o solution.json
  [[ ! -e .run.4194300.abcdef ]]
  [[ -e .run.$$.abcdef/outcome.json && -d .run.notapid.abcdef && -L .run.4194301.abcdef && -e /etc/passwd ]]
  # The run's own private folder is gone with it.
  [[ $(find . -maxdepth 1 -name '.run.*' | wc -l) == 3 ]]
}

@test "solve: the program runs in bubblewrap: no file outside its run folder, no /etc, no network, no environment" {
  mkdir -p run
  local marker="helios-escape-$$-$RANDOM"
  cat >escape.cpp <<CPP
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <iostream>
int main() {
  std::ostream& report = std::cerr;
  std::ofstream("/tmp/$marker") << "x";
  std::ofstream("../$marker") << "x";
  std::ofstream("$HOME/$marker") << "x";
  std::ostringstream passwd;
  passwd << std::ifstream("/etc/passwd").rdbuf();
  report << "passwd " << passwd.str().size() << "\n";
  report << "project " << (std::ifstream("$ROOT/Makefile") ? "readable" : "hidden") << "\n";
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(53);
  inet_pton(AF_INET, "1.1.1.1", &a.sin_addr);
  report << "connect " << (fd >= 0 && connect(fd, (sockaddr*)&a, sizeof a) == 0 ? "ok" : "failed") << "\n";
  report << "key " << (std::getenv("HELIOS_LLM_API_KEY") ? "seen" : "unset") << "\n";
}
CPP
  HELIOS_LLM_API_KEY=secret-key run -0 --separate-stderr "$BIN/helios-solve" escape.cpp --cache-dir "$CACHE" \
    --trajectory run/trajectory.csv -o solution.json
  assert_jq solution.json '.sandbox == "bubblewrap" and .status == "crashed"'
  [[ ! -e /tmp/$marker && ! -e $marker && ! -e run/$marker && ! -e $HOME/$marker ]]
  # What the program printed reaches helios-solve's stderr as progress, never its stdout.
  [[ $(grep -E '^helios-solve: (passwd|project|connect|key) ' <<<"$stderr") == \
     $'helios-solve: passwd 0\nhelios-solve: project hidden\nhelios-solve: connect failed\nhelios-solve: key unset' ]] ||
    { echo "$stderr" >&2; false; }
  # Unsandboxed only when told, and then recorded.
  run -0 --separate-stderr "$BIN/helios-solve" escape.cpp --no-sandbox --cache-dir "$CACHE" \
    --trajectory run/trajectory.csv -o solution.json
  assert_jq solution.json '.sandbox == "none"'
  rm -f "/tmp/$marker" "$marker" "$HOME/$marker"
}

@test "solve: the compiler runs in bubblewrap too: a source including host files quotes none of them" {
  printf '#include "/etc/passwd"\n#include "%s/Makefile"\nint main() {}\n' "$ROOT" >leak.cpp
  run -0 --separate-stderr "$BIN/helios-solve" leak.cpp --compile-only --cache-dir "$CACHE" -o compile.json
  assert_jq compile.json '.ok == false and (.diagnostics | contains("/etc/passwd: No such file or directory"))'
  assert_jq compile.json '(.diagnostics | contains("root:") or contains("SHELL :=")) | not'
  # A relative cache folder (the Makefile's runs/.cache) is bound at its absolute path.
  echo 'int main() {}' >empty.cpp
  run -0 --separate-stderr "$BIN/helios-solve" empty.cpp --compile-only --cache-dir relative-cache -o compile.json
  assert_jq compile.json '.ok'
}

# ---- shared contract -------------------------------------------------------------------------

@test "solve: no arguments -> exit 2, one error line" {
  contract_no_args solve
}

@test "solve: unknown option -> exit 2" {
  contract_bad_option solve "$SRC/shoot.cpp"
}

@test "solve: a non-positive or non-numeric --time-limit -> exit 2" {
  local limit
  for limit in 0 -5 abc; do
    mkdir "out$limit"
    run -2 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings "$S01/settings.json" \
      --cache-dir "$CACHE" --trajectory "out$limit/t.csv" --plots "" --time-limit "$limit" -o "out$limit/solution.json"
    assert_one_error_line solve
    assert_stderr_contains "--time-limit"
    assert_dir_empty "out$limit"
  done
}

@test "solve: a non-positive --memory-limit -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings "$S01/settings.json" \
    --cache-dir "$CACHE" --plots "" --memory-limit 0
  assert_one_error_line solve
}

@test "solve: a --cache-dir that is a file, or under one -> exit 2 naming the option, nothing written" {
  echo x >cache
  run -2 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings "$S01/settings.json" --cache-dir cache -o sol.json
  assert_one_error_line solve
  [[ $stderr == "helios-solve: error: --cache-dir cache: is not a folder, name a folder (it is made when missing)" ]]
  run -2 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings "$S01/settings.json" --cache-dir cache/c -o sol.json
  [[ $stderr == "helios-solve: error: --cache-dir cache/c: cache is not a folder, name a folder (it is made when missing)" ]]
  [[ ! -e sol.json ]]
}

@test "solve: an unknown --backend -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings "$S01/settings.json" \
    --cache-dir "$CACHE" --plots "" --backend nope
  assert_one_error_line solve
}

@test "solve: missing input file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-solve" no-such-shoot.cpp --settings "$S01/settings.json" \
    --cache-dir "$CACHE" --trajectory out/trajectory.csv --plots out/ -o out/solution.json
  assert_one_error_line solve
  assert_stderr_contains "no-such-shoot.cpp"
  assert_dir_empty out
}

@test "solve: missing input file without the optional --settings/--plots -> exit 3 naming the file" {
  run -3 --separate-stderr "$BIN/helios-solve" no-such-shoot.cpp
  assert_one_error_line solve
  assert_stderr_contains "no-such-shoot.cpp"
}

@test "solve: --plots is optional (no plots drawn without it)" {
  cp "$SRC/shoot.cpp" shoot.cpp
  run -0 --separate-stderr "$BIN/helios-solve" shoot.cpp --settings "$S01/settings.json" --cache-dir "$CACHE" \
    --trajectory trajectory.csv -o solution.json
  assert_jq solution.json '.status == "converged"'
  [[ -s trajectory.csv && ! -e trajectory.png && ! -e throttle_mass.png ]]
}

@test "solve: --help ends with an e.g. line" {
  contract_help solve
}

@test "solve: --version" {
  contract_version solve
}

@test "solve: malformed --settings JSON -> exit 3 naming the file, nothing written" {
  printf '{"seed": 1,' >settings.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings settings.json --cache-dir "$CACHE" \
    --trajectory out/trajectory.csv --plots out/ -o out/solution.json
  assert_one_error_line solve
  assert_stderr_contains "settings.json" "malformed JSON"
  assert_dir_empty out
}

@test "solve: --settings that is not a JSON object -> exit 3" {
  echo '[1, 2, 3]' >settings.json
  run -3 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings settings.json --cache-dir "$CACHE" \
    --plots "" -o solution.json
  assert_one_error_line solve
  assert_stderr_contains "settings.json"
  [[ ! -e solution.json ]]
}

@test "solve: missing --settings file -> exit 3 naming the file" {
  run -3 --separate-stderr "$BIN/helios-solve" "$SRC/shoot.cpp" --settings no-such-settings.json \
    --cache-dir "$CACHE" --plots "" -o solution.json
  assert_one_error_line solve
  assert_stderr_contains "no-such-settings.json"
  [[ ! -e solution.json ]]
}

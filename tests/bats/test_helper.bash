# Common setup for the HELIOS Bats suite (bats-core >= 1.5).
#
#   load test_helper        (at the top of every *.bats file)
#
# Every test runs in its own $BATS_TEST_TMPDIR (the working directory); nothing is written to the
# source tree (pipeline.bats runs make with SCENARIOS_DIR and RUNS_ROOT in its temporary folder).
# The tools are NOT rebuilt here: run `make tools` first (`make bats` does).

bats_require_minimum_version 1.5.0

ROOT="$(cd "$BATS_TEST_DIRNAME/../.." && pwd)"
# The build tree whose tools run (make test-sanitized points it at build-asan); relative to ROOT.
HELIOS_BUILD_DIR="${HELIOS_BUILD_DIR:-build}"
[[ $HELIOS_BUILD_DIR == /* ]] || HELIOS_BUILD_DIR="$ROOT/$HELIOS_BUILD_DIR"
BIN="$HELIOS_BUILD_DIR/bin"
S01="$ROOT/scenarios/S01"
export ROOT HELIOS_BUILD_DIR BIN S01

# Called from each file's setup().
common_setup() {
  cd "$BATS_TEST_TMPDIR" || return 1
}

# Fails the test (or setup_file) with a clear message when a tool has not been built.
require_tool() {
  local tool
  for tool in "$@"; do
    if [[ ! -x "$BIN/helios-$tool" ]]; then
      echo "missing $BIN/helios-$tool: run 'make tools' first" >&2
      return 1
    fi
  done
}

# ---- S01 artifacts, written into the current test's tmpdir (or DIR) -------------------------

# s01_spec [DIR] -> DIR/spec.json
s01_spec() {
  local dir="${1:-$BATS_TEST_TMPDIR}"
  "$BIN/helios-parse" "$S01/problem.txt" -o "$dir/spec.json"
}

# s01_derivation [DIR] -> DIR/spec.json, DIR/derivation.json
s01_derivation() {
  local dir="${1:-$BATS_TEST_TMPDIR}"
  s01_spec "$dir"
  "$BIN/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
}

# s01_verify [DIR] -> ... DIR/verify.json
s01_verify() {
  local dir="${1:-$BATS_TEST_TMPDIR}"
  [[ -f "$dir/derivation.json" ]] || s01_derivation "$dir"
  "$BIN/helios-verify" "$dir/derivation.json" -o "$dir/verify.json"
}

# s01_shoot [DIR [POLICY]] -> ... DIR/shoot.cpp (POLICY: auto | generated)
s01_shoot() {
  local dir="${1:-$BATS_TEST_TMPDIR}" policy="${2:-auto}"
  [[ -f "$dir/derivation.json" ]] || s01_derivation "$dir"
  "$BIN/helios-gen" --modules "$policy" "$dir/derivation.json" -o "$dir/shoot.cpp"
}

# s01_solve DIR CACHE_DIR -> DIR/solution.json, DIR/trajectory.csv, DIR/trajectory.png,
# DIR/throttle_mass.png (needs DIR/shoot.cpp)
s01_solve() {
  local dir="$1" cache="$2"
  "$BIN/helios-solve" "$dir/shoot.cpp" --settings "$S01/settings.json" --cache-dir "$cache" \
    --trajectory "$dir/trajectory.csv" --plots "$dir/" -o "$dir/solution.json"
}

# ---- assertions ------------------------------------------------------------------------------

# After `run -N --separate-stderr helios-TOOL ...`: stderr is exactly one line "helios-TOOL: error: ...".
assert_one_error_line() {
  local tool="$1"
  if [[ ${#stderr_lines[@]} -ne 1 ]]; then
    echo "expected exactly one stderr line, got ${#stderr_lines[@]}:" >&2
    printf '%s\n' "$stderr" >&2
    return 1
  fi
  if [[ ${stderr_lines[0]} != "helios-$tool: error: "* ]]; then
    echo "stderr does not start with 'helios-$tool: error: ': $stderr" >&2
    return 1
  fi
}

# assert_stderr_contains TEXT...: every TEXT occurs in $stderr (fixed strings).
assert_stderr_contains() {
  local text
  for text in "$@"; do
    if [[ $stderr != *"$text"* ]]; then
      echo "stderr does not mention '$text': $stderr" >&2
      return 1
    fi
  done
}

# assert_no_temp_files DIR: no dot-files (atomic-write temps such as .x.json.tmp.PID.N) below DIR.
assert_no_temp_files() {
  local left
  left="$(find "$1" -mindepth 1 -name '.*' 2>/dev/null)"
  if [[ -n $left ]]; then
    echo "temp files left behind:" >&2
    printf '%s\n' "$left" >&2
    return 1
  fi
}

# assert_dir_empty DIR: nothing at all was written into DIR.
assert_dir_empty() {
  local left
  left="$(find "$1" -mindepth 1 2>/dev/null)"
  if [[ -n $left ]]; then
    echo "expected $1 to stay empty, found:" >&2
    printf '%s\n' "$left" >&2
    return 1
  fi
}

# run_chain PROBLEM SETTINGS WORK: the builtin chain in WORK, cold, compile cache in the file's
# temp folder: spec, derivation, verify, shoot.cpp, solution.json (stderr in WORK/stderr) and
# trajectory.csv. SETTINGS "": the solver's defaults.
run_chain() {
  local problem=$1 work=$3 settings=()
  [[ -z $2 ]] || settings=(--settings "$2")
  mkdir -p "$work"
  "$BIN/helios-parse" "$problem" -o "$work/spec.json"
  "$BIN/helios-derive" "$work/spec.json" -o "$work/derivation.json"
  "$BIN/helios-verify" "$work/derivation.json" -o "$work/verify.json"
  "$BIN/helios-gen" "$work/derivation.json" -o "$work/shoot.cpp"
  "$BIN/helios-solve" "$work/shoot.cpp" "${settings[@]}" --cache-dir "$BATS_FILE_TMPDIR/cache" --plots "" \
    --trajectory "$work/trajectory.csv" -o "$work/solution.json" 2>"$work/stderr"
}

# within GOT WANT REL: |GOT - WANT| <= REL |WANT|
within() {
  awk -v g="$1" -v w="$2" -v r="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; a = w < 0 ? -w : w; exit !(d <= r * a) }' || {
    echo "got $1, want $2 to $3 relative" >&2
    return 1
  }
}

# assert_s14_minimum_time SOLUTION: converged cold to S14's published minimum time,
# 14.800364354648908 h (the control-toolbox tutorial's), within 1e-5 h, with H = 0 on the whole arc
# (minimum time with tf free: the drift at round-off).
assert_s14_minimum_time() {
  local sol=$1
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10'
  assert_jq "$sol" '(.tof_days * 24 - 14.800364354648908) | fabs <= 1e-5'
  assert_jq "$sol" '.hamiltonian_drift < 1e-10'
}

# assert_ends_on_geo TRAJECTORY: the last row of a trajectory.csv is on the circular equatorial
# orbit of radius 42165 km about the Earth (mu 398600.47 km^3/s^2): |r| = 42165 km, r.v = 0,
# |v| = sqrt(mu/42165), z and vz 0, and prograde (h_z = x vy - y vx > 0, not the retrograde mirror).
assert_ends_on_geo() {
  tail -n 1 "$1" | awk -F, '{
    r = sqrt($2*$2 + $3*$3 + $4*$4); v = sqrt($5*$5 + $6*$6 + $7*$7); rv = $2*$5 + $3*$6 + $4*$7
    hz = $2*$6 - $3*$5
    ok = (r - 42165 < 1e-4 && 42165 - r < 1e-4) && (rv * rv < 1e-20 * r * r * v * v) && \
         ((v - sqrt(398600.47 / 42165))^2 < 1e-16) && ($4^2 < 1e-8) && ($7^2 < 1e-16) && hz > 0
    if (!ok) { printf "r %.9f v %.12f r.v %g z %g vz %g h_z %g\n", r, v, rv, $4, $7, hz > "/dev/stderr"; exit 1 }
  }'
}

# assert_jq FILE FILTER: `jq -e FILTER FILE` is true (prints the file's relevant part on failure).
assert_jq() {
  local file="$1" filter="$2"
  if ! jq -e "$filter" "$file" >/dev/null; then
    echo "jq -e '$filter' failed on $file" >&2
    head -c 3000 "$file" >&2
    return 1
  fi
}

# assert_png FILE: exists and starts with the PNG signature 89 50 4E 47 0D 0A 1A 0A.
assert_png() {
  [[ -s $1 ]] || { echo "missing or empty PNG: $1" >&2; return 1; }
  local magic
  magic="$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')"
  [[ $magic == 89504e470d0a1a0a ]] || { echo "$1 does not start with the PNG magic (got $magic)" >&2; return 1; }
}

# assert_file_map SHOOT_CPP NAME...: the program's opening map lists the PROBLEM block, each NAME
# (a module) and the entry point, every line number pointing at that part's banner, and the SHA-256
# of the runtime it links (the header and library beside the tools).
assert_file_map() {
  local src="$1" name line
  shift
  [[ $(sed -n 3p "$src") == "// Map (line numbers of this file):" ]] || { echo "no map at line 3 of $src" >&2; return 1; }
  for name in "PROBLEM (generated)" "$@"; do
    line=$(sed -n '4,20p' "$src" | awk -v n="$name" 'index($0, "  " n) { print $2; exit }')
    [[ -n $line ]] || { echo "the map lists no '$name'" >&2; sed -n '3,12p' "$src" >&2; return 1; }
    local banner
    banner=$(sed -n "${line}p" "$src")
    [[ $banner =~ ^//\ (-----|=====\ HELIOS\ LLM\ MODULE:)\  && $banner == *"${name#module }"* ]] ||
      { echo "map line $line for '$name' is: $banner" >&2; return 1; }
  done
  line=$(sed -n '4,20p' "$src" | awk 'index($0, "entry point") { print $2; exit }')
  sed -n "$((line + 1))p" "$src" | grep -q "^// HELIOS shooting runtime, entry point" ||
    { echo "the map's entry point line $line is wrong" >&2; return 1; }
  local runtime_sha
  local include=$HELIOS_BUILD_DIR/include/helios-runtime
  runtime_sha=$(cat "$include"/{helios_runtime,runtime_records,runtime_calls,module_interface}.hpp \
    "$HELIOS_BUILD_DIR/lib/libhelios-runtime.a" | sha256sum | cut -d' ' -f1)
  grep -qx "//   runtime SHA-256 $runtime_sha" "$src" ||
    { echo "the map names another runtime than the build tree's ($runtime_sha):" >&2; grep 'runtime SHA' "$src" >&2; return 1; }
}

# ---- the contract every tool shares (used by each tool's file) -------------------------------

# contract_no_args TOOL
contract_no_args() {
  run -2 --separate-stderr "$BIN/helios-$1"
  assert_one_error_line "$1"
  [[ -z $output ]]
}

# contract_bad_option TOOL [ARGS...]
contract_bad_option() {
  local tool="$1"
  shift
  run -2 --separate-stderr "$BIN/helios-$tool" --no-such-option "$@"
  assert_one_error_line "$tool"
  assert_stderr_contains "--no-such-option"
}

contract_help() {
  run -0 --separate-stderr "$BIN/helios-$1" --help
  [[ $output == *"usage: helios-$1"* ]]
  local last="${lines[${#lines[@]} - 1]}"
  [[ $last == "e.g.: helios-$1 "* ]] || { echo "last help line is not 'e.g.: helios-$1 ...': $last" >&2; return 1; }
  [[ -z $stderr ]]
}

contract_version() {
  run -0 --separate-stderr "$BIN/helios-$1" --version
  [[ $output == "helios-$1 0.1.0" ]] || { echo "got: $output" >&2; return 1; }
  [[ -z $stderr ]]
}

# chain SCENARIO DIR [PROBLEM]: parse -> derive -> verify -> gen -> solve -> score into DIR
chain() {
  local s=$1 dir=$2 problem=${3:-$ROOT/scenarios/$1/problem.txt}
  mkdir -p "$dir"
  "$BIN/helios-parse" "$problem" -o "$dir/spec.json"
  "$BIN/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$BIN/helios-verify" --advisory "$dir/derivation.json" -o "$dir/verify.json"
  "$BIN/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
  "$BIN/helios-solve" "$dir/shoot.cpp" --settings "$ROOT/scenarios/$s/settings.json" --cache-dir "$BATS_FILE_TMPDIR/cache" \
    --trajectory "$dir/trajectory.csv" --plots "$dir/" -o "$dir/solution.json"
  "$BIN/helios-score" --reference "$ROOT/scenarios/$s/reference.json" --spec "$dir/spec.json" \
    --derivation "$dir/derivation.json" --verify "$dir/verify.json" --solution "$dir/solution.json" -o "$dir/score.json"
}

# chain_or_note SCENARIO DIR [PROBLEM]: chain in a setup_file, its output in DIR.log; a failure is
# noted for chains_passed, which each test's setup calls.
chain_or_note() {
  chain "$@" >"$2.log" 2>&1 || echo "$(basename "$2") failed" >>"$BATS_FILE_TMPDIR/failures"
}

# chains_passed: fails (showing what failed and the logs) when a chain of the file's setup failed.
chains_passed() {
  if [[ -s $BATS_FILE_TMPDIR/failures ]]; then
    cat "$BATS_FILE_TMPDIR/failures" "$BATS_FILE_TMPDIR"/*.log >&2
    return 1
  fi
}

# assert_oem_of_run DIR: helios-score --oem writes DIR's converged trajectory as DIR/trajectory.oem,
# and the independent parser of oem.bats (oem_check.awk) accepts it and finds trajectory.csv in it.
assert_oem_of_run() {
  local dir=$1 epoch
  "$BIN/helios-score" --oem --spec "$dir/spec.json" --solution "$dir/solution.json" \
    --trajectory "$dir/trajectory.csv" -o "$dir/trajectory.oem"
  [[ -s $dir/trajectory.oem ]] || { echo "$dir: no trajectory.oem (did the run converge?)" >&2; return 1; }
  epoch=$(jq -r '.time.epoch_mjd2000 // 0.5' "$dir/spec.json")
  awk -v epoch0="$epoch" -f "$ROOT/tests/bats/oem_check.awk" "$dir/trajectory.csv" "$dir/trajectory.oem" \
    >"$dir/oem_check.log" 2>&1 || { echo "$dir: the OEM parser refused trajectory.oem:" >&2; cat "$dir/oem_check.log" >&2; return 1; }
}

# converged_and_verified DIR: verify passes, converged at max|F| < 1e-10, score 100
converged_and_verified() {
  assert_jq "$1/verify.json" '.verdict == "pass"'
  assert_jq "$1/solution.json" '.status == "converged" and .max_residual < 1e-10 and .epsilon == 0'
  assert_jq "$1/score.json" '.total == 100'
}

# unnested_make ARGS...: make in the repository, isolated from an enclosing make (`make bats`).
unnested_make() {
  env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u MAKEOVERRIDES make --no-print-directory -C "$ROOT" "$@"
}

# isolated_make RUNS_ROOT CACHE ARGS...: unnested_make into a private runs tree and compile cache,
# the tools taken as built (no rebuild).
isolated_make() {
  local runs="$1" cache="$2"
  shift 2
  unnested_make -o build/tools.stamp RUNS_ROOT="$runs" CACHE="$cache" "$@"
}

# sweep_make RUNS_ROOT [VAR=VALUE...]: make sweep sweep=P01 (its 3 x 3 CI grid) into RUNS_ROOT with
# -j2; the compile cache is SWEEP_CACHE, else SHARED_CACHE (sweep.bats, slurm.bats).
sweep_make() {
  local runs="$1"
  shift
  isolated_make "$runs" "${SWEEP_CACHE:-$SHARED_CACHE}" sweep sweep=P01 -j2 "$@"
}

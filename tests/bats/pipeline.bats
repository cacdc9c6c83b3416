#!/usr/bin/env bats
# The Makefile pipeline: problem.txt -> spec -> derivation -> verify -> shoot.cpp -> solution -> score.
#
# Runs make in the repository on a private scenario T01 (a copy of S01) in a private scenarios
# folder and runs root (SCENARIOS_DIR, RUNS_ROOT under $BATS_FILE_TMPDIR), so it writes nothing into
# the tree and never touches the runs of others.
#
# make is run with `-o build/tools.stamp`: the tools are taken as built (as in the other files, run
# `make tools` first; `make bats` does), so that a colleague editing a tool source meanwhile does not
# turn these runs into tool rebuilds. The compile cache is a private one (CACHE=...). The two tests
# that edit a tool's source and rebuild do it on a copy of the tree and its build tree, mounted at
# the tree's own path for the make that rebuilds (on_copy): the tree and its build are left as they were.

load test_helper

BATS_NO_PARALLELIZE_WITHIN_FILE=true

ARTIFACTS=(spec.json derivation.json verify.json shoot.cpp solution.json trajectory.oem report.md score.json)
EARLY=(spec.json derivation.json verify.json shoot.cpp)
LATE=(solution.json trajectory.oem score.json)

setup_file() {
  require_tool parse derive verify gen solve score
  export PIPE_SCENARIOS="$BATS_FILE_TMPDIR/scenarios" PIPE_RUNS="$BATS_FILE_TMPDIR/runs"
  export PIPE_CACHE="$BATS_FILE_TMPDIR/cache"
  mkdir -p "$PIPE_SCENARIOS/T01"
  sed 's/^Problem S01:/Problem T01:/' "$S01/problem.txt" >"$PIPE_SCENARIOS/T01/problem.txt"
  grep -q '^Problem T01:' "$PIPE_SCENARIOS/T01/problem.txt"
  jq '.scenario = "T01"' "$S01/reference.json" >"$PIPE_SCENARIOS/T01/reference.json"
  cp "$S01/settings.json" "$PIPE_SCENARIOS/T01/settings.json"
}

setup() {
  common_setup
  RUNDIR="$PIPE_RUNS/builtin/T01"
  MAKE_CACHE="$PIPE_CACHE"
}

# make_t01 ARGS...: make for T01 in the private folders, isolated from an enclosing make (`make bats`).
make_t01() {
  unnested_make scenario=T01 SCENARIOS_DIR="$PIPE_SCENARIOS" RUNS_ROOT="$PIPE_RUNS" CACHE="$MAKE_CACHE" "$@"
}

# pmake ARGS...: make_t01 with the tools taken as built.
pmake() {
  make_t01 -o build/tools.stamp "$@"
}

# tree_copy -> $COPY: a copy of the tree with its build tree (object files, stamps and times kept, so
# a rebuild compiles only what changed); not runs/, .git or the other build trees.
tree_copy() {
  COPY="$BATS_TEST_TMPDIR/tree"
  mkdir "$COPY"
  local entry
  for entry in "$ROOT"/* "$ROOT"/.[!.]*; do
    case ${entry##*/} in runs | .git | build-asan | build-fuzz) continue ;; esac
    cp -a "$entry" "$COPY/"
  done
  [[ -x $COPY/build/bin/helios-score ]] || { echo "the copy of the tree has no build/bin/helios-score" >&2; return 1; }
}

# make_on_copy ARGS...: make_t01 ARGS in a mount namespace (bubblewrap) where $COPY is mounted at
# $ROOT: the make rebuilds and stamps the copy's tools; every other path is the host's.
make_on_copy() {
  bwrap --dev-bind / / --bind "$COPY" "$ROOT" --chdir "$BATS_TEST_TMPDIR" \
    bash -c "$(declare -p MAKE_CACHE); $(declare -f make_t01 unnested_make); make_t01 \"\$@\"" make_on_copy "$@"
}

# Builds T01 unless it is complete and up to date.
ensure_built() {
  local f complete=1
  for f in "${ARTIFACTS[@]}"; do [[ -s $RUNDIR/$f ]] || complete=0; done
  if ((complete)) && pmake -q; then return 0; fi
  # make would not remake a missing intermediate artifact under an up-to-date score.json.
  ((complete)) || rm -f "$RUNDIR/score.json"
  pmake >"$BATS_TEST_TMPDIR/ensure.log" 2>&1 || { cat "$BATS_TEST_TMPDIR/ensure.log" >&2; return 1; }
}

# mtime_of FILE: mtime of $RUNDIR/FILE in nanoseconds.
mtime_of() {
  local t
  t="$(stat -c %.9Y "$RUNDIR/$1")"
  echo "${t/./}"
}

# snapshot FILE...: "FILE MTIME" lines.
snapshot() {
  local f
  for f in "$@"; do echo "$f $(mtime_of "$f")"; done
}

# poll SECONDS CMD...: retries CMD every 0.1 s until it succeeds or SECONDS pass.
poll() {
  local deadline=$((SECONDS + $1))
  shift
  until "$@"; do
    ((SECONDS < deadline)) || return 1
    sleep 0.1
  done
}

is_group_leader() {
  [[ $(ps -o pgid= -p "$1" | tr -d ' ') == "$1" ]]
}

solve_running_in_group() {
  pgrep -g "$1" -f 'helios-solve.*T01' >/dev/null
}

group_gone() {
  ! pgrep -g "$1" >/dev/null
}

# assert_ran TOOL...: make's output shows these tools running; assert_not_ran: it does not.
assert_ran() {
  local t
  for t in "$@"; do [[ $output == *"bin/helios-$t' "* ]] || { echo "make did not run helios-$t:" >&2; echo "$output" >&2; return 1; }; done
}
assert_not_ran() {
  local t
  for t in "$@"; do [[ $output != *"bin/helios-$t' "* ]] || { echo "make ran helios-$t:" >&2; echo "$output" >&2; return 1; }; done
}

# ---- tests -------------------------------------------------------------------------------------

@test "pipeline: make scenario=T01 runs the whole chain and scores 100" {
  rm -rf "$RUNDIR"
  run -0 pmake
  assert_ran parse derive verify gen solve score
  local f
  for f in "${ARTIFACTS[@]}" trajectory.csv; do [[ -s $RUNDIR/$f ]] || { echo "missing $f" >&2; false; }; done
  assert_png "$RUNDIR/trajectory.png"
  assert_png "$RUNDIR/throttle_mass.png"
  assert_jq "$RUNDIR/spec.json" '.problem.id == "T01"'
  assert_jq "$RUNDIR/verify.json" '.verdict == "pass"'
  assert_jq "$RUNDIR/solution.json" '.status == "converged" and .max_residual < 1e-10'
  assert_jq "$RUNDIR/score.json" '.scenario == "T01" and .total == 100'
  # The OEM, read by the independent parser of oem.bats against trajectory.csv (S01: no epoch).
  run -0 awk -v epoch0=0.5 -f "$ROOT/tests/bats/oem_check.awk" "$RUNDIR/trajectory.csv" "$RUNDIR/trajectory.oem"
  [[ $output == "segments 1 data_lines "* ]] || { echo "$output" >&2; false; }
  assert_no_temp_files "$RUNDIR"
}

@test "pipeline: a second make does nothing" {
  ensure_built
  local before after
  before="$(snapshot "${ARTIFACTS[@]}" trajectory.csv trajectory.png throttle_mass.png)"
  run -0 pmake -q
  run -0 pmake
  [[ $output == *"Nothing to be done"* ]] || { echo "$output" >&2; false; }
  assert_not_ran parse derive verify gen solve score
  after="$(snapshot "${ARTIFACTS[@]}" trajectory.csv trajectory.png throttle_mass.png)"
  [[ $before == "$after" ]] || { diff <(echo "$before") <(echo "$after") >&2; false; }
}

@test "pipeline: touching settings.json re-runs only solve and score" {
  ensure_built
  local before_early before_late f
  before_early="$(snapshot "${EARLY[@]}")"
  declare -A before_late
  for f in "${LATE[@]}"; do before_late[$f]="$(mtime_of "$f")"; done
  sleep 0.05 # past the file system's timestamp granularity
  touch "$PIPE_SCENARIOS/T01/settings.json"
  run -1 pmake -q
  run -0 pmake
  assert_ran solve score
  assert_not_ran parse derive verify gen
  [[ $(snapshot "${EARLY[@]}") == "$before_early" ]]
  for f in "${LATE[@]}"; do
    (($(mtime_of "$f") > ${before_late[$f]})) || { echo "$f was not rebuilt" >&2; false; }
  done
  assert_jq "$RUNDIR/score.json" '.total == 100'
  run -0 pmake -q
}

@test "pipeline: a rebuilt tool whose bytes did not change re-runs nothing (touch score.cpp)" {
  ensure_built
  local before
  before="$(snapshot "${ARTIFACTS[@]}")"
  tree_copy
  sleep 0.05 # past the file system's timestamp granularity
  touch "$COPY/tools/lib/src/score/score.cpp"
  # without -o: the copy's tools are rebuilt (the library and every tool relinked), byte for byte the same
  run -0 make_on_copy
  [[ $output == *"Linking CXX executable bin/helios-score"* ]] || { echo "the tools were not rebuilt: $output" >&2; false; }
  assert_not_ran parse derive verify gen solve score
  [[ $(snapshot "${ARTIFACTS[@]}") == "$before" ]]
  run -0 pmake -q
}

@test "pipeline: an edit of score.cpp rebuilds the tools and re-runs helios-score alone" {
  ensure_built
  tree_copy
  local before
  before="$(snapshot "${ARTIFACTS[@]:0:5}")"
  # A real change of helios-score's bytes (an unreferenced constant, no change of behaviour); no
  # other tool links the score module, so their bytes and stamps stay the same.
  printf '\nnamespace helios::score {\nextern const char kPipelineProbe[];\nconst char kPipelineProbe[] = "%s";\n}\n' \
    "$BATS_TEST_NAME" >>"$COPY/tools/lib/src/score/score.cpp"
  run -0 make_on_copy
  assert_ran score
  assert_not_ran parse derive verify gen solve
  [[ $(snapshot "${ARTIFACTS[@]:0:5}") == "$before" ]]
}

@test "pipeline: a deleted solution.json is remade (make -q reports it)" {
  ensure_built
  local before_early
  before_early="$(snapshot "${EARLY[@]}")"
  rm -f "$RUNDIR/solution.json"
  run -1 pmake -q
  run -0 pmake
  assert_ran solve score
  assert_not_ran parse derive verify gen
  [[ -s $RUNDIR/solution.json ]]
  [[ $(snapshot "${EARLY[@]}") == "$before_early" ]]
}

@test "pipeline: make killed mid-solve leaves no partial artifacts, and a rerun resumes" {
  ensure_built
  local before_early score_before
  before_early="$(snapshot "${EARLY[@]}")"
  score_before="$(mtime_of score.json)"
  # The state of a first run that reached the solve (score.json goes too: with it in place, make
  # 4.3 would not remake the missing intermediate solution.json, see the test above).
  rm -f "$RUNDIR/solution.json" "$RUNDIR/score.json"
  # A fresh compile cache and a compiler that waits 30 s before it compiles: the window to interrupt
  # helios-solve, whatever the machine's speed (against the prebuilt runtime T01 compiles and solves
  # in about a second, less than a poll and a sleep on a fast machine). It is g++ on the PATH and
  # its --version line is the real one, so the rerun's compile key is the same.
  MAKE_CACHE="$BATS_TEST_TMPDIR/cache"
  local slow_bin="$BATS_TEST_TMPDIR/slow-compiler/bin"
  mkdir -p "$slow_bin"
  printf '#!/bin/sh\n[ "$1" = --version ] || sleep 30\nexec /usr/bin/g++ "$@"\n' >"$slow_bin/g++"
  chmod +x "$slow_bin/g++"
  PATH="$slow_bin:$PATH" setsid bash -c "$(declare -p MAKE_CACHE); $(declare -f make_t01 pmake unnested_make); pmake" \
    >"$BATS_TEST_TMPDIR/make.log" 2>&1 3>&- &
  local pid=$!
  # setsid execs the bash that runs make as the leader of a new process group; never signal any other group.
  if ! poll 5 is_group_leader "$pid"; then
    kill "$pid" 2>/dev/null || true
    cat "$BATS_TEST_TMPDIR/make.log" >&2
    echo "make ($pid) did not become a process group leader" >&2
    false
  fi
  if ! poll 120 solve_running_in_group "$pid"; then
    kill -TERM -- "-$pid" 2>/dev/null || true
    cat "$BATS_TEST_TMPDIR/make.log" >&2
    echo "helios-solve never started" >&2
    false
  fi
  sleep 1
  solve_running_in_group "$pid" || { echo "helios-solve finished before it could be interrupted" >&2; false; }
  kill -TERM -- "-$pid"
  local rc=0
  wait "$pid" || rc=$?
  ((rc != 0)) || { echo "make exited 0 although it was killed" >&2; false; }
  poll 10 group_gone "$pid" || { echo "processes of the killed make are still running:" >&2; pgrep -a -g "$pid" >&2; false; }
  echo "--- log of the interrupted make:"
  cat "$BATS_TEST_TMPDIR/make.log"

  [[ ! -e $RUNDIR/solution.json ]] || { echo "solution.json exists after the interrupted solve" >&2; false; }
  assert_no_temp_files "$RUNDIR"
  assert_no_temp_files "$MAKE_CACHE"
  # The kill came while the compiler waited: no binary is in the cache and the rerun compiles anew.
  ! compgen -G "$MAKE_CACHE/*/shoot" >/dev/null || { echo "a binary is in the cache although the compile was killed" >&2; false; }
  [[ $(snapshot "${EARLY[@]}") == "$before_early" ]]
  run -1 pmake -q

  # The rerun resumes at the solve: only solution.json and score.json are made.
  run -0 pmake
  assert_ran solve score
  assert_not_ran parse derive verify gen
  [[ $(snapshot "${EARLY[@]}") == "$before_early" ]]
  [[ -s $RUNDIR/solution.json && -s $RUNDIR/score.json ]]
  (($(mtime_of score.json) > score_before))
  (($(mtime_of solution.json) > score_before))
  assert_jq "$RUNDIR/solution.json" ".status == \"converged\" and .compile.ok and (.compile.cached | not)"
  assert_jq "$RUNDIR/score.json" '.total == 100'
  assert_no_temp_files "$RUNDIR"
  run -0 pmake -q
}

#!/usr/bin/env bats
# Launch-window sweeps (tools/lib/src/sweep/README.md): make sweep sweep=P01 on its small CI grid
# (3 departures x 3 times of flight): each departure's minimum-time boundary, sweep.csv and
# porkchop.png, the chains' warm starts, the neighbour cross-check, a cell below its boundary
# called infeasible and not solved, a second make that does nothing, a killed sweep that resumes
# without redoing a cell, and helios-solve --warm-start's refusals. Runs go to private RUNS_ROOTs
# under $BATS_FILE_TMPDIR.

load test_helper

BATS_NO_PARALLELIZE_WITHIN_FILE=true

setup_file() {
  require_tool parse derive verify gen solve score
  export RUNS="$BATS_FILE_TMPDIR/runs" SHARED_CACHE="$BATS_FILE_TMPDIR/cache"
}

setup() {
  common_setup
}

CELLS=(d9700_t300 d9700_t350 d9700_t400 d9740_t300 d9740_t350 d9740_t400 d9780_t300 d9780_t350 d9780_t400)

@test "sweep: make sweep sweep=P01 writes sweep.csv and porkchop.png; each row's first cell cold, the others warm" {
  run -0 sweep_make "$RUNS"
  local dir="$RUNS/builtin/P01"
  [[ -s $dir/sweep.csv ]]
  [[ $(head -n 1 "$dir/sweep.csv") == "departure_mjd2000,tof_days,cell,status,propellant_kg,max_residual,start,answer_from,extremals_compared,t_min_days,boundary_saturated" ]]
  [[ $(tail -n +2 "$dir/sweep.csv" | wc -l) -eq 9 ]]
  local cell dep tof name status objective residual start from compared t_min saturated
  while IFS=, read -r dep tof name status objective residual start from compared t_min saturated; do
    [[ $name == "d${dep}_t${tof}" ]] || { echo "row $name is not d${dep}_t${tof}" >&2; false; }
    [[ $status == converged ]] || { echo "$name: $status" >&2; false; }
    # Earth -> Mars at 0.5 N, Isp 2000 s, 1000 kg: some hundred kg of propellant, a tight residual.
    awk -v m="$objective" -v r="$residual" 'BEGIN { exit !(m > 100 && m < 900 && r < 1e-9) }' ||
      { echo "$name: $objective kg, residual $residual" >&2; false; }
    if [[ $tof == 300 ]]; then
      [[ $start == cold ]] || { echo "$name (a row's first cell) started $start" >&2; false; }
      assert_jq "$dir/$name/solution.json" '(has("warm_start") | not) and .start == "cold"'
    else
      [[ $start == warm ]] || { echo "$name started $start" >&2; false; }
      local prev=$((tof - 50))
      assert_jq "$dir/$name/solution.json" \
        ".warm_start.used and .warm_start.neighbour_status == \"converged\" and (.warm_start.from | endswith(\"/d${dep}_t${prev}/solution.json\")) and .search.starts == 0"
    fi
    # The cell's problem text is the template's with the swept values.
    grep -qx "The spacecraft departs at MJD2000 $dep from Earth." "$dir/$name/problem.txt"
    grep -qx "The time of flight is $tof days." "$dir/$name/problem.txt"
    # Every cell is above its departure's boundary: the minimum-time transfer of the same problem,
    # solved to a saturated search (0.5 N Earth -> Mars: some 250-300 days in this window).
    awk -v t="$t_min" -v f="$tof" 'BEGIN { exit !(t > 240 && t < 300 && t <= f) }' ||
      { echo "$name: t_min $t_min" >&2; false; }
    [[ $saturated == true && $from == own && $compared -ge 1 ]] || { echo "$name: $from $compared $saturated" >&2; false; }
  done < <(tail -n +2 "$dir/sweep.csv")
  [[ $(head -c 8 "$dir/porkchop.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]]
  # The boundary's problem: the template's with the time of flight free and minimized.
  grep -qx "The spacecraft departs at MJD2000 9740 from Earth." "$dir/b9740/problem.txt"
  grep -qx "The time of flight is free, between 50 days and 700 days." "$dir/b9740/problem.txt"
  grep -qx "Minimize the time of flight." "$dir/b9740/problem.txt"
  assert_jq "$dir/b9740/solution.json" '.status == "converged" and .search.saturated and .max_residual < 1e-9'
  assert_jq "$dir/b9740/settings.json" 'has("search_starts") | not'
}

@test "sweep: the cross-check re-solves each cell from its converged neighbours and keeps the best" {
  run -0 sweep_make "$RUNS"
  local dir="$RUNS/builtin/P01"
  assert_jq "$dir/crosscheck.json" '.schema == "helios/sweep-crosscheck" and .saturated and .rounds >= 1 and (.cells | length) == 9'
  # Round 1 tries every cell from each of its grid neighbours (all converged): 24 tries on 3 x 3.
  assert_jq "$dir/crosscheck.json" '[.cells[].tried[] | select(.round == 1)] | length == 24'
  # A cell's answer is never worse than any converged try from a neighbour (1e-9 relative).
  assert_jq "$dir/crosscheck.json" '[.cells[] | .propellant_kg as $m | .tried[] | select(.status == "converged")
    | .propellant_kg >= $m * (1 - 1e-9)] | all'
  # sweep.csv reports each cell's answer: the objective and where it came from.
  local name objective from
  while IFS=, read -r name objective from; do
    assert_jq "$dir/crosscheck.json" ".cells[\"$name\"] | .answer_from == \"$from\" and ((.propellant_kg - $objective) | fabs) <= 1e-6"
  done < <(tail -n +2 "$dir/sweep.csv" | cut -d, -f3,5,8)
  # The tries ran warm only: no search.
  local f
  for f in "$dir"/*/crosscheck/*/solution.json; do
    assert_jq "$f" '.start == "warm" and (.search.starts // 0) == 0'
  done
}

# Issue 46: --sweep writes a row only for a solution of its cell's problem; one that flies another
# time of flight (or another epoch) is refused, naming the cell and the values.
@test "sweep: --sweep refuses a cell's solution of another time of flight or epoch, naming the cell" {
  local copy="$BATS_TEST_TMPDIR/P01" edit answer
  cp -r "$RUNS/builtin/P01" "$copy"
  for edit in '.tof_days = 2100' '.departure_mjd2000 = 19700'; do
    answer="$copy/$(jq -r '.cells.d9740_t350.answer' "$copy/crosscheck.json")"
    jq "$edit" "$RUNS/builtin/P01/$(jq -r '.cells.d9740_t350.answer' "$copy/crosscheck.json")" >"$answer"
    run -3 --separate-stderr "$BIN/helios-score" --sweep "$ROOT/scenarios/P01/sweep.json" --cells "$copy" \
      --crosscheck "$copy/crosscheck.json" -o "$copy/sweep.csv"
    [[ ${#stderr_lines[@]} == 1 && $stderr == "helios-score: error: $answer: the sweep's cell d9740_t350 has a solution that flies "* ]] ||
      { echo "$stderr" >&2; false; }
    [[ $stderr == *"not its grid values, departure MJD2000 9740 and 350 d"* ]]
  done
  [[ $(cat "$copy/sweep.csv") == $(cat "$RUNS/builtin/P01/sweep.csv") ]]
}

# Issue 46: a template whose cells state another time of flight or epoch than their labels (a
# placeholder read in weeks, glued to a digit, only in a comment, in a bound) is refused before any
# cell is solved, in one line naming the cell and the values.
@test "sweep: a template whose cells fly another problem than their labels is refused, no cell solved" {
  local scenarios="$BATS_TEST_TMPDIR/scenarios" runs="$BATS_TEST_TMPDIR/runs" sentence stated
  for sentence in 'The time of flight is @TOF_DAYS@ weeks.:a time of flight of 2100 d' \
    'The time of flight is 1@TOF_DAYS@ days.:a time of flight of 1300 d' \
    'The time of flight is 250 days. # @TOF_DAYS@:a time of flight of 250 d' \
    'The time of flight is free, between @TOF_DAYS@ days and 500 days.:a free time of flight'; do
    stated=${sentence##*:}
    rm -rf "$scenarios" "$runs"
    mkdir -p "$scenarios"
    cp -r "$ROOT/scenarios/P01" "$scenarios/P09"
    sed -i "s/^The time of flight is @TOF_DAYS@ days.\$/${sentence%:*}/; s/ # @TOF_DAYS@/\n# @TOF_DAYS@/" \
      "$scenarios/P09/problem.txt"
    echo '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [300, 350]}, "boundary": false}' \
      >"$scenarios/P09/sweep.json"
    run ! env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u MAKEOVERRIDES make --no-print-directory -C "$ROOT" \
      -o build/tools.stamp sweep sweep=P09 SCENARIOS_DIR="$scenarios" RUNS_ROOT="$runs" CACHE="$SHARED_CACHE"
    [[ $output == *"helios-score: error: $scenarios/P09/problem.txt: the sweep's cell d9700_t300 states departure MJD2000 9700 and $stated, not its grid values, departure MJD2000 9700 and 300 d"* ]] ||
      { echo "$output" >&2; false; }
    [[ -z $(find "$runs" -name 'problem.txt' -o -name solution.json) ]]
  done
}

@test "sweep: a cell below its departure's minimum time is infeasible, with the t_min that proves it, and not solved" {
  local scenarios="$BATS_TEST_TMPDIR/scenarios" runs="$BATS_TEST_TMPDIR/runs"
  mkdir -p "$scenarios"
  cp -r "$ROOT/scenarios/P01" "$scenarios/P01"
  cat >"$scenarios/P01/sweep.json" <<'JSON'
{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [250, 300]},
 "boundary": {"tof_min_days": 50, "tof_max_days": 700}}
JSON
  run -0 sweep_make "$runs" SCENARIOS_DIR="$scenarios"
  local dir="$runs/builtin/P01"
  cat "$dir/sweep.csv" >&2
  [[ $(sed -n 2p "$dir/sweep.csv" | cut -d, -f3,4) == d9700_t250,infeasible ]]
  [[ $(sed -n 3p "$dir/sweep.csv" | cut -d, -f3,4) == d9700_t300,converged ]]
  # t_min (0.5 N, 2000 s, 1000 kg, Earth -> Mars from MJD2000 9700) lies between the two cells.
  awk -F, 'NR == 2 { exit !($10 > 250 && $10 < 300 && $11 == "true") }' "$dir/sweep.csv"
  [[ ! -e $dir/d9700_t250 ]]
  [[ -s $dir/porkchop.png ]]
}

@test "sweep: a second make does nothing" {
  run -0 sweep_make "$RUNS"
  local dir="$RUNS/builtin/P01" before after
  before="$(stat -c '%n %Y' "$dir"/*/solution.json "$dir"/*/problem.txt "$dir/sweep.csv")"
  sleep 1
  run -0 sweep_make "$RUNS"
  [[ $output != *helios-* ]] || { echo "the second make ran: $output" >&2; false; }
  after="$(stat -c '%n %Y' "$dir"/*/solution.json "$dir"/*/problem.txt "$dir/sweep.csv")"
  [[ $before == "$after" ]]
}

@test "sweep: a warm cell's objective equals its cold search's (1e-9 relative)" {
  run -0 sweep_make "$RUNS"
  run -0 sweep_make "$RUNS" SWEEP_START=cold
  local warm="$RUNS/builtin/P01/sweep.csv" cold="$RUNS/builtin/P01-cold/sweep.csv"
  [[ $(cut -d, -f7 "$cold" | tail -n +2 | sort -u) == cold ]]
  paste -d, <(tail -n +2 "$warm" | cut -d, -f3,5) <(tail -n +2 "$cold" | cut -d, -f3,5) |
    awk -F, '{ d = $2 - $4; if (d < 0) d = -d; if ($1 != $3 || d > 1e-9 * $4) { print "differs: " $0; bad = 1 } } END { exit bad }' >&2
}

@test "sweep: a killed sweep resumes with no cell redone and no partial artifact" {
  local runs="$BATS_TEST_TMPDIR/runs" dir="$BATS_TEST_TMPDIR/runs/builtin/P01"
  export SWEEP_CACHE="$BATS_TEST_TMPDIR/cache"  # its own cache: the compiles make the sweep slow enough to kill
  export -f sweep_make isolated_make unnested_make
  setsid bash -c 'sweep_make "$1" >"$2" 2>&1' _ "$runs" "$BATS_TEST_TMPDIR/first.log" &
  local pid=$! i n=0
  for ((i = 0; i < 1200; i++)); do
    n=$(compgen -G "$dir/d*/solution.json" | wc -l)
    ((n >= 2)) && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  kill -TERM -- "-$pid" 2>/dev/null || true
  wait "$pid" || true
  n=$(compgen -G "$dir/d*/solution.json" | wc -l)
  echo "# killed with $n of 9 cells solved" >&3
  ((n >= 1 && n < 9)) || { echo "the kill came at $n cells: $(cat "$BATS_TEST_TMPDIR/first.log")" >&2; false; }
  [[ ! -e $dir/sweep.csv ]]
  # No partial artifact: every solution.json there is a whole one; no .part file is left but in a
  # killed program's private run folder (.run.PID.*), which the next solve of that cell removes.
  local f
  for f in "$dir"/*/solution.json; do assert_jq "$f" '.status == "converged"'; done
  [[ -z $(find "$dir" -name '*.part' -not -path '*/.run.*') ]] || { find "$dir" -name '*.part' >&2; false; }
  local before
  before="$(stat -c '%n %Y' "$dir"/*/solution.json)"
  sleep 1
  run -0 sweep_make "$runs"
  # The finished cells were not redone: their solution.json files are the same files as before.
  while read -r f t; do
    [[ $(stat -c %Y "$f") == "$t" ]] || { echo "$f was redone" >&2; false; }
  done <<<"$before"
  [[ $(compgen -G "$dir/d*/solution.json" | wc -l) -eq 9 ]]
  [[ $(compgen -G "$dir/b*/solution.json" | wc -l) -eq 3 ]]
  [[ -z $(find "$dir" -name '.run.*' -o -name '*.part') ]] || { find "$dir" -name '.run.*' -o -name '*.part' >&2; false; }
  [[ $(tail -n +2 "$dir/sweep.csv" | cut -d, -f4 | sort -u) == converged ]]
}

@test "sweep: helios-solve --warm-start refuses what is not a solution, and a neighbour of another shape" {
  run -0 sweep_make "$RUNS"
  local cell="$RUNS/builtin/P01/d9700_t350" neighbour="$RUNS/builtin/P01/d9700_t300/solution.json"
  echo '{"a": 1}' >bad.json
  run "$BIN/helios-solve" "$cell/shoot.cpp" --cache-dir "$SHARED_CACHE" --warm-start bad.json \
    --trajectory t.csv -o s.json
  [ "$status" -ne 0 ]
  [[ $output == *"bad.json: field /status"* ]] || { echo "$output" >&2; false; }
  [[ ! -e s.json ]]
  # A neighbour whose variables are named otherwise (another derivation's shape) is refused.
  jq '.x[0].name = "lambda_other"' "$neighbour" >renamed.json
  run -0 "$BIN/helios-solve" "$cell/shoot.cpp" --quiet --cache-dir "$SHARED_CACHE" --warm-start renamed.json \
    --trajectory t.csv -o s.json
  assert_jq s.json '.status == "crashed" and (.status_detail | test("warm start: the neighbour.s variable 0 is lambda_other"))'
  # A neighbour far from the answer: the warm solve fails and the search starts cold.
  jq '.x |= map(.value = 0.3)' "$neighbour" >far.json
  run -0 "$BIN/helios-solve" "$cell/shoot.cpp" --quiet --cache-dir "$SHARED_CACHE" \
    --settings "$ROOT/scenarios/P01/settings.json" --warm-start far.json --trajectory t.csv -o s.json
  assert_jq s.json '.status == "converged" and .start == "cold-after-warm-failed" and .search.starts > 0'
  # A neighbour that did not converge: no guess, a cold start, and the record says why.
  jq '.status = "not_converged" | del(.x)' "$neighbour" >failed.json
  run -0 "$BIN/helios-solve" "$cell/shoot.cpp" --quiet --cache-dir "$SHARED_CACHE" \
    --settings "$ROOT/scenarios/P01/settings.json" --warm-start failed.json --trajectory t.csv -o s.json
  assert_jq s.json '.start == "cold" and (.warm_start.used | not) and (.start_detail | test("did not converge"))'
}

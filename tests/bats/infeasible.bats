#!/usr/bin/env bats
# Infeasibility as a result (templates/runtime/search/bound.hpp): a problem whose bound is below its
# minimum time ends `infeasible` with that minimum time, helios-solve exits 5 with solution.json
# written, and the score and report say so. The minimum time is sought past the bound: a
# minimum-time window opened to the burnout, a fixed final time doubled until starts converge and
# then continued down; it shows the problem infeasible only where the search for it settled (its
# starts saturated). A porkchop's boundary and a single solve share the rule
# (tools/lib/include/helios/solve/verdict.hpp).

load test_helper

setup_file() {
  require_tool parse derive verify gen solve score
  export WORK="$BATS_FILE_TMPDIR" CACHE="$BATS_FILE_TMPDIR/cache"
  # S14 (GTO -> GEO at 60 N, published minimum time 14.800364 h) bounded by 12 h
  mkdir -p "$WORK/time"
  sed -e 's/The time of flight is free, at most 2 days./The time of flight is free, at most 0.5 days./' \
    "$ROOT/scenarios/S14/problem.txt" >"$WORK/time/problem.txt"
  # a P01 cell (0.5 N, Earth to Mars from MJD2000 9400) in 200 days: its minimum time is 326 days
  mkdir -p "$WORK/fixed"
  sed -e 's/@DEPARTURE_MJD2000@/9400/' -e 's/@TOF_DAYS@/200/' "$ROOT/scenarios/P01/problem.txt" >"$WORK/fixed/problem.txt"
  echo '{"seed": 1}' >"$WORK/fixed/settings.json"
  local dir
  for dir in time fixed; do
    "$BIN/helios-parse" "$WORK/$dir/problem.txt" -o "$WORK/$dir/spec.json"
    "$BIN/helios-derive" "$WORK/$dir/spec.json" -o "$WORK/$dir/derivation.json"
    "$BIN/helios-gen" "$WORK/$dir/derivation.json" -o "$WORK/$dir/shoot.cpp"
  done
  local status=0
  "$BIN/helios-solve" "$WORK/time/shoot.cpp" --settings "$ROOT/scenarios/S14/settings.json" --cache-dir "$CACHE" \
    --plots "" --trajectory "$WORK/time/trajectory.csv" -o "$WORK/time/solution.json" 2>"$WORK/time/stderr" || status=$?
  echo "$status" >"$WORK/time/exit"
  status=0
  "$BIN/helios-solve" "$WORK/fixed/shoot.cpp" --settings "$WORK/fixed/settings.json" --cache-dir "$CACHE" \
    --plots "" --trajectory "$WORK/fixed/trajectory.csv" -o "$WORK/fixed/solution.json" 2>"$WORK/fixed/stderr" || status=$?
  echo "$status" >"$WORK/fixed/exit"
}

setup() {
  common_setup
}

@test "infeasible: a minimum-time bound below the minimum time ends infeasible with it, exit 5" {
  local sol="$WORK/time/solution.json"
  [[ $(cat "$WORK/time/exit") == 5 ]]
  assert_jq "$sol" '.status == "infeasible" and (.status_detail | test("no transfer within the stated bound of 12 h"))'
  # the minimum time found past the bound is S14's published one
  assert_jq "$sol" '.search.minimum_time | .settled and .bound_days == 0.5 and ((.tf_days * 24 - 14.800364354648908) | fabs) < 1e-5'
  assert_jq "$sol" '[.search.routes[] | select(.name == "minimum time past the bound")][0].ran'
  grep -q '^helios-solve: search: infeasible: no transfer within the stated bound of 12 h' "$WORK/time/stderr"
}

@test "infeasible: a fixed time of flight below the minimum time ends infeasible with it, the same as the porkchop's boundary" {
  local sol="$WORK/fixed/solution.json"
  [[ $(cat "$WORK/fixed/exit") == 5 ]]
  assert_jq "$sol" '.status == "infeasible" and .search.minimum_time.settled and .search.minimum_time.bound_days == 200'
  # the P01 boundary's minimum time at this departure (minimum_time.bats: 326.0 days through the companion)
  assert_jq "$sol" '(.search.minimum_time.tf_days - 325.9929) | fabs < 1e-3'
}

@test "infeasible: a minimum time beyond the bound from a search that did not settle proves nothing" {
  # P01's own settings cap the starts at 16: they cannot saturate, so the verdict is not infeasible
  run --separate-stderr "$BIN/helios-solve" "$WORK/fixed/shoot.cpp" --settings "$ROOT/scenarios/P01/settings.json" \
    --cache-dir "$CACHE" --plots "" --trajectory trajectory.csv -o solution.json
  [ "$status" -eq 0 ]
  assert_jq solution.json '.status == "not_converged" and (.search.minimum_time.settled | not)'
  assert_jq solution.json '.status_detail | test("did not settle")'
}

@test "infeasible: the report says so, with the minimum time and what each route did" {
  "$BIN/helios-derive" "$WORK/time/spec.json" -o derivation.json
  "$BIN/helios-score" --report --problem "$WORK/time/problem.txt" --spec "$WORK/time/spec.json" \
    --derivation derivation.json --solution "$WORK/time/solution.json" -o report.md
  grep -q '^| `status` | infeasible |' report.md
  grep -q '^The minimum time found: 0.61668' report.md
  grep -q '^| minimum time past the bound | yes |' report.md
}

# A solar-electric engine's mass flow follows the Sun's distance: the route once skipped it, so such
# a problem ended "0 converged" like a solver failure. An NSTAR-like thruster (fits of thrust and
# mass flow, 5 kW arrays) on S01's 348.795-day rendezvous at 350 kg: infeasible, and the minimum time
# it gives is the one the same transfer's minimum-time problem returns (a separate program and
# search). The fuel extremals at the doubled final time come down to 638 days only (one family): the
# minimum-time problem's own starts there find the shorter one.
@test "infeasible: a solar-electric problem below its minimum time ends infeasible with the minimum-time problem's answer" {
  local sentence="The spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW.\nThe thruster's thrust is -1.9137 + 36.242 P - 0.5 P^2 mN and its mass flow is 0.47556 + 0.90209 P + 0.01 P^3 mg\/s for an input power P between 0.5 and 2.6 kW.\nThe spacecraft has an initial mass of 350 kg."
  mkdir -p "$WORK/sep-fixed" "$WORK/sep-time"
  sed -e "s/^The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.\$/$sentence/" \
    "$ROOT/scenarios/S01/problem.txt" >"$WORK/sep-fixed/problem.txt"
  sed -e 's/^The time of flight is 348.795 days.$/The time of flight is at most 1000 days./' \
    -e 's/^Minimize the fuel consumption.$/Minimize the time of flight./' "$WORK/sep-fixed/problem.txt" >"$WORK/sep-time/problem.txt"
  grep -q 'at most 1000 days' "$WORK/sep-time/problem.txt"
  local status=0
  run_chain "$WORK/sep-fixed/problem.txt" "" "$WORK/sep-fixed" || status=$?
  [[ $status == 5 ]] || { tail -5 "$WORK/sep-fixed/stderr" >&2; return 1; }
  run_chain "$WORK/sep-time/problem.txt" "" "$WORK/sep-time"
  assert_jq "$WORK/sep-time/solution.json" '.status == "converged" and .search.saturated'
  local fixed="$WORK/sep-fixed/solution.json"
  assert_jq "$fixed" '.status == "infeasible" and .search.minimum_time.settled and .search.minimum_time.bound_days == 348.795'
  within "$(jq '.search.minimum_time.tf_days' "$fixed")" "$(jq '.tof_days' "$WORK/sep-time/solution.json")" 1e-8
}

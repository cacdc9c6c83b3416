#!/usr/bin/env bats
# A final condition that is an orbit (S14: GTO -> GEO in minimum time at 60 N, the circular
# equatorial orbit of radius 42165 km with the longitude free). The chain runs cold from the
# problem text; the published shooting solution is t_f = 14.800364354648908 h (control-toolbox
# tutorial, after Caillau, Gergaud and Noailles 2003).
#
# setup_file runs S14's chain once.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/s14"
  run_chain "$ROOT/scenarios/S14/problem.txt" "$ROOT/scenarios/S14/settings.json" "$WORK"
}

setup() {
  common_setup
}

@test "orbit target: the derivation keeps the multipliers of the orbit's five rows and every transversality row, and verifies" {
  assert_jq "$WORK/derivation.json" '[.constraints[] | select(.kind == "orbit_insertion") | .psi | length] == [5]'
  assert_jq "$WORK/derivation.json" '[.shooting.variables[] | select(.name | startswith("nu_arrival_"))] | length == 5'
  assert_jq "$WORK/derivation.json" '[.shooting.equations[] | select(.name | startswith("transversality_"))] | length == 8'
  assert_jq "$WORK/verify.json" '.verdict == "pass"'
}

@test "orbit target: the rows also hold on the retrograde GEO; h.n > 0 keeps every extremal there from being returned" {
  assert_jq "$WORK/derivation.json" '.constraints[1].must_be_positive | length == 1 and (.[0].meaning | startswith("h.n_arrival > 0"))'
  assert_jq "$WORK/solution.json" '.search.extremals[.search.returned] | has("off_side") | not'
  assert_jq "$WORK/solution.json" 'all(.search.extremals[] | select(has("off_side")); .off_side | startswith("h.n_arrival > 0"))'
}

@test "orbit target: S14 reaches t_f = 14.80036 +- 0.00001 h cold, on the orbit, with H = 0 along the extremal" {
  assert_s14_minimum_time "$WORK/solution.json"
  assert_ends_on_geo "$WORK/trajectory.csv"
}

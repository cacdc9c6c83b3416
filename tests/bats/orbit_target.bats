#!/usr/bin/env bats
# A final condition that is an orbit (S14: GTO -> GEO in minimum time at 60 N, the circular
# equatorial orbit of radius 42165 km with the longitude free). The chain runs cold from the
# problem text; the published shooting solution is t_f = 14.800364354648908 h (control-toolbox
# tutorial, after Caillau, Gergaud and Noailles 2003).
#
# setup_file runs S14's chain once; the orbits on the way run their own.

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

# S14 with an orbit on the way (a semi-major axis met inside a window), solved cold.
s14_with_orbit_on_the_way() {
  local name=$1 sentence=$2
  sed -e "s/The time of flight is free, at most 2 days./& $sentence/" "$ROOT/scenarios/S14/problem.txt" \
    >"$BATS_TEST_TMPDIR/$name.txt"
  grep -qF "$sentence" "$BATS_TEST_TMPDIR/$name.txt"
  run_chain "$BATS_TEST_TMPDIR/$name.txt" "$ROOT/scenarios/S14/settings.json" "$BATS_TEST_TMPDIR/$name"
}

@test "orbit on the way: one the minimum-time transfer crosses anyway changes nothing (t_f as S14's, nu = 0)" {
  s14_with_orbit_on_the_way crossed \
    "The spacecraft passes through an orbit with semi-major axis 35000 km between day 0.1 and day 0.6."
  local sol="$BATS_TEST_TMPDIR/crossed/solution.json"
  assert_jq "$BATS_TEST_TMPDIR/crossed/verify.json" '.verdict == "pass"'
  assert_s14_minimum_time "$sol"
  assert_jq "$sol" '[.x[] | select(.name | startswith("nu_orbit_")) | .value | fabs] | length == 3 and max < 1e-10'
}

@test "orbit on the way: one reached earlier than the transfer would costs time, its multiplier and window active" {
  s14_with_orbit_on_the_way early \
    "The spacecraft passes through an orbit with semi-major axis 29000 km between day 0.05 and day 0.1."
  local sol="$BATS_TEST_TMPDIR/early/solution.json"
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10 and .hamiltonian_drift < 1e-10'
  # longer than S14's 14.800364 h, the orbit met at the window's end with a nonzero multiplier
  assert_jq "$sol" '.tof_days * 24 > 14.8004 + 0.01'
  assert_jq "$sol" '(.x[] | select(.name == "t_orbit_frac") | .value) > 1 - 1e-9'
  assert_jq "$sol" '(.x[] | select(.name == "nu_orbit_1") | .value | fabs) > 1e-3'
  assert_ends_on_geo "$BATS_TEST_TMPDIR/early/trajectory.csv"
}

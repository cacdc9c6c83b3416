#!/usr/bin/env bats
# Conditions written as equations of the final state ("At the final time |r| = 42165 km, r·v = 0
# and |r|·|v|² = mu."): S14's transfer with its final orbit so written
# (tests/fixtures/problems/geo_by_equations.txt). Another psi for the same orbit: the chain must
# reach S14's published minimum time, 14.800364354648908 h, cold.
#
# setup_file runs the chain once.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/equations"
  run_chain "$ROOT/tests/fixtures/problems/geo_by_equations.txt" "$ROOT/scenarios/S14/settings.json" "$WORK"
}

setup() {
  common_setup
}

@test "state conditions: five rows of psi in the state, their multipliers unknowns, and the derivation verifies" {
  assert_jq "$WORK/spec.json" '.constraints[1].kind == "state_conditions" and (.constraints[1].target.conditions | length) == 5'
  assert_jq "$WORK/derivation.json" '[.constraints[] | select(.id == "arrival") | .psi | length] == [5]'
  assert_jq "$WORK/derivation.json" '[.shooting.variables[] | select(.name | startswith("nu_arrival_"))] | length == 5'
  assert_jq "$WORK/derivation.json" '(.shooting.variables | length) == (.shooting.equations | length)'
  assert_jq "$WORK/verify.json" '.verdict == "pass"'
}

@test "state conditions: S14's minimum time cold, the equations met at tf, H = 0" {
  assert_s14_minimum_time "$WORK/solution.json"
  assert_ends_on_geo "$WORK/trajectory.csv"
}

#!/usr/bin/env bats
# An objective on the final state with the engine at full throttle throughout: Bryson and Ho's
# maximum-radius orbit transfer (tests/fixtures/problems/maximum_radius.txt), the thrust direction
# the only control, onto the circular orbit of largest radius at a fixed final time. Published
# (Applied Optimal Control, 1975, section 2.5): r(tf) = 1.525 r0. The chain runs cold.
#
# setup_file runs the chain once.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/maxr"
  run_chain "$ROOT/tests/fixtures/problems/maximum_radius.txt" "$ROOT/scenarios/S14/settings.json" "$WORK"
}

setup() {
  common_setup
}

@test "maximum radius: a Mayer term phi = -|r(tf)|, no running cost, no throttle, and the derivation verifies" {
  assert_jq "$WORK/spec.json" '.objective.kind == "maximum_final_radius" and .spacecraft.full_throttle == true'
  assert_jq "$WORK/derivation.json" '.dynamics.endpoint_cost == "-sqrt(rx^2+ry^2+rz^2)" and .dynamics.running_cost == "0"'
  assert_jq "$WORK/derivation.json" '[.controls[].name] == ["ax", "ay", "az"]'
  assert_jq "$WORK/derivation.json" '[.terms[].name] == ["two_body", "full_thrust", "final_radius"]'
  assert_jq "$WORK/verify.json" '.verdict == "pass"'
}

@test "maximum radius: converges cold to Bryson and Ho's r(tf) = 1.525 r0 on a circular orbit, H constant" {
  local sol="$WORK/solution.json"
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10'
  assert_jq "$sol" '(.final_radius_km / 149597870.7 - 1.525) | fabs < 5e-4'
  # full throttle: the propellant is the mass flow times the flight, 0.0749 m0 per time unit for 3.32
  assert_jq "$sol" '(.propellant_kg - 0.0749 * 3.32 * 10000) | fabs < 1e-6'
  assert_jq "$sol" '.hamiltonian_drift < 1e-10'
  # on a circular orbit at tf (r.v = 0, |r| |v|^2 = mu), and along the arc the direction is
  # a = -lambda_v/|lambda_v| (H minimized over the unit vector)
  tail -n 1 "$WORK/trajectory.csv" | awk -F, '{
    mu = 132712440018; r = sqrt($2*$2 + $3*$3 + $4*$4); v2 = $5*$5 + $6*$6 + $7*$7; rv = $2*$5 + $3*$6 + $4*$7
    if ((rv / (r * sqrt(v2)))^2 > 1e-20 || (r * v2 / mu - 1)^2 > 1e-20) { printf "r.v %g r v^2/mu %.15f\n", rv, r * v2 / mu > "/dev/stderr"; exit 1 }
  }'
  awk -F, 'NR > 1 {
    n = sqrt($12*$12 + $13*$13 + $14*$14)
    d = ($16 + $12/n)^2 + ($17 + $13/n)^2 + ($18 + $14/n)^2
    if (d > 1e-20) { printf "row %d: a is not -lambda_v/|lambda_v| (%g)\n", NR, d > "/dev/stderr"; bad = 1 }
  } END { exit bad }' "$WORK/trajectory.csv"
}

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

@test "orbit target: S14 reaches t_f = 14.80036 +- 0.00001 h cold, on the orbit, with H = 0 along the extremal" {
  local sol="$WORK/solution.json"
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10'
  assert_jq "$sol" '(.tof_days * 24 - 14.800364354648908) | fabs <= 1e-5'
  # minimum time with tf free: H(t) = 0 on the whole arc, the drift at round-off
  assert_jq "$sol" '.hamiltonian_drift < 1e-10'
  # the last row of the trajectory: |r| = 42165 km, r.v = 0, |v| = sqrt(mu/42165), z and vz 0
  tail -n 1 "$WORK/trajectory.csv" | awk -F, '{
    r = sqrt($2*$2 + $3*$3 + $4*$4); v = sqrt($5*$5 + $6*$6 + $7*$7); rv = $2*$5 + $3*$6 + $4*$7
    ok = (r - 42165 < 1e-4 && 42165 - r < 1e-4) && (rv * rv < 1e-20 * r * r * v * v) && \
         ((v - sqrt(398600.47 / 42165))^2 < 1e-16) && ($4^2 < 1e-8) && ($7^2 < 1e-16)
    if (!ok) { printf "r %.9f v %.12f r.v %g z %g vz %g\n", r, v, rv, $4, $7 > "/dev/stderr"; exit 1 }
  }'
}

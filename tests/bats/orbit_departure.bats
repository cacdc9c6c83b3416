#!/usr/bin/env bats
# A departure anywhere on an orbit (pykep's or2or kind): S14's transfer with the departure point
# on the GTO free (tests/fixtures/problems/gto_anywhere_to_geo.txt). The chain runs cold from the
# problem text. S14's start, the GTO's apogee, is one admissible departure, so the minimum time
# with the point free is no longer than S14's published 14.800364354648908 h.
#
# setup_file runs the chain once.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/or2or"
  run_chain "$ROOT/tests/fixtures/problems/gto_anywhere_to_geo.txt" "$ROOT/scenarios/S14/settings.json" "$WORK"
}

setup() {
  common_setup
}

@test "orbit departure: the anomaly is an unknown with its stationarity row, and the derivation verifies" {
  assert_jq "$WORK/derivation.json" '[.shooting.variables[] | select(.name == "theta_departure" and .role == "initial_state")] | length == 1'
  assert_jq "$WORK/derivation.json" '[.shooting.equations[] | select(.name == "stationarity_departure_theta_departure")] | length == 1'
  assert_jq "$WORK/derivation.json" '(.shooting.variables | length) == (.shooting.equations | length)'
  assert_jq "$WORK/verify.json" '.verdict == "pass"'
  assert_jq "$WORK/verify.json" '[.checks[] | select(.id == "initial_stationarity:departure_theta_departure" and .verdict == "pass")] | length == 1'
}

@test "orbit departure: converges cold, no slower than from the apogee, leaving from the GTO and arriving on GEO, H = 0" {
  local sol="$WORK/solution.json"
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10'
  assert_jq "$sol" '[.residuals[] | select(.name == "stationarity_departure_theta_departure") | .value | fabs < 1e-10] == [true]'
  assert_jq "$sol" '.tof_days * 24 < 14.800364354648908'
  assert_jq "$sol" '.hamiltonian_drift < 1e-10'
  # the first row on the GTO (a = 26571.43 km, e = 0.75, i = 7.0043 deg), the last on GEO
  sed -n 2p "$WORK/trajectory.csv" | awk -F, '{
    mu = 398600.47; r = sqrt($2*$2 + $3*$3 + $4*$4); v2 = $5*$5 + $6*$6 + $7*$7
    a = 1 / (2 / r - v2 / mu)
    hx = $3*$7 - $4*$6; hy = $4*$5 - $2*$7; hz = $2*$6 - $3*$5; h = sqrt(hx*hx + hy*hy + hz*hz)
    e = sqrt(1 - h*h / (mu * a)); i = atan2(sqrt(hx*hx + hy*hy), hz) * 180 / 3.141592653589793
    ok = ((a - 26571.428571428576)^2 < 1e-12) && ((e - 0.75)^2 < 1e-20) && ((i - 7.004267441546314)^2 < 1e-16) && (hx^2 < 1e-6)
    if (!ok) { printf "a %.9f e %.12f i %.12f hx %g\n", a, e, i, hx > "/dev/stderr"; exit 1 }
  }'
  tail -n 1 "$WORK/trajectory.csv" | awk -F, '{
    r = sqrt($2*$2 + $3*$3 + $4*$4)
    if ((r - 42165)^2 > 1e-8 || $4^2 > 1e-8 || $7^2 > 1e-16) { printf "r %.9f z %g vz %g\n", r, $4, $7 > "/dev/stderr"; exit 1 }
  }'
}

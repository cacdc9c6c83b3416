#!/usr/bin/env bats
# Dynamics the template was not written for (issue 4), end to end on the builtin backend:
# J2 (S05, S06 with a coasting target), a solar sail in minimum time (S11) and a user-written
# acceleration (S12). Each chain runs once in setup_file into $BATS_FILE_TMPDIR/<scenario>.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve score
  local s
  for s in S05 S06 S11 S12; do
    chain_or_note "$s" "$BATS_FILE_TMPDIR/$s"
  done
  grep -v "include the J2 perturbation" "$ROOT/scenarios/S05/problem.txt" >"$BATS_FILE_TMPDIR/S05-noJ2.txt"
  chain_or_note S05 "$BATS_FILE_TMPDIR/S05-noJ2" "$BATS_FILE_TMPDIR/S05-noJ2.txt"
}

setup() {
  common_setup
  chains_passed
}


@test "dynamics: S05 (J2 orbit raise) converges, verified, score 100, with generated modules" {
  converged_and_verified "$BATS_FILE_TMPDIR/S05"
  grep -q "module RESIDUAL (generated)" "$BATS_FILE_TMPDIR/S05/shoot.cpp"
  grep -q "modules DYNAMICS + SWITCH (generated from the derivation)" "$BATS_FILE_TMPDIR/S05/shoot.cpp"
  assert_jq "$BATS_FILE_TMPDIR/S05/derivation.json" '.shooting.variables | length == 8'
}

@test "dynamics: J2 changes S05's final mass measurably (J2 off converges to a different m_f)" {
  local on="$BATS_FILE_TMPDIR/S05/solution.json" off="$BATS_FILE_TMPDIR/S05-noJ2/solution.json"
  assert_jq "$off" '.status == "converged" and .max_residual < 1e-10'
  # NOTE: both are converged to ~1e-9 kg, so a 1 g difference is 1e6 times the solver's noise.
  run -0 jq -n --slurpfile a "$on" --slurpfile b "$off" '($a[0].final_mass_kg - $b[0].final_mass_kg) | fabs > 0.001'
  [[ $output == true ]]
  run -0 jq -e '.costate_odes[0].rhs | test("J2")' "$BATS_FILE_TMPDIR/S05/derivation.json"
  run -1 jq -e '.costate_odes[0].rhs | test("J2")' "$BATS_FILE_TMPDIR/S05-noJ2/derivation.json"
}

@test "dynamics: S06 rendezvous with a target coasting under J2 converges, score 100" {
  converged_and_verified "$BATS_FILE_TMPDIR/S06"
  assert_jq "$BATS_FILE_TMPDIR/S06/derivation.json" '[.parameters[] | select(.source? // "" | startswith("coast:"))] | length == 6'
  grep -q "coast_state(" "$BATS_FILE_TMPDIR/S06/shoot.cpp"
}

@test "dynamics: S11 solar sail, minimum time: no mass, 8 variables, t_f in days, cone-angle plot" {
  local d="$BATS_FILE_TMPDIR/S11"
  converged_and_verified "$d"
  assert_jq "$d/derivation.json" '(.states | map(.name) | index("m")) == null and (.shooting.variables | length) == 8'
  assert_jq "$d/derivation.json" '.times.final_time == "free" and (.control_law | has("throttle") | not)'
  assert_jq "$d/solution.json" '.tof_days > 100 and .tof_days < 1000 and (has("final_mass_kg") | not)'
  assert_jq "$d/solution.json" '.files.cone_angle_plot == "cone_angle.png"'
  assert_png "$d/cone_angle.png"
  # Every sample's sail normal is a unit vector pointing away from the Sun.
  run -0 awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    { n = $c["nx"]^2 + $c["ny"]^2 + $c["nz"]^2; d = $c["nx"]*$c["rx_km"] + $c["ny"]*$c["ry_km"] + $c["nz"]*$c["rz_km"]
      if (n < 1 - 1e-9 || n > 1 + 1e-9 || d < 0) bad++ } END { print bad + 0 }' "$d/trajectory.csv"
  [[ $output == 0 ]]
}

@test "dynamics: S12 with a user-written SRP acceleration converges, its Jacobian includes d/dm" {
  converged_and_verified "$BATS_FILE_TMPDIR/S12"
  run -0 jq -r '.costate_odes[6].rhs' "$BATS_FILE_TMPDIR/S12/derivation.json"
  [[ $output == *"rx"* ]]  # the SRP term's 1/m makes lambda_m depend on the position
  run -0 jq -n --slurpfile a "$BATS_FILE_TMPDIR/S12/solution.json" '$a[0].final_mass_kg < 603.94'
  [[ $output == true ]]
}

@test "dynamics: each converged run's trajectory.oem passes the independent OEM parser (S05, S06, S11, S12)" {
  local s
  for s in S05 S06 S11 S12; do assert_oem_of_run "$BATS_FILE_TMPDIR/$s"; done
}

#!/usr/bin/env bats
# A third body as one term (issue 31): S01 (Earth to Mars, fixed time, minimum fuel) with Jupiter
# perturbing the spacecraft as a point mass on a circular orbit, at its mu and at twice its mu.
# Physics says the change of the optimal final mass is first order in mu3: doubling mu3 doubles it
# (the second-order part is of the relative size of the perturbation, about 1e-4 here).

load test_helper

# jupiter MU OUT: S01's problem text with Jupiter's sentence at gravitational parameter MU.
jupiter() {
  { cat "$ROOT/scenarios/S01/problem.txt"
    echo "Jupiter perturbs the spacecraft as a point mass of mu = $1 km^3/s^2 on a circular orbit of radius 778570000 km, inclination 1.3 deg, node 100.5 deg, phase 40 deg."
  } >"$2"
}

setup_file() {
  require_tool parse derive verify gen solve score
  local name
  jupiter 126686534 "$BATS_FILE_TMPDIR/J1.txt"
  jupiter 253373068 "$BATS_FILE_TMPDIR/J2.txt"
  chain_or_note S01 "$BATS_FILE_TMPDIR/S01"
  for name in J1 J2; do chain_or_note S01 "$BATS_FILE_TMPDIR/$name" "$BATS_FILE_TMPDIR/$name.txt"; done
}

setup() {
  common_setup
  chains_passed
}

@test "third body: Jupiter is one listed term, recomputed by verify, and the perturbed S01 converges" {
  local d="$BATS_FILE_TMPDIR/J1"
  assert_jq "$d/derivation.json" '[.terms[].name] == ["two_body", "thrust", "third_body", "fuel"]'
  assert_jq "$d/derivation.json" '.terms[2].body == "Jupiter" and (.terms[2].parameters | length) == 6'
  assert_jq "$d/verify.json" '.verdict == "pass" and ([.checks[] | select(.id == "dynamics_terms" or .id == "cost_terms") | .verdict] == ["pass", "pass"])'
  assert_jq "$d/solution.json" '.status == "converged" and .max_residual < 1e-10 and .epsilon == 0'
  assert_jq "$BATS_FILE_TMPDIR/J2/solution.json" '.status == "converged" and .max_residual < 1e-10 and .epsilon == 0'
  grep -q "modules DYNAMICS + SWITCH (generated from the derivation)" "$d/shoot.cpp"
}

@test "third body: the change of the optimal final mass is first order in mu3 (doubling mu3 doubles it)" {
  run -0 jq -n --slurpfile a "$BATS_FILE_TMPDIR/S01/solution.json" --slurpfile b "$BATS_FILE_TMPDIR/J1/solution.json" \
    --slurpfile c "$BATS_FILE_TMPDIR/J2/solution.json" \
    '($b[0].final_mass_kg - $a[0].final_mass_kg) as $d1 | ($c[0].final_mass_kg - $a[0].final_mass_kg) as $d2
     | "\($d1) \($d2) \($d2 / $d1)"'
  read -r d1 d2 ratio <<<"${output//\"/}"
  # NOTE: the solutions are converged to ~1e-9 kg; a change of 1 g is 1e6 times that noise.
  awk -v d="$d1" 'BEGIN { exit !(d > 0.001 || d < -0.001) }'
  awk -v r="$ratio" 'BEGIN { exit !(r > 1.97 && r < 2.03) }'
}

@test "third body: a sentence without the orbit's radius is refused with the sentence to write" {
  { cat "$ROOT/scenarios/S01/problem.txt"
    echo "Jupiter perturbs the spacecraft as a point mass of mu = 126686534 km^3/s^2."
  } >problem.txt
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "the third body Jupiter needs the radius of its circular orbit, e.g. 'The Moon perturbs"
  [[ ! -e spec.json ]]
}

#!/usr/bin/env bats
# Atmospheric drag as one term: S05 (a J2 orbit raise at 7000-7080 km, fixed time, minimum fuel) in an
# exponential atmosphere at two densities. Drag only takes energy, so it costs propellant; and the
# change of the optimal final mass is first order in the density: doubling it doubles the change (the
# second-order part is of the relative size of drag against the engine, about 1e-5 here).

load test_helper

# atmosphere DENSITY OUT: S05's problem text with drag at DENSITY kg/m^3 at 400 km.
atmosphere() {
  { cat "$ROOT/scenarios/S05/problem.txt"
    echo "Atmospheric drag acts on the spacecraft: drag coefficient 2.2, area 4 m^2, in an exponential atmosphere of density $1 kg/m^3 at 400 km altitude with scale height 58 km."
  } >"$2"
}

setup_file() {
  require_tool parse derive verify gen solve score
  local name
  atmosphere 3.6e-11 "$BATS_FILE_TMPDIR/D1.txt"
  atmosphere 7.2e-11 "$BATS_FILE_TMPDIR/D2.txt"
  chain_or_note S05 "$BATS_FILE_TMPDIR/S05"
  for name in D1 D2; do chain_or_note S05 "$BATS_FILE_TMPDIR/$name" "$BATS_FILE_TMPDIR/$name.txt"; done
}

setup() {
  common_setup
  chains_passed
}

@test "drag: one listed term, recomputed by verify, and the S05 with drag converges" {
  local d="$BATS_FILE_TMPDIR/D1"
  assert_jq "$d/derivation.json" '[.terms[].name] == ["two_body", "j2", "thrust", "drag", "fuel"]'
  assert_jq "$d/derivation.json" '.terms[3].parameters == ["Bd", "r0", "H", "w"]'
  assert_jq "$d/verify.json" '.verdict == "pass" and ([.checks[] | select(.id == "dynamics_terms") | .verdict] == ["pass"])'
  assert_jq "$d/solution.json" '.status == "converged" and .max_residual < 1e-10 and .epsilon == 0'
  assert_jq "$BATS_FILE_TMPDIR/D2/solution.json" '.status == "converged" and .max_residual < 1e-10 and .epsilon == 0'
}

@test "drag: it costs propellant, first order in the density (doubling the density doubles the cost)" {
  run -0 jq -n --slurpfile a "$BATS_FILE_TMPDIR/S05/solution.json" --slurpfile b "$BATS_FILE_TMPDIR/D1/solution.json" \
    --slurpfile c "$BATS_FILE_TMPDIR/D2/solution.json" \
    '($a[0].final_mass_kg - $b[0].final_mass_kg) as $d1 | ($a[0].final_mass_kg - $c[0].final_mass_kg) as $d2
     | "\($d1) \($d2) \($d2 / $d1)"'
  read -r d1 d2 ratio <<<"${output//\"/}"
  # NOTE: the solutions are converged to ~1e-9 kg; the cost at the lower density is about 1e5 times that.
  awk -v d="$d1" 'BEGIN { exit !(d > 1e-5) }'
  awk -v r="$ratio" 'BEGIN { exit !(r > 1.99 && r < 2.01) }'
}

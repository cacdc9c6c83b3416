#!/usr/bin/env bats
# Constraint-adaptive derivation (issue 3), end to end on the builtin backend: interior rendezvous
# at free epochs (S03), a position-only flyby (S04), stays with a sliding departure (S07), minimum
# initial mass with a lander and a flyby (S08) and with a bounded arrival speed (S09), a Mars
# gravity assist with a periapsis bound (S10). Each
# chain runs once in setup_file into $BATS_FILE_TMPDIR/<scenario>; the interior-event conditions
# are then checked independently by re-solving with one condition replaced
# (tests/events/sensitivity.cpp).

load test_helper

setup_file() {
  require_tool parse derive verify gen solve score
  local s
  for s in S03 S04 S07 S08 S09 S10; do
    chain_or_note "$s" "$BATS_FILE_TMPDIR/$s"
  done
}

setup() {
  common_setup
  chains_passed
}

# sensitivity SCENARIO ARGS...: the harness built against the scenario's generated program
sensitivity() {
  local dir=$BATS_FILE_TMPDIR/$1
  shift
  if [[ ! -x $dir/sensitivity ]]; then
    g++ -std=c++17 -O2 -fno-math-errno -pthread -DSHOOT_CPP="\"$dir/shoot.cpp\"" -I"$ROOT/templates/runtime" -I"$ROOT/tools/lib/include" \
      "$ROOT/tests/events/sensitivity.cpp" -o "$dir/sensitivity" -lcminpack
  fi
  "$dir/sensitivity" "$dir/solution.json" "$@"
}

@test "events: S03 (three interior rendezvous) converges with the paper's 29 variables + 6 window bounds" {
  converged_and_verified "$BATS_FILE_TMPDIR/S03"
  assert_jq "$BATS_FILE_TMPDIR/S03/derivation.json" '.shooting.variables | length == 35'
  assert_jq "$BATS_FILE_TMPDIR/S03/derivation.json" '[.shooting.equations[] | select(.inequality)] | length == 6'
  # every epoch inside its window: one pass, no bound active
  assert_jq "$BATS_FILE_TMPDIR/S03/solution.json" '.passes == 1 and ([.bounds[] | select(.active)] | length == 0)'
  assert_jq "$BATS_FILE_TMPDIR/S03/derivation.json" '[.events[].kind] == ["rendezvous", "rendezvous", "rendezvous"]'
  # every rendezvous is instantaneous: continued onto from the problem without them
  assert_jq "$BATS_FILE_TMPDIR/S03/solution.json" '.method | startswith("events off, then continuation")'
  assert_jq "$BATS_FILE_TMPDIR/S03/solution.json" '[.continuation[] | select(.stage == "targets" and .value == 1 and .converged)] | length >= 1'
}

@test "events: S04 (flyby) converges with 12 variables + 2 window bounds; the flyby costs fuel against S01" {
  converged_and_verified "$BATS_FILE_TMPDIR/S04"
  assert_jq "$BATS_FILE_TMPDIR/S04/derivation.json" '.shooting.variables | length == 14'
  # position only: three multipliers, the velocity and mass costates carried through unchanged
  assert_jq "$BATS_FILE_TMPDIR/S04/derivation.json" '.events[0].costate_map[3:] | map(.expression) == ["l_vx_ast_9482_m", "l_vy_ast_9482_m", "l_vz_ast_9482_m", "l_m_ast_9482_m"]'
  assert_jq "$BATS_FILE_TMPDIR/S04/solution.json" '.final_mass_kg < 603.94'
}

@test "events: S07 (stays, sliding departure) converges with 48 variables + 6 window bounds, every epoch in its window" {
  converged_and_verified "$BATS_FILE_TMPDIR/S07"
  assert_jq "$BATS_FILE_TMPDIR/S07/derivation.json" '.shooting.variables | length == 54'
  # unbounded, two epochs fall after their windows; the last pass holds one at its window's end
  # with a multiplier >= 0, and every bound holds
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '[.bounds[] | select(.first_pass_value > 0)] | length == 2'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '.passes >= 2 and ([.bounds[] | select(.active)] | length >= 1)'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" 'all(.bounds[]; (.active | not) and .value <= 1e-12 or .active and .multiplier >= 0 and (.value | fabs) < 1e-12)'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" 'all(.x[] | select(.name | test("^t_.*_frac$")); .value >= -1e-12 and .value <= 1 + 1e-12)'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '.departure_mjd2000 > 10306.6 and .departure_mjd2000 < 10366.6'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '(.tof_days - 981.1 | fabs) < 1e-9'
  # stays cannot be switched off: the legs, solved alone and joined
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '.method | test("legs, then multiple shooting")'
  assert_jq "$BATS_FILE_TMPDIR/S07/solution.json" '[.legs[] | select(.converged)] | length >= 4'
  # the sliding-t0 condition carries both ends' target motion, not H(t0) = 0 alone
  assert_jq "$BATS_FILE_TMPDIR/S07/derivation.json" '.shooting.equations[] | select(.name == "transversality_t0") | .expression | test("H_t0") and test("H_tf") and test("departure_rx_rate") and test("arrival_rx_rate")'
}

@test "events: S08 finds the least initial mass: m0 = final mass + propellant + lander, lambda_m continuous" {
  converged_and_verified "$BATS_FILE_TMPDIR/S08"
  local d=$BATS_FILE_TMPDIR/S08/derivation.json sol=$BATS_FILE_TMPDIR/S08/solution.json
  assert_jq "$d" '.shooting.variables | length == 45'
  assert_jq "$d" '[.shooting.variables[] | select(.role == "initial_state") | .name] == ["m_t0"]'
  assert_jq "$d" '.shooting.equations[] | select(.name == "transversality_m_t0") | .expression == "l_m_t0"'
  assert_jq "$d" '.initial_values[] | select(.state == "m") | .value == "m_t0"'
  # the lander: m+ = m- - drop, lambda_m carried through unchanged
  assert_jq "$d" '.events[0].state_map[6].expression == "-drop_nikko+m_nikko_m" and .events[0].costate_map[6].expression == "l_m_nikko_m"'
  assert_jq "$sol" '(.final_mass_kg - 1500 | fabs) < 1e-6'
  assert_jq "$sol" '(.initial_mass_kg - .final_mass_kg - .propellant_kg - 50 | fabs) < 1e-6'
  # the flyby is held at its window's end by an active bound with a multiplier > 0
  assert_jq "$sol" '[.bounds[] | select(.active) | .name] == ["psi_ast_8648_5"] and all(.bounds[] | select(.active); .multiplier > 0)'
}

@test "events: S09's arrival-speed bound is violated free, then active with a positive multiplier" {
  converged_and_verified "$BATS_FILE_TMPDIR/S09"
  local d=$BATS_FILE_TMPDIR/S09/derivation.json sol=$BATS_FILE_TMPDIR/S09/solution.json
  assert_jq "$d" '.shooting.variables | length == 40'
  assert_jq "$d" '.shooting.equations[] | select(.name == "psi_arrival_4") | .inequality.multiplier == "nu_arrival_4"'
  # with the bound, lambda_v(tf) = 2 nu (v - v_T): the velocity rows are transversality equations
  assert_jq "$d" '.shooting.equations[] | select(.name == "transversality_vx") | .expression | test("nu_arrival_4")'
  assert_jq "$sol" '.passes == 2'
  assert_jq "$sol" '.bounds[] | select(.name == "psi_arrival_4") | .first_pass_value > 0 and .active and .multiplier > 0 and (.value | fabs) < 1e-12'
}

@test "events: S10's swing-by passes below Mars free, then its periapsis bound is active with a positive multiplier" {
  converged_and_verified "$BATS_FILE_TMPDIR/S10"
  local d=$BATS_FILE_TMPDIR/S10/derivation.json sol=$BATS_FILE_TMPDIR/S10/solution.json
  assert_jq "$d" '.shooting.variables | length == 20'
  assert_jq "$d" '[.shooting.variables[] | select(.role == "parameter") | .name] == ["delta_mars", "phi_mars"]'
  assert_jq "$d" '.shooting.equations[] | select(.name == "psi_mars_6") | .inequality.multiplier == "nu_mars_6"'
  assert_jq "$sol" '.passes == 2'
  # 2201 days to Jupiter past a swing-by: x moved by round-off moves single shooting's arrival
  # rows by ~1e-10; multiple shooting (a node at Mars and every ~200 days) resolves every row to
  # well below 1e-12, continuity included, and says what x alone gives by single shooting
  assert_jq "$sol" '.max_residual <= 1e-12 and .residual_noise < 1e-12'
  assert_jq "$sol" '.multiple_shooting.single_shooting_max_residual > 1e-11'
  assert_jq "$sol" '[.multiple_shooting.continuity[].value | fabs] | max <= 1e-12'
  assert_jq "$sol" '.multiple_shooting.node_t_days | length == 11 and . == sort and first > 0 and last < 2201'
  assert_jq "$sol" '(.multiple_shooting.nodes | length) == 11 * 14'
  assert_jq "$sol" '.bounds[] | select(.name == "psi_mars_6") | .first_pass_value > 0 and .active and .multiplier > 0 and (.value | fabs) < 1e-10'
  # the passes start from each of pass 1's distinct extremals; the solution is the best place they led to
  assert_jq "$sol" '([.search.extremals[] | select(.with_bounds.converged) | .with_bounds.propellant_kg] | min) as $best | ($best - .propellant_kg | fabs) < 1e-3'
}

@test "events: the problem without its events is searched once, and every attempt continues from its solutions (S10)" {
  local sol=$BATS_FILE_TMPDIR/S10/solution.json
  assert_jq "$sol" '.search.events_off_draws >= 1 and .search.converged_at_eps_start >= 1'
  assert_jq "$sol" '(.search.extremals_at_eps_start | length) >= 1 and (.search.extremals_at_eps_start | all(.continued))'
  # never more draws than the old per-attempt budget
  assert_jq "$sol" '.search.events_off_draws <= (.settings.search_attempts * .settings.leg_attempts)'
  # the returned extremal's record starts with the events-off solve it continued from
  assert_jq "$sol" '.continuation[0].stage == "events off" and .continuation[0].converged'
  assert_jq "$sol" '.search.extremals | length >= 1 and all(.polished)'
}

@test "events: a search at the integrator's own tolerance returns S03's extremal to 1e-9; one and two threads agree" {
  local dir=$BATS_FILE_TMPDIR/S03 run a b
  for run in fine one two; do
    mkdir -p "$dir/$run"
    case $run in
      fine) jq '.search_integrator_tol = 0' "$ROOT/scenarios/S03/settings.json" >"$dir/$run/settings.json" ;;
      one) jq '.threads = 1' "$ROOT/scenarios/S03/settings.json" >"$dir/$run/settings.json" ;;
      two) jq '.threads = 2' "$ROOT/scenarios/S03/settings.json" >"$dir/$run/settings.json" ;;
    esac
    "$BIN/helios-solve" "$dir/shoot.cpp" --settings "$dir/$run/settings.json" --cache-dir "$BATS_FILE_TMPDIR/cache" \
      --trajectory "$dir/$run/trajectory.csv" --plots "" -o "$dir/$run/solution.json" 2>/dev/null
    assert_jq "$dir/$run/solution.json" '.status == "converged" and .max_residual < 1e-10'
  done
  # the default search integrates at 1e-10 and polishes at 1e-13: the same extremal
  a=$(jq '.final_mass_kg' "$dir/solution.json")
  b=$(jq '.final_mass_kg' "$dir/fine/solution.json")
  awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-9 * b) }'
  # the events-off draws run in parallel and are merged in order: the thread count changes nothing
  assert_jq "$dir/two/solution.json" '.search.threads == 2'
  a=$(jq -c '[.x[].value], .search.events_off_draws, [.search.extremals[].objective]' "$dir/two/solution.json")
  b=$(jq -c '[.x[].value], .search.events_off_draws, [.search.extremals[].objective]' "$dir/one/solution.json")
  [[ $a == "$b" ]] || { echo "two threads: $a" >&2; echo "one thread: $b" >&2; false; }
}

@test "events: multiple shooting is kept only where it lowers max|F|, and node_spacing_days 0 turns it off (S09)" {
  local dir=$BATS_FILE_TMPDIR/S09 single
  # S09's nodes lowered max|F|: every row of the record, continuity included, within max_residual
  assert_jq "$dir/solution.json" '.multiple_shooting.single_shooting_max_residual > .max_residual'
  assert_jq "$dir/solution.json" '([.residuals[].value | fabs] + [.multiple_shooting.continuity[].value | fabs] | max) == .max_residual'
  mkdir -p "$dir/single"
  jq '.node_spacing_days = 0' "$ROOT/scenarios/S09/settings.json" >"$dir/single/settings.json"
  "$BIN/helios-solve" "$dir/shoot.cpp" --settings "$dir/single/settings.json" --cache-dir "$BATS_FILE_TMPDIR/cache" \
    --trajectory "$dir/single/trajectory.csv" --plots "" -o "$dir/single/solution.json" 2>/dev/null
  assert_jq "$dir/single/solution.json" '.status == "converged" and (has("multiple_shooting") | not)'
  single=$(jq '.final_mass_kg' "$dir/single/solution.json")
  assert_jq "$dir/solution.json" "(.final_mass_kg - $single) | fabs <= 1e-9 * $single"
  # the trajectory is one curve: no time repeats inside an arc (the nodes add no sample)
  [[ $(cut -d, -f1 "$dir/trajectory.csv" | sort | uniq -d | wc -l) -eq $(cut -d, -f1 "$dir/single/trajectory.csv" | sort | uniq -d | wc -l) ]]
}

@test "events: S10's periapsis multiplier is the sensitivity of the final mass to the bound; the flyby epoch is stationary" {
  local fd claim first curvature
  # a shift of 1e-3: the rows of the 2201-day legs carry integration noise near 1e-11
  read -r fd claim < <(sensitivity S10 psi mars 6 1e-3)
  echo "finite difference $fd, nu/lambda0 $claim"
  awk -v a="$fd" -v b="$claim" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(d <= 1e-5 * m) }'
  read -r first curvature < <(sensitivity S10 epoch mars)
  echo "|m(t+h) - m(t-h)| = $first, |m(t+h) + m(t-h) - 2 m(t)| = $curvature"
  awk -v a="$first" -v b="$curvature" 'BEGIN { exit !(a <= 0.01 * b) }'
}

@test "events: H is constant on every arc of S03, S04, S07, S08, S09 and S10 (it may jump only at events)" {
  local s
  for s in S03 S04 S07 S08 S09 S10; do
    assert_jq "$BATS_FILE_TMPDIR/$s/solution.json" '.hamiltonian_drift < 1e-9'
  done
}

@test "events: each flyby multiplier is the sensitivity of the optimal final mass to its constraint (S04)" {
  local k fd claim
  for k in 1 2 3; do
    read -r fd claim < <(sensitivity S04 psi ast_9482 "$k")
    echo "row $k: finite difference $fd, nu/lambda0 $claim"
    awk -v a="$fd" -v b="$claim" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(d <= 1e-6 * m + 1e-9) }'
  done
}

@test "events: a rendezvous multiplier is the sensitivity of the optimal final mass (S03, Nikko's velocity row)" {
  local fd claim
  read -r fd claim < <(sensitivity S03 psi nikko 4)
  echo "finite difference $fd, nu/lambda0 $claim"
  awk -v a="$fd" -v b="$claim" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(d <= 1e-6 * m + 1e-9) }'
}

@test "events: the final mass is stationary in every free event epoch (the H-jump conditions, S03 and S04)" {
  local s event first curvature
  for s in "S03 nikko" "S03 ast_8648" "S03 tengstrom" "S04 ast_9482"; do
    read -r first curvature < <(sensitivity ${s% *} epoch "${s#* }")
    echo "$s: |m(t+h) - m(t-h)| = $first, |m(t+h) + m(t-h) - 2 m(t)| = $curvature"
    awk -v a="$first" -v b="$curvature" 'BEGIN { exit !(a <= 0.01 * b) }'
  done
}

@test "events: each converged run's trajectory.oem passes the independent OEM parser (S03, S04, S07, S08, S09, S10)" {
  local s
  for s in S03 S04 S07 S08 S09 S10; do assert_oem_of_run "$BATS_FILE_TMPDIR/$s"; done
}

#!/usr/bin/env bats
# A solar-electric engine (issue 48): "The spacecraft is solar-electric: its arrays give P at 1 AU, ..."
# parses, derives with T(r) = 2 eta P_in(r)/(g0 Isp) and its dT/dr in the costates, verifies, and
# solves S15 (S01 flown by it) from a cold start with the default settings; the thrust the trajectory
# burns at the arrival is the power law's; in the 1-AU limit (the cap binding throughout) the engine is
# S01's constant one and the final mass S01's. A thruster given by fits to its input power flies the
# same way.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/work"
  mkdir -p "$WORK"
}

setup() {
  common_setup
}

# last_burn TRAJECTORY: "DAY R_AU FLOW_KG_S" of the last two samples at full throttle: the day, the
# distance from the Sun at their mid-point and the mass flow between them.
last_burn() {
  awk -F, -v AU=149597870.691 '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { t[NR] = $1; m[NR] = $col["m_kg"]; u[NR] = $col["u"]; x[NR] = $col["rx_km"]; y[NR] = $col["ry_km"]; z[NR] = $col["rz_km"]; n = NR }
    END {
      for (k = n; k > 2 && !(u[k] == 1 && u[k - 1] == 1 && t[k] > t[k - 1]); k--) ;
      if (k <= 2) { print "no burn in the trajectory" > "/dev/stderr"; exit 1 }
      r = sqrt(((x[k] + x[k - 1]) / 2) ^ 2 + ((y[k] + y[k - 1]) / 2) ^ 2 + ((z[k] + z[k - 1]) / 2) ^ 2) / AU
      printf "%.17g %.17g %.17g\n", t[k], r, -(m[k] - m[k - 1]) / ((t[k] - t[k - 1]) * 86400)
    }' "$1"
}

@test "sep: S15 converges cold with default settings, verified, its arrival thrust the power law's, its mass consistent" {
  mkdir -p "$WORK/s15"
  cp "$ROOT/scenarios/S15/problem.txt" "$WORK/s15/"
  run_chain "$WORK/s15/problem.txt" "" "$WORK/s15"
  local dir="$WORK/s15" sol="$WORK/s15/solution.json"
  assert_jq "$dir/verify.json" '.verdict == "pass"'
  assert_jq "$dir/spec.json" '.spacecraft | has("thrust_N") | not'
  assert_jq "$dir/derivation.json" '[.terms[].name] == ["two_body", "solar_electric_thrust", "fuel"]'
  assert_jq "$dir/derivation.json" '[.parameters[] | select(.role == "thrust_scale") | .name] == ["P0", "Pbus", "Pmax", "Pw"]'
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .epsilon == 0 and .max_residual < 1e-10'
  # the minimum-time route needs only that the throttle burns mass, not a constant flow: it runs,
  # and its path from the minimum time (shorter than the stated flight) arrives at the returned extremal
  assert_jq "$sol" '[.search.routes[] | select(.name == "minimum-time route")][0].ran'
  assert_jq "$sol" '.search.minimum_time_route.paths | length > 0 and all(.minimum_tf_days < 348.795) and any(.extremal == 0)'
  assert_jq "$sol" '.search.returned == 0'
  # the mass: the propellant is what the mass lost, and the trajectory ends at the final mass
  assert_jq "$sol" '(.initial_mass_kg - .final_mass_kg - .propellant_kg) | fabs < 1e-9'
  local m_end
  m_end=$(tail -1 "$dir/trajectory.csv" | cut -d, -f8)
  within "$m_end" "$(jq '.final_mass_kg' "$sol")" 1e-9
  # the thrust the last burn's samples burn: -dm/dt g0 Isp, against 2 eta P_in(r)/(g0 Isp) at their
  # mid-point (P_in the smooth floor of width 5 W and cap of width 100 W, as derived; the hard minimum
  # differs by 1e-4 here)
  local burn
  burn=$(last_burn "$dir/trajectory.csv")
  awk -v burn="$burn" '
    BEGIN {
      split(burn, b, " ")
      c = 9.80665 * 2000
      measured = b[3] * c; r = b[2]
      pa = 20000 / (r * r) - 500; pmax = 10000; w = 100; f = 5
      pin = (sqrt(pa * pa + f * f) + sqrt(pmax * pmax + w * w) - sqrt((pa - pmax) ^ 2 + w * w)) / 2
      hard = pa < pmax ? pa : pmax
      want = 2 * 0.6 * pin / c
      printf "day %.3f r %.6f AU: measured %.9g N, power law %.9g N (hard minimum %.9g N)\n", b[1], r, measured, want, 2 * 0.6 * hard / c
      d = measured - want; if (d < 0) d = -d
      exit !(d < 1e-5 * want)
    }' >"$dir/thrust.txt" || { cat "$dir/thrust.txt" >&2; return 1; }
  cat "$dir/thrust.txt"
}

@test "sep: in the 1-AU limit (the cap always binding at S01's thrust) the final mass is S01's" {
  mkdir -p "$WORK/limit" "$WORK/s01"
  cp "$S01/problem.txt" "$WORK/s01/"
  sed 's/^The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.$/The spacecraft is solar-electric: its arrays give 1000 MW at 1 AU, the engine takes at most 9806.65 W with an efficiency of 0.5 and a specific impulse of 2000 s.\nThe spacecraft has an initial mass of 1000 kg./' \
    "$S01/problem.txt" >"$WORK/limit/problem.txt"
  grep -q 'solar-electric' "$WORK/limit/problem.txt"
  run_chain "$WORK/s01/problem.txt" "" "$WORK/s01"
  run_chain "$WORK/limit/problem.txt" "" "$WORK/limit"
  assert_jq "$WORK/limit/verify.json" '.verdict == "pass"'
  assert_jq "$WORK/limit/solution.json" '.status == "converged" and .epsilon == 0 and .max_residual < 1e-10'
  echo "S01 $(jq '.final_mass_kg' "$WORK/s01/solution.json") kg, SEP limit $(jq '.final_mass_kg' "$WORK/limit/solution.json") kg"
  # the smooth cap is Pw^2/(4 (Pa - Pmax)) < 1e-6 of Pmax below it: the same extremal to 1e-6
  within "$(jq '.final_mass_kg' "$WORK/limit/solution.json")" "$(jq '.final_mass_kg' "$WORK/s01/solution.json")" 1e-6
}

# A spiral out from 1 AU to a circular 1.5 AU orbit in minimum time with 1.5 kW arrays (2.9
# revolutions about the Sun): the thrust route runs on the engine's powers (their role thrust_scale)
# and arrives at the problem's thrust; the delta-v is at least Edelbaum's circle-to-circle |v1 - v2|
# (5465.6 m/s: the low-thrust limit) and near it, and the propellant is the rocket equation's at the
# engine's constant exhaust velocity.
@test "sep: a minimum-time spiral to 1.5 AU: the thrust route runs on the powers, delta-v at Edelbaum's" {
  mkdir -p "$WORK/spiral"
  cat >"$WORK/spiral/problem.txt" <<'EOF'
Problem SEPSPIRAL: a solar-electric spiral from 1 AU to 1.5 AU in minimum time.
The central body is the Sun with gravitational parameter 1.32712440018e11 km^3/s^2.
The spacecraft is solar-electric: its arrays give 1.5 kW at 1 AU, an efficiency of 0.6 and a specific impulse of 3000 s.
The spacecraft has an initial mass of 1000 kg.
The spacecraft departs at t = 0 days from position [149597870.7, 0, 0] km with velocity [0, 29.784691831696804, 0] km/s.
At the final time the spacecraft is on the circular equatorial orbit of radius 224396806 km.
The time of flight is free, at most 3000 days.
Minimize the time of flight.
EOF
  run_chain "$WORK/spiral/problem.txt" "" "$WORK/spiral"
  local sol="$WORK/spiral/solution.json"
  assert_jq "$WORK/spiral/verify.json" '.verdict == "pass"'
  assert_jq "$sol" '.status == "converged" and .start == "cold" and .max_residual < 1e-10 and .search.saturated'
  assert_jq "$sol" '.search.routes[] | select(.name == "thrust continuation") | .ran'
  assert_jq "$sol" '.search.thrust_continuation.arrived'
  echo "tof $(jq '.tof_days' "$sol") d, delta-v $(jq '.delta_v_m_s' "$sol") m/s, propellant $(jq '.propellant_kg' "$sol") kg"
  assert_jq "$sol" '.delta_v_m_s > 5465.59 and .delta_v_m_s < 1.02 * 5465.59'
  within "$(jq '.propellant_kg' "$sol")" "$(jq '1000 * (1 - ((-.delta_v_m_s / (9.80665 * 3000)) | exp))' "$sol")" 1e-6
}

# A thruster given by fits of its thrust and mass flow to its input power (NSTAR, NEXT): linear fits
# equal to S15's engine (T = 2 eta P/(g0 Isp), F = T/(g0 Isp)) fly S15's extremal, its input power
# and gradient kept as the derivation's intermediates.
@test "sep: fits equal to S15's engine give S15's final mass, with the power kept as an intermediate" {
  mkdir -p "$WORK/fits" "$WORK/s15"
  sed -e "s/, the engine takes at most 10 kW with an efficiency of 0.6 and a specific impulse of 2000 s\./.\nThe thruster's thrust is 61.1829727786757 P mN and its mass flow is 3.1194634650301425 P mg\/s, with P its input power in kW up to 10 kW./" \
    "$ROOT/scenarios/S15/problem.txt" >"$WORK/fits/problem.txt"
  grep -q 'thruster' "$WORK/fits/problem.txt"
  [[ -f $WORK/s15/solution.json ]] || { cp "$ROOT/scenarios/S15/problem.txt" "$WORK/s15/" && run_chain "$WORK/s15/problem.txt" "" "$WORK/s15"; }
  run_chain "$WORK/fits/problem.txt" "" "$WORK/fits"
  assert_jq "$WORK/fits/verify.json" '.verdict == "pass"'
  assert_jq "$WORK/fits/derivation.json" '[.terms[].name] == ["two_body", "solar_electric_fitted_thrust", "fuel"] and [.intermediates[].name] == ["P_in", "T_P", "F_P", "dP_in_drx", "dP_in_dry", "dP_in_drz"]'
  assert_jq "$WORK/fits/solution.json" '.status == "converged" and .start == "cold" and .epsilon == 0 and .max_residual < 1e-10'
  echo "S15 $(jq '.final_mass_kg' "$WORK/s15/solution.json") kg, its engine as fits $(jq '.final_mass_kg' "$WORK/fits/solution.json") kg"
  within "$(jq '.final_mass_kg' "$WORK/fits/solution.json")" "$(jq '.final_mass_kg' "$WORK/s15/solution.json")" 1e-10
}

# An NSTAR-like thruster (a quadratic thrust and a cubic mass flow in P, 0.5 to 2.6 kW) on S01's
# transfer with 5 kW arrays: converged cold and verified; the mass flow a burn's samples burn is the
# fit's at the input power of their distance (smooth cap and step as derived).
@test "sep: an NSTAR-like thruster given by fits converges cold, its burn's mass flow the fit's" {
  mkdir -p "$WORK/nstar"
  sed -e "s/^The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.\$/The spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW.\nThe thruster's thrust is -1.9137 + 36.242 P - 0.5 P^2 mN and its mass flow is 0.47556 + 0.90209 P + 0.01 P^3 mg\/s for an input power P between 0.5 and 2.6 kW.\nThe spacecraft has an initial mass of 150 kg./" \
    "$S01/problem.txt" >"$WORK/nstar/problem.txt"
  grep -q 'thruster' "$WORK/nstar/problem.txt"
  run_chain "$WORK/nstar/problem.txt" "" "$WORK/nstar"
  local dir="$WORK/nstar"
  assert_jq "$dir/verify.json" '.verdict == "pass"'
  assert_jq "$dir/solution.json" '.status == "converged" and .start == "cold" and .epsilon == 0 and .max_residual < 1e-10 and .search.saturated'
  local burn
  burn=$(last_burn "$dir/trajectory.csv")
  awk -v burn="$burn" '
    BEGIN {
      split(burn, b, " ")
      measured = b[3] * 1e6; r = b[2]
      pa = 5000 / (r * r) - 300; pmax = 2600; w = 26; f = 3
      p = (sqrt(pa * pa + f * f) + sqrt(pmax * pmax + w * w) - sqrt((pa - pmax) ^ 2 + w * w)) / 2 / 1000
      on = 1 / (1 + exp(-(p * 1000 - 500) / 5))
      want = on * (0.47556 + 0.90209 * p + 0.01 * p ^ 3)
      printf "day %.3f r %.6f AU, input power %.6g kW: measured %.9g mg/s, the fit %.9g mg/s\n", b[1], r, p, measured, want
      d = measured - want; if (d < 0) d = -d
      exit !(d < 1e-5 * want)
    }' >"$dir/flow.txt" || { cat "$dir/flow.txt" >&2; return 1; }
  cat "$dir/flow.txt"
}

# The same thruster given by a table of its fits' values (8 rows, 0.5 to 2.6 kW): the derivation fits
# the table (least squares, the lowest degree that reproduces it), and the transfer costs what the
# fits' transfer above costs.
@test "sep: a thruster given by its table flies as its fits do" {
  [[ -s $WORK/nstar/solution.json ]] || skip "runs after the NSTAR-like fits' test of this file"
  mkdir -p "$WORK/table"
  local table="The thruster's table gives its thrust and mass flow at these input powers:\n| input power [kW] | thrust [mN] | mass flow [mg\/s] |\n|---|---|---|"
  local p
  for p in 0.5 0.8 1.1 1.4 1.7 2.0 2.3 2.6; do
    table+=$(awk -v p="$p" 'BEGIN { printf "\\n| %s | %.6f | %.6f |", p, -1.9137 + 36.242 * p - 0.5 * p * p, 0.47556 + 0.90209 * p + 0.01 * p ^ 3 }')
  done
  sed -e "s/^The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.\$/The spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW.\n$table\nThe spacecraft has an initial mass of 150 kg./" \
    "$S01/problem.txt" >"$WORK/table/problem.txt"
  grep -q '^| 2.6 | 88.935500 | 2.996754 |$' "$WORK/table/problem.txt"
  run_chain "$WORK/table/problem.txt" "" "$WORK/table"
  local dir="$WORK/table"
  assert_jq "$dir/spec.json" '.spacecraft.thruster_table | length == 8 and .[0].input_power_W == 500'
  assert_jq "$dir/derivation.json" '.parameters[] | select(.name == "T0") | .meaning | test("least squares over the thruster table.s 8 rows: the thrust of degree 2, .* the mass flow of degree 3")'
  assert_jq "$dir/verify.json" '.verdict == "pass"'
  assert_jq "$dir/solution.json" '.status == "converged" and .start == "cold" and .epsilon == 0 and .max_residual < 1e-10 and .search.saturated'
  within "$(jq '.final_mass_kg' "$dir/solution.json")" "$(jq '.final_mass_kg' "$WORK/nstar/solution.json")" 1e-9
}

@test "sep: a wrong sentence is refused in one line naming the field and the value" {
  mkdir -p bad
  sed 's/an efficiency of 0.6/an efficiency of 1.6/' "$ROOT/scenarios/S15/problem.txt" >bad/problem.txt
  run --separate-stderr "$BIN/helios-parse" bad/problem.txt -o bad/spec.json
  [ "$status" -ne 0 ]
  [[ $stderr == *"efficiency must be in (0, 1]"*"1.6"* ]]
  [[ $(printf '%s\n' "$stderr" | wc -l) -eq 1 ]]
  [[ ! -e bad/spec.json ]]
}

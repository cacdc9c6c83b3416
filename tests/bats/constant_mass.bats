#!/usr/bin/env bats
# An engine of constant mass (issue 48): "The spacecraft's mass is constant at Q." derives without a
# mass state and solves with default settings, end to end.
#   - control-toolbox's planar minimum-time orbit transfer (CTProblems.jl, "Orbital transfert - time
#     minimisation", src/problems/orbital_transfert_time.jl: 100 N on 2000 kg, mu = 5.1658620912e12
#     km^3/h^2, x0 = [-42272.67 km, 0, 0, -5796.72 km/h], the circular orbit of radius 42165 km):
#     its published shooting solution tf = 13.403181957149329 h, to 1e-9 relative;
#   - S14's GTO to GEO made planar (the out-of-plane velocity zeroed) at a constant 1500 kg: its
#     minimum time against the same problem solved with a variable mass and Isp = 1e13 s (the
#     constant mass in the limit; 15.226404686181887 h, the mass then falls by 2e-11, which moves
#     the time by 6.5e-12), to 1e-9 relative;
#   - its minimum fuel at 1.5 t_min: converged at eps = 0, the propellant in kg where an Isp is
#     given, cheaper than the minimum time followed by a coast; and the delta-v in m/s without one.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
  export WORK="$BATS_FILE_TMPDIR/work"
  mkdir -p "$WORK"
}

setup() {
  common_setup
}

# gto DIR ENGINE TIME OBJECTIVE: S14 made planar at a constant mass of 1500 kg.
gto() {
  mkdir -p "$1"
  cat >"$1/problem.txt" <<EOF
Problem GTOCM: planar GTO to GEO at constant mass.
The central body is the Earth with gravitational parameter 398600.47 km^3/s^2.
$2
The spacecraft's mass is constant at 1500 kg.
The spacecraft departs at t = 0 days from position [-46500, 0, 0] km with velocity [0, -1.4529784332509441, 0] km/s.
At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.
$3
$4
EOF
}

@test "constant mass: control-toolbox's planar minimum-time transfer, 13.403181957149329 h to 1e-9" {
  mkdir -p "$WORK/ct"
  cat >"$WORK/ct/problem.txt" <<'EOF'
Problem CT: control-toolbox's planar orbit transfer in minimum time at constant mass.
The central body is the Earth with gravitational parameter 398600.47 km^3/s^2.
The spacecraft has a maximum thrust of 100 N.
The spacecraft's mass is constant at 2000 kg.
The spacecraft departs at t = 0 days from position [-42272.67, 0, 0] km with velocity [0, -1.6102, 0] km/s.
At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km.
The time of flight is free, at most 1 day.
Minimize the time of flight.
EOF
  run_chain "$WORK/ct/problem.txt" "" "$WORK/ct"
  local sol="$WORK/ct/solution.json"
  assert_jq "$WORK/ct/verify.json" '.verdict == "pass"'
  assert_jq "$WORK/ct/derivation.json" '[.states[].name] == ["rx", "ry", "rz", "vx", "vy", "vz"]'
  assert_jq "$sol" '.status == "converged" and .epsilon == 0 and .max_residual < 1e-10'
  within "$(jq '.tof_hours' "$sol")" 13.403181957149329 1e-9
  # no Isp: no propellant, the delta-v is the acceleration times the flight, 0.05 m/s^2 * tf
  assert_jq "$sol" 'has("propellant_kg") | not'
  within "$(jq '.delta_v_m_s' "$sol")" "$(jq '0.05 * .tof_hours * 3600' "$sol")" 1e-9
}

@test "constant mass: planar GTO to GEO at 60 N, its minimum time the Isp = 1e13 s limit to 1e-9" {
  gto "$WORK/time" "The spacecraft has a maximum thrust of 60 N and a specific impulse of 1994.7500254 s." \
    "The time of flight is free, at most 2 days." "Minimize the time of flight."
  run_chain "$WORK/time/problem.txt" "" "$WORK/time"
  local sol="$WORK/time/solution.json"
  assert_jq "$WORK/time/verify.json" '.verdict == "pass"'
  assert_jq "$sol" '.status == "converged" and .max_residual < 1e-10'
  within "$(jq '.tof_hours' "$sol")" 15.226404686181887 1e-9
  # the mass throughout, and the propellant the engine at that Isp would burn
  assert_jq "$sol" '.initial_mass_kg == 1500 and .final_mass_kg == 1500'
  within "$(jq '.propellant_kg' "$sol")" "$(jq '60 / (1994.7500254 * 9.80665) * .tof_hours * 3600' "$sol")" 1e-9
  # the companion priced the throttle by the L1 rate: it ran, nothing turned off silently
  assert_jq "$sol" '.search.routes[] | select(.name == "minimum-fuel companion") | .ran'
  jq '.tof_days' "$sol" >"$WORK/t_min_days"
  # at full throttle throughout (constant_mass_full_thrust): the same transfer, nothing to price
  gto "$WORK/full" "The spacecraft has a maximum thrust of 60 N and a specific impulse of 1994.7500254 s." \
    "The time of flight is free, at most 2 days." $'The engine thrusts at full throttle throughout.\nMinimize the time of flight.'
  run_chain "$WORK/full/problem.txt" "" "$WORK/full"
  assert_jq "$WORK/full/derivation.json" '[.terms[].name] == ["two_body", "constant_mass_full_thrust", "time"]'
  within "$(jq '.tof_hours' "$WORK/full/solution.json")" "$(jq '.tof_hours' "$sol")" 1e-9
  within "$(jq '.propellant_kg' "$WORK/full/solution.json")" "$(jq '.propellant_kg' "$sol")" 1e-9
}

@test "constant mass: minimum fuel at 1.5 t_min converges and beats the minimum time with a coast" {
  [[ -s $WORK/t_min_days ]] || skip "needs the minimum time of the test before"
  local tof
  tof=$(jq -n "1.5 * $(cat "$WORK/t_min_days")")
  gto "$WORK/fuel" "The spacecraft has a maximum thrust of 60 N and a specific impulse of 1994.7500254 s." \
    "The time of flight is $tof days." "Minimize the fuel consumption."
  run_chain "$WORK/fuel/problem.txt" "" "$WORK/fuel"
  local sol="$WORK/fuel/solution.json"
  assert_jq "$WORK/fuel/verify.json" '.verdict == "pass"'
  assert_jq "$WORK/fuel/derivation.json" '[.terms[].name] == ["two_body", "constant_mass_thrust", "fuel"]'
  assert_jq "$sol" '.status == "converged" and .epsilon == 0 and .max_residual < 1e-10'
  # the minimum time (full thrust) and a coast costs 168.13 kg; the bang-bang transfer less
  assert_jq "$sol" '.search.minimum_time_and_coast.propellant_kg > 168 and .search.minimum_time_and_coast.propellant_kg < 168.2'
  assert_jq "$sol" '.propellant_kg > 0 and .propellant_kg < .search.minimum_time_and_coast.propellant_kg'
  assert_jq "$sol" '(.switches | length) >= 2'
  # without an Isp the same extremal, its cost the delta-v in m/s
  gto "$WORK/dv" "The spacecraft has a maximum thrust of 60 N." "The time of flight is $tof days." \
    "Minimize the fuel consumption."
  run_chain "$WORK/dv/problem.txt" "" "$WORK/dv"
  local dv="$WORK/dv/solution.json"
  assert_jq "$WORK/dv/derivation.json" '[.terms[].name] == ["two_body", "constant_mass_thrust", "delta_v"]'
  assert_jq "$dv" '.status == "converged" and (has("propellant_kg") | not)'
  within "$(jq '.delta_v_m_s' "$dv")" "$(jq '.delta_v_m_s' "$sol")" 1e-7
}

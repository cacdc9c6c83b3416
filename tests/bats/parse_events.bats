#!/usr/bin/env bats
# helios-parse: bodies given by elements, a free departure epoch and events on the way
# (tests/fixtures/parse/*.txt, variants made with sed).

load test_helper

FIXTURES="$ROOT/tests/fixtures/parse"

setup() {
  common_setup
  require_tool parse
}

# write_tour FILE SED_EXPR...: the tour fixture with sed expressions applied.
write_tour() {
  local file="$1"
  shift
  local args=()
  local e
  for e in "$@"; do args+=(-e "$e"); done
  sed "${args[@]}" "$FIXTURES/tour.txt" >"$file"
}

# line_of FILE TEXT: the line number of TEXT's first occurrence (to check error locations).
line_of() {
  grep -n -F -- "$2" "$1" | head -1 | cut -d: -f1
}

@test "parse_events: the tour fixture parses into a spec with orbits, a free departure and three events" {
  run -0 --separate-stderr "$BIN/helios-parse" "$FIXTURES/tour.txt" -o spec.json
  [[ -z $output && -z $stderr ]]
  assert_jq spec.json '[.constraints[] | [.id, .kind, .at]] == [["departure", "initial_state", "t0"],
    ["nikko", "rendezvous", "interior"], ["rock_1423", "flyby", "interior"], ["mars", "gravity_assist", "interior"],
    ["arrival", "rendezvous", "tf"]]'
  assert_jq spec.json '.time == {"t0_days": 0, "epoch_mjd2000": 10336.6, "departure": "free",
    "t0_window_days": [-30, 30], "final_time": "fixed", "tof_days": 981.1}'
  assert_jq spec.json '.constraints[0].target | .kind == "orbit" and .body == "Azusa"'
  assert_jq spec.json '.constraints[1] | .window_days == [200, 320] and .stay_days == 30 and .mass_drop_kg == 50'
  # Nikko's row: epoch MJD 56800 = MJD2000 5256.
  assert_jq spec.json '.constraints[1].target.elements == {"epoch_mjd2000": 5256, "a_AU": 2.2375176,
    "e": 0.1052183, "i_deg": 5.70117, "raan_deg": 71.94548, "argp_deg": 2.08462, "mean_anomaly_deg": 287.3844555}'
  assert_jq spec.json '.constraints[2] | .window_days == [400, 500] and (has("stay_days") | not)'
  assert_jq spec.json '.constraints[3] | .target == {"kind": "body", "body": "Mars", "ephemeris": "jpl_lp"}
    and .body_mu_km3_s2 == 42828.3 and .min_periapsis_radius_km == 3889.9'
  # SIMBAD: i = 0.2 rad in degrees, a true anomaly.
  assert_jq spec.json '.constraints[4].target.elements | ((.i_deg - 11.459155902616466) | fabs < 1e-12)
    and .true_anomaly_deg == 90 and (has("mean_anomaly_deg") | not)'
  assert_no_temp_files .
}

@test "parse_events: a final rendezvous with a body given by elements" {
  run -0 --separate-stderr "$BIN/helios-parse" "$FIXTURES/final-orbit.txt" -o spec.json
  assert_jq spec.json '.constraints | length == 2'
  assert_jq spec.json '.constraints[0].target == {"kind": "body", "body": "Earth", "ephemeris": "jpl_lp"}'
  assert_jq spec.json '.constraints[1] | .id == "arrival" and .at == "tf" and .target.kind == "orbit"
    and .target.body == "SIMBAD" and .target.elements.epoch_mjd2000 == 5256'
  assert_jq spec.json '.time | .epoch_mjd2000 == 10336.6 and (has("departure") | not)'
}

@test "parse_events: the windows may be given as MJD2000 dates" {
  write_tour dates.txt 's/between day 200 and day 320/between MJD2000 10536.6 and MJD2000 10656.6/'
  grep -q 'MJD2000 10656.6 and stays' dates.txt
  "$BIN/helios-parse" dates.txt -o spec.json
  assert_jq spec.json '.constraints[1].window_days | ((.[0] - 200) | fabs < 1e-9) and ((.[1] - 320) | fabs < 1e-9)'
}

@test "parse_events: a body visited twice gets the id suffix _2" {
  write_tour twice.txt 's/^The spacecraft flies by Rock_1423 between day 400 and day 500\.$/The spacecraft flies by Nikko between day 400 and day 500./' \
    '/^| Rock_1423/d'
  run -0 --separate-stderr "$BIN/helios-parse" twice.txt -o spec.json
  assert_jq spec.json '[.constraints[].id] == ["departure", "nikko", "nikko_2", "mars", "arrival"]'
}

@test "parse_events: an unknown body -> exit 3 naming the sentence, its line and the body" {
  write_tour unknown.txt 's/flies by Rock_1423/flies by Ceres/'
  mkdir out
  run -3 --separate-stderr "$BIN/helios-parse" unknown.txt -o out/spec.json
  assert_one_error_line parse
  assert_stderr_contains "unknown.txt:$(line_of unknown.txt 'flies by Ceres'): cannot use sentence \"The spacecraft flies by Ceres" \
    "unknown body 'Ceres'"
  assert_dir_empty out
}

@test "parse_events: a name that is not an identifier -> exit 3" {
  write_tour badname.txt 's/Rock_1423/Rock-1423/g'
  run -3 --separate-stderr "$BIN/helios-parse" badname.txt
  assert_one_error_line parse
  assert_stderr_contains "badname.txt:$(line_of badname.txt '| Rock-1423'): cannot use table row" \
    "'Rock-1423' is not a body name"
}

@test "parse_events: overlapping windows -> exit 3 naming both events" {
  write_tour overlap.txt 's/between day 400 and day 500/between day 300 and day 500/'
  run -3 --separate-stderr "$BIN/helios-parse" overlap.txt
  assert_one_error_line parse
  assert_stderr_contains "overlap.txt:$(line_of overlap.txt 'flies by Rock_1423'):" \
    "starts before the window of the event at Nikko (day 200 to day 320) ends"
}

@test "parse_events: events stated out of order -> exit 3" {
  write_tour order.txt 's/between day 400 and day 500/between day 100 and day 150/'
  run -3 --separate-stderr "$BIN/helios-parse" order.txt
  assert_one_error_line parse
  assert_stderr_contains "state the events in the order they happen"
}

@test "parse_events: elements without their epoch -> exit 3" {
  write_tour noepoch.txt 's/ at MJD2000 10336\.6\.$/./'
  grep -q 'mean anomaly = 10 deg\.$' noepoch.txt
  run -3 --separate-stderr "$BIN/helios-parse" noepoch.txt
  assert_one_error_line parse
  assert_stderr_contains "noepoch.txt:$(line_of noepoch.txt 'Azusa moves'):" "the elements of Azusa need their epoch"
}

@test "parse_events: bodies on the way without a calendar epoch -> exit 3" {
  sed -e 's/^The spacecraft departs at MJD2000 10336\.6 from Earth\.$/The spacecraft departs at t = 0 days from Earth./' \
    "$FIXTURES/final-orbit.txt" >noepoch.txt
  grep -q 't = 0 days' noepoch.txt
  run -3 --separate-stderr "$BIN/helios-parse" noepoch.txt
  assert_one_error_line parse
  assert_stderr_contains "needs a calendar epoch"
}

@test "parse_events: wrong units -> exit 3 naming the unit" {
  write_tour angle.txt 's/i = 3\.5 deg/i = 3.5 kg/'
  run -3 --separate-stderr "$BIN/helios-parse" angle.txt
  assert_one_error_line parse
  assert_stderr_contains "unit 'kg' is not an angle unit (use deg, rad)"
  write_tour stay.txt 's/stays there for 30 days/stays there for 30 km/'
  run -3 --separate-stderr "$BIN/helios-parse" stay.txt
  assert_one_error_line parse
  assert_stderr_contains "unit 'km' is not a time unit"
}

@test "parse_events: a table header with a column it does not know -> exit 3 quoting the header" {
  write_tour header.txt 's/^| body | a \[AU\] | e | i \[deg\]/| body | a [AU] | ecc | i [deg]/'
  grep -q '^| body | a \[AU\] | ecc' header.txt
  run -3 --separate-stderr "$BIN/helios-parse" header.txt
  assert_one_error_line parse
  assert_stderr_contains "cannot use table row \"| body | a [AU] | ecc" "column 3 is 'ecc'"
}

@test "parse_events: a flyby with a stay -> exit 3" {
  write_tour flyby.txt 's/between day 400 and day 500\./between day 400 and day 500 and stays there for 3 days./'
  run -3 --separate-stderr "$BIN/helios-parse" flyby.txt
  assert_one_error_line parse
  assert_stderr_contains "a flyby matches the position only"
}

@test "parse_events: a free departure with a free time of flight -> exit 3" {
  write_tour free.txt 's/^The total time of flight is 981\.1 days\.$/The time of flight is free, between 500 days and 1000 days./'
  run -3 --separate-stderr "$BIN/helios-parse" free.txt
  assert_one_error_line parse
  assert_stderr_contains "a free departure epoch needs a fixed total time of flight"
}

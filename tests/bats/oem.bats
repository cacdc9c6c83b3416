#!/usr/bin/env bats
# helios-score --oem: a converged run's trajectory.csv -> trajectory.oem (CCSDS OEM 2.0, KVN),
# checked by an independent parser (oem_check.awk, not the C++ writer's code) against the CSV.
#
# The fixture (tests/fixtures/oem) is S08's spec, its solution trimmed to what the schema needs,
# and 17 of its trajectory's samples: a stay with a lander at Nikko, a flyby of Ast_8648 (a repeated
# time) and a stay at Tengstrom, so four segments. Nothing is solved here: the OEMs of real converged
# runs are checked by the same parser where those runs are made: the OEM make writes for T01
# (pipeline.bats), and those of events.bats and dynamics.bats (assert_oem_of_run, test_helper.bash).

load test_helper

FIXTURES="$ROOT/tests/fixtures/oem"
CHECK="$ROOT/tests/bats/oem_check.awk"

setup() {
  common_setup
  require_tool score
}

# oem [ARGS...]: the fixture's OEM, plus ARGS.
oem() {
  "$BIN/helios-score" --oem --spec "$FIXTURES/spec.json" --solution "$FIXTURES/solution.json" \
    --trajectory "$FIXTURES/trajectory.csv" "$@"
}

# oem_refused SPEC CSV: helios-score --oem on SPEC, the fixture's solution and CSV must refuse
# (exit 3, one error line) and write nothing into out/.
oem_refused() {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --oem --spec "$1" --solution "$FIXTURES/solution.json" \
    --trajectory "$2" -o out/x.oem
  assert_one_error_line score
  assert_dir_empty out
}

# check_oem CSV OEM EPOCH_MJD2000: the independent parser accepts OEM and it matches CSV.
check_oem() {
  awk -v epoch0="$3" -f "$CHECK" "$1" "$2"
}

@test "oem: the fixture's OEM passes the independent parser and matches trajectory.csv to 1e-9" {
  oem -o out.oem
  run check_oem "$FIXTURES/trajectory.csv" out.oem "$(jq -r .time.epoch_mjd2000 "$FIXTURES/spec.json")"
  [[ $status -eq 0 ]] || { echo "$output" >&2; false; }
  [[ $output == "segments 4 data_lines 17" ]] || { echo "$output" >&2; false; }
  assert_no_temp_files .
}

@test "oem: header and metadata say the frame, centre, TDB and the epoch of t = 0" {
  oem -o out.oem
  [[ $(head -1 out.oem) == "CCSDS_OEM_VERS = 2.0" ]]
  [[ $(grep -c '^REF_FRAME = ECLIPJ2000$' out.oem) -eq 4 ]]
  [[ $(grep -c '^CENTER_NAME = SUN$' out.oem) -eq 4 ]]
  [[ $(grep -c '^TIME_SYSTEM = TDB$' out.oem) -eq 4 ]]
  grep -q '^COMMENT Epochs: t = 0 of the problem is MJD2000 10313.6 = 2028-03-27T14:24:00.000000 TDB$' out.oem
  grep -q '^START_TIME = 2028-03-27T14:24:00.000000$' out.oem
  # The calendar day by GNU date from the MJD's own origin, 1858-11-17 (MJD2000 = MJD - 51544):
  # MJD2000 10313.6 is MJD 61857.6, 0.6 d = 14:24.
  [[ $(date -u -d "1858-11-17 00:00:00 UTC + $((10313 + 51544)) days" +%F) == 2028-03-27 ]]
  grep -q '^COMMENT Segment 2 of 4: from event nikko (rendezvous, stay of 30 d, lander of 50 kg left) to event ast_8648 (flyby)$' out.oem
  grep -q '^COMMENT Mass 1867.760280 kg at START_TIME, 1790.449315 kg at STOP_TIME$' out.oem
  grep -q '^COMMENT Throttle 0 from ' out.oem
}

@test "oem: the same inputs give the same bytes, from any folder" {
  oem -o a.oem
  mkdir elsewhere && cp "$FIXTURES"/* elsewhere/
  "$BIN/helios-score" --oem --spec elsewhere/spec.json --solution elsewhere/solution.json \
    --trajectory elsewhere/trajectory.csv -o b.oem
  cmp a.oem b.oem
  oem | cmp - a.oem
}

@test "oem: a problem without an epoch gets the default epoch J2000.0 and a COMMENT" {
  jq 'del(.time.epoch_mjd2000)' "$FIXTURES/spec.json" >spec.json
  "$BIN/helios-score" --oem --spec spec.json --solution "$FIXTURES/solution.json" \
    --trajectory "$FIXTURES/trajectory.csv" -o out.oem
  grep -q '^START_TIME = 2000-01-01T12:00:00.000000$' out.oem
  grep -q '^COMMENT The problem states no calendar epoch' out.oem
  run check_oem "$FIXTURES/trajectory.csv" out.oem 0.5
  [[ $status -eq 0 ]] || { echo "$output" >&2; false; }
}

@test "oem: a solution that did not converge writes nothing, removes a stale OEM, exit 0" {
  jq '.status = "not_converged"' "$FIXTURES/solution.json" >solution.json
  echo stale >out.oem
  run -0 --separate-stderr "$BIN/helios-score" --oem --spec "$FIXTURES/spec.json" --solution solution.json \
    --trajectory no-such.csv -o out.oem
  [[ ! -e out.oem ]]
  assert_stderr_contains "not_converged" "no OEM written"
}

@test "oem: a malformed trajectory.csv -> exit 3 naming file, line and field, nothing written" {
  sed '5s/^\([^,]*\),[^,]*,/\1,abc,/' "$FIXTURES/trajectory.csv" >bad.csv
  oem_refused "$FIXTURES/spec.json" bad.csv
  assert_stderr_contains "bad.csv:5: field rx_km: 'abc' is not a finite number"
}

@test "oem: a trajectory whose events do not match the spec's -> exit 3 naming the file" {
  sed '/^454,/d' "$FIXTURES/trajectory.csv" >noflyby.csv
  oem_refused "$FIXTURES/spec.json" noflyby.csv
  assert_stderr_contains "noflyby.csv" "field t_days" "interior events"
}

@test "oem: a central body without a known frame -> exit 3 naming the spec and /central_body/name" {
  jq '.central_body.name = "Mars" | .central_body.mu_km3_s2 = 42828.37' "$FIXTURES/spec.json" >spec.json
  oem_refused spec.json "$FIXTURES/trajectory.csv"
  assert_stderr_contains "spec.json: field /central_body/name"
}

@test "oem: a missing trajectory file -> exit 3 naming it" {
  oem_refused "$FIXTURES/spec.json" no-such.csv
  assert_stderr_contains "no-such.csv"
}

@test "oem: usage errors -> exit 2 (--oem without --trajectory, --trajectory without --oem, --oem with --reference)" {
  run -2 --separate-stderr "$BIN/helios-score" --oem --spec "$FIXTURES/spec.json" --solution "$FIXTURES/solution.json"
  assert_one_error_line score
  assert_stderr_contains "--trajectory"
  run -2 --separate-stderr "$BIN/helios-score" --reference "$S01/reference.json" --trajectory "$FIXTURES/trajectory.csv"
  assert_one_error_line score
  run -2 --separate-stderr "$BIN/helios-score" --oem --reference "$S01/reference.json" --spec "$FIXTURES/spec.json" \
    --solution "$FIXTURES/solution.json" --trajectory "$FIXTURES/trajectory.csv"
  assert_one_error_line score
}

@test "oem: the independent parser rejects what breaks the grammar or the CSV" {
  oem -o good.oem
  local csv="$FIXTURES/trajectory.csv" e=10313.6 line
  line=$(grep -n -m1 '^2028-' good.oem | cut -d: -f1)
  sed "${line}s/e+08/e+07/" good.oem >value.oem                 # a position off by a factor 10
  sed "${line}s/ [^ ]*\$//" good.oem >fields.oem                # a data line of 6 fields
  sed "${line}a COMMENT late" good.oem >comment.oem             # a COMMENT between data lines
  sed "${line}a FOO = 1" good.oem >keyword.oem                  # a KEY = value line among the data
  sed 's/^TIME_SYSTEM = TDB$/TIME_SYSTEM = UTC/' good.oem >utc.oem
  sed '0,/^META_STOP$/{/^META_STOP$/d}' good.oem >nostop.oem
  sed '1s/2\.0/1.0/' good.oem >version.oem
  awk -v n="$line" 'NR == n + 1 { held = $0; next } { print } NR == n + 2 { print held }' good.oem >order.oem
  for bad in value fields comment keyword utc nostop version order; do
    run check_oem "$csv" "$bad.oem" "$e"
    [[ $status -ne 0 ]] || { echo "the parser accepted $bad.oem" >&2; false; }
  done
}

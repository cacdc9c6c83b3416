#!/usr/bin/env bats
# helios-verify: derivation.json -> verify.json
#   helios-verify DERIVATION.json -o verify.json   exit 0 (pass) | 4 (fail, verify.json still written)
#   --advisory                                     a failing verdict exits 0

load test_helper

setup() {
  common_setup
  require_tool parse derive verify
}

# flip_l_rx IN OUT: the derivation with the sign of the l_rx costate equation flipped.
flip_l_rx() {
  jq -e '.costate_odes[0].costate == "l_rx"' "$1" >/dev/null
  jq '.costate_odes[0].rhs |= "-(" + . + ")"' "$1" >"$2"
}

# ---- shared contract -------------------------------------------------------------------------

@test "verify: no arguments -> exit 2, one error line" {
  contract_no_args verify
}

@test "verify: unknown option -> exit 2" {
  s01_derivation
  contract_bad_option verify derivation.json
}

@test "verify: missing input file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-verify" no-such-derivation.json -o out/verify.json
  assert_one_error_line verify
  assert_stderr_contains "no-such-derivation.json"
  assert_dir_empty out
}

@test "verify: --help ends with an e.g. line" {
  contract_help verify
}

@test "verify: --version" {
  contract_version verify
}

@test "verify: malformed JSON -> exit 3, nothing written" {
  printf '{"schema": "helios/derivation", "hamiltonian": ' >broken.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-verify" broken.json -o out/verify.json
  assert_one_error_line verify
  assert_stderr_contains "broken.json"
  assert_dir_empty out
}

@test "verify: schema violation (derivation without hamiltonian) -> exit 3 naming the field" {
  s01_derivation
  jq 'del(.hamiltonian)' derivation.json >bad.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-verify" bad.json -o out/verify.json
  assert_one_error_line verify
  assert_stderr_contains "bad.json" "hamiltonian"
  assert_dir_empty out
}

@test "verify: schema violation (non-positive variable scale) -> exit 3 naming the field path" {
  s01_derivation
  jq '.shooting.variables[0].scale = 0' derivation.json >bad.json
  run -3 --separate-stderr "$BIN/helios-verify" bad.json
  assert_one_error_line verify
  assert_stderr_contains "scale"
  [[ $stderr == *"/shooting/variables/0/scale"* ]]
}

@test "verify: wrong artifact kind (a spec) -> exit 3" {
  s01_spec
  mkdir out
  run -3 --separate-stderr "$BIN/helios-verify" spec.json -o out/verify.json
  assert_one_error_line verify
  assert_stderr_contains "helios/spec" "helios/derivation"
  assert_dir_empty out
}

@test "verify: a bad --points value -> exit 2" {
  s01_derivation
  run -2 --separate-stderr "$BIN/helios-verify" --points 0 derivation.json
  assert_one_error_line verify
}

# ---- verdicts ----------------------------------------------------------------------------------

@test "verify: the S01 derivation passes" {
  s01_derivation
  run -0 --separate-stderr "$BIN/helios-verify" derivation.json -o verify.json
  [[ -z $output && -z $stderr ]]
  assert_jq verify.json '.schema == "helios/verify"'
  assert_jq verify.json '.verdict == "pass"'
  assert_jq verify.json '.checks | length > 0'
  assert_jq verify.json '.checks | all(.verdict == "pass")'
  assert_jq verify.json '.checks | all(has("id") and has("verdict") and has("feedback"))'
  assert_jq verify.json '[.checks[].id] | any(test("l_rx"))'
  assert_no_temp_files .
}

@test "verify: reads the derivation from stdin with -" {
  s01_derivation
  run -0 --separate-stderr bash -c '"$BIN/helios-verify" - <derivation.json'
  jq -e '.verdict == "pass"' <<<"$output"
}

@test "verify: the l_rx costate equation with its sign flipped fails with exit 4" {
  s01_derivation
  flip_l_rx derivation.json flipped.json
  run -4 --separate-stderr "$BIN/helios-verify" flipped.json -o verify.json
  assert_one_error_line verify
  # verify.json is written even though the verdict fails.
  assert_jq verify.json '.verdict == "fail"'
  assert_jq verify.json '[.checks[] | select(.verdict == "fail") | .id] | any(test("l_rx"))'
  # Only the flipped equation fails, and its feedback says something.
  assert_jq verify.json '[.checks[] | select(.verdict == "fail")] | all(.id | test("l_rx"))'
  assert_jq verify.json '.checks[] | select(.verdict == "fail") | .feedback | length > 0'
  assert_no_temp_files .
}

@test "verify: --advisory makes the failing verdict exit 0" {
  s01_derivation
  flip_l_rx derivation.json flipped.json
  run -0 --separate-stderr "$BIN/helios-verify" --advisory flipped.json -o verify.json
  assert_jq verify.json '.verdict == "fail"'
  assert_jq verify.json '[.checks[] | select(.verdict == "fail") | .id] | any(test("l_rx"))'
}

@test "verify: a failing verdict to stdout still exits 4 and prints the report" {
  s01_derivation
  flip_l_rx derivation.json flipped.json
  run -4 --separate-stderr "$BIN/helios-verify" flipped.json
  jq -e '.verdict == "fail"' <<<"$output"
}

@test "verify: output is deterministic for a fixed seed" {
  s01_derivation
  "$BIN/helios-verify" derivation.json -o a.json
  "$BIN/helios-verify" derivation.json -o b.json
  cmp a.json b.json
}

# ---- issue 4: sail, free final time, corpus ------------------------------------------------

# s11_derivation: the builtin derivation of the solar-sail scenario (free tf) -> derivation.json
s11_derivation() {
  "$BIN/helios-parse" "$ROOT/scenarios/S11/problem.txt" -o spec.json
  "$BIN/helios-derive" spec.json -o derivation.json
}

@test "verify: the S11 sail derivation (free tf, no mass) passes, sail and free-tf checks included" {
  s11_derivation
  run -0 --separate-stderr "$BIN/helios-verify" derivation.json -o verify.json
  assert_jq verify.json '.verdict == "pass"'
  assert_jq verify.json '[.checks[].id] | contains(["control_sail", "control_sail_cone_angle", "transversality_tf"])'
  assert_jq verify.json '[.checks[].id] | any(. == "costate_ode:l_m") | not'
}

@test "verify: a sail law with the other root of dH/dalpha = 0 fails with exit 4 naming control_law.sail" {
  s11_derivation
  jq '(.control_law.sail.definitions[] | select(.name == "sail_alpha") | .expression) =
      "atan((3*sail_A-sqrt(8*sail_B^2+9*sail_A^2))/(4*sail_B))"' derivation.json >wrong.json
  run -4 --separate-stderr "$BIN/helios-verify" wrong.json -o verify.json
  assert_one_error_line verify
  assert_stderr_contains "control_sail"
  assert_jq verify.json '[.checks[] | select(.verdict == "fail") | .id] == ["control_sail"]'
  assert_jq verify.json '.feedback | test("control_law.sail.law does not minimize H")'
}

# A corpus case is its base with its JSON Patch applied (build/bin/json-patch), if it has one.
@test "verify: every corpus case gets its expected verdict and failing checks" {
  local corpus="$ROOT/tests/verify-corpus" n=0 name base want patch file got
  [[ -x $BIN/json-patch ]] || { echo "missing $BIN/json-patch: run 'make unit' (builds the test tools) first" >&2; return 1; }
  while IFS=$'\t' read -r name base want patch; do
    file="$corpus/$base"
    if [[ -n $patch ]]; then
      "$BIN/json-patch" "$file" "$corpus/$patch" >case.json
      file=case.json
    fi
    "$BIN/helios-verify" --advisory "$file" -o out.json
    got=$(jq -r '[.verdict, ([.checks[] | select(.verdict == "fail") | .id] | sort | join(","))] | join(" ")' out.json)
    [[ $got == "$want" ]] || { echo "$name: got '$got', expected '$want'" >&2; return 1; }
    n=$((n + 1))
  done < <(jq -r '.cases[] | [.name, .base, .verdict + " " + (.fails | join(",")), .patch // ""] | @tsv' \
    "$corpus/manifest.json")
  ((n >= 40))
}

# ---- interior events and a sliding departure -------------------------------------------------

@test "verify: a flyby and a sliding departure pass; H(t0) = 0 alone fails naming transversality_t0" {
  "$BIN/helios-derive" "$ROOT/tests/verify-corpus/base/E-slide.spec.json" -o derivation.json
  run -0 --separate-stderr "$BIN/helios-verify" derivation.json -o verify.json
  assert_jq verify.json '[.checks[].id] | contains(["event_time:rock", "costate_jump:rock_rx", "transversality_t0"])'
  jq '(.shooting.equations[] | select(.name == "transversality_t0") | .expression) = "H_t0"' derivation.json >h0.json
  run -4 --separate-stderr "$BIN/helios-verify" h0.json -o verify.json
  assert_jq verify.json '[.checks[] | select(.verdict == "fail") | .id] == ["transversality_t0"]'
  assert_jq verify.json '.feedback | test("departure body.s motion is missing") and test("coupling with tf is missing")'
}

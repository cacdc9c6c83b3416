#!/usr/bin/env bats
# helios-derive: spec.json -> derivation.json

load test_helper

setup() {
  common_setup
  require_tool parse derive
}

# ---- shared contract -------------------------------------------------------------------------

@test "derive: no arguments -> exit 2, one error line" {
  contract_no_args derive
}

@test "derive: unknown option -> exit 2" {
  s01_spec
  contract_bad_option derive spec.json
}

@test "derive: --backend other than builtin -> exit 2" {
  s01_spec
  run -2 --separate-stderr "$BIN/helios-derive" --backend nope spec.json
  assert_one_error_line derive
}

@test "derive: missing input file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-derive" no-such-spec.json -o out/derivation.json
  assert_one_error_line derive
  assert_stderr_contains "no-such-spec.json"
  assert_dir_empty out
}

@test "derive: --help ends with an e.g. line" {
  contract_help derive
}

@test "derive: --version" {
  contract_version derive
}

@test "derive: malformed JSON -> exit 3, nothing written" {
  printf '{"schema": "helios/spec",' >broken.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-derive" broken.json -o out/derivation.json
  assert_one_error_line derive
  assert_stderr_contains "broken.json" "malformed JSON"
  assert_dir_empty out
}

@test "derive: empty input -> exit 3" {
  : >empty.json
  run -3 --separate-stderr "$BIN/helios-derive" empty.json
  assert_one_error_line derive
  assert_stderr_contains "empty.json"
}

@test "derive: schema violation (thrust_N = -1) -> exit 3 naming the field path" {
  s01_spec
  jq '.spacecraft.thrust_N = -1' spec.json >bad-spec.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-derive" bad-spec.json -o out/derivation.json
  assert_one_error_line derive
  assert_stderr_contains "bad-spec.json" "schema violation"
  # The path may be written as a JSON pointer or as valijson's [a][b] context.
  [[ $stderr == *"/spacecraft/thrust_N"* ]]
  assert_dir_empty out
}

@test "derive: schema violation (missing isp_s) -> exit 3 naming the field" {
  s01_spec
  jq 'del(.spacecraft.isp_s)' spec.json >bad-spec.json
  run -3 --separate-stderr "$BIN/helios-derive" bad-spec.json -o derivation.json
  assert_one_error_line derive
  assert_stderr_contains "isp_s" "spacecraft"
  [[ ! -e derivation.json ]]
  assert_no_temp_files .
}

@test "derive: schema violation (unknown field) -> exit 3 naming it" {
  s01_spec
  jq '.spacecraft.colour = "blue"' spec.json >bad-spec.json
  run -3 --separate-stderr "$BIN/helios-derive" bad-spec.json
  assert_one_error_line derive
  assert_stderr_contains "spacecraft"
}

@test "derive: schema violation inside a oneOf (position with 2 components) -> names position_km" {
  s01_spec
  jq '.constraints[1].target.position_km = [1, 2]' spec.json >bad-spec.json
  run -3 --separate-stderr "$BIN/helios-derive" bad-spec.json
  assert_one_error_line derive
  assert_stderr_contains "position_km"
}

@test "derive: wrong artifact kind (a derivation, a reference) -> exit 3" {
  s01_derivation
  run -3 --separate-stderr "$BIN/helios-derive" derivation.json -o out.json
  assert_one_error_line derive
  assert_stderr_contains "helios/derivation" "helios/spec"
  run -3 --separate-stderr "$BIN/helios-derive" "$S01/reference.json" -o out.json
  assert_one_error_line derive
  [[ ! -e out.json ]]
  assert_no_temp_files .
}

# ---- S01 ---------------------------------------------------------------------------------------

@test "derive: S01 has 8 shooting variables and 8 equations" {
  s01_spec
  run -0 --separate-stderr "$BIN/helios-derive" spec.json -o derivation.json
  [[ -z $output && -z $stderr ]]
  assert_jq derivation.json '.schema == "helios/derivation" and .schema_version == 1'
  assert_jq derivation.json '.problem.id == "S01"'
  assert_jq derivation.json '.shooting.variables | length == 8'
  assert_jq derivation.json '.shooting.equations | length == 8'
  assert_jq derivation.json '[.shooting.variables[].name] | index("lambda0") != null'
  assert_jq derivation.json '.shooting.equations | any(.expression == "l_m_tf")'
  assert_jq derivation.json '.hamiltonian | length > 0'
  assert_jq derivation.json '[.costate_odes[].costate] == ["l_rx","l_ry","l_rz","l_vx","l_vy","l_vz","l_m"]'
  assert_jq derivation.json '.shooting.variables | all(.scale > 0)'
  assert_no_temp_files .
}

@test "derive: output is byte-identical across runs" {
  s01_spec
  "$BIN/helios-derive" spec.json -o first.json
  "$BIN/helios-derive" spec.json -o second.json
  cmp first.json second.json
  "$BIN/helios-derive" spec.json >third.json
  cmp first.json third.json
}

@test "derive: helios-parse | helios-derive - works" {
  s01_derivation
  run -0 --separate-stderr bash -c '"$BIN/helios-parse" "$S01/problem.txt" | "$BIN/helios-derive" - -o piped.json'
  assert_jq piped.json '.shooting.variables | length == 8'
  # Same derivation as from the file, whatever the input was called.
  cmp derivation.json piped.json
}

#!/usr/bin/env bats
# helios-score: a run's artifacts + reference.json -> score.json; a folder of runs -> scoreboard.md
#
# setup_file runs the S01 chain once (one ~5 s compile) into $BATS_FILE_TMPDIR/run.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve score
  export RUN="$BATS_FILE_TMPDIR/run"
  mkdir -p "$RUN"
  s01_verify "$RUN"
  s01_shoot "$RUN"
  s01_solve "$RUN" "$BATS_FILE_TMPDIR/cache"
}

setup() {
  common_setup
  require_tool score
  REF="$S01/reference.json"
}

# score_full [ARGS...]: score the setup_file run with every stage, plus ARGS.
score_full() {
  "$BIN/helios-score" --reference "$REF" --spec "$RUN/spec.json" --derivation "$RUN/derivation.json" \
    --verify "$RUN/verify.json" --solution "$RUN/solution.json" "$@"
}

# ---- shared contract -------------------------------------------------------------------------

@test "score: no arguments -> exit 2, one error line" {
  contract_no_args score
}

@test "score: unknown option -> exit 2" {
  contract_bad_option score --reference "$REF"
}

@test "score: missing --reference -> exit 2" {
  mkdir out
  run -2 --separate-stderr "$BIN/helios-score" --spec "$RUN/spec.json" --solution "$RUN/solution.json" -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "--reference"
  assert_dir_empty out
}

@test "score: a positional argument -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-score" --reference "$REF" "$RUN/spec.json"
  assert_one_error_line score
}

@test "score: --scoreboard with a stage option -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-score" --scoreboard "$BATS_TEST_TMPDIR" --reference "$REF"
  assert_one_error_line score
}

@test "score: missing reference file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --reference no-such-reference.json --spec "$RUN/spec.json" -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "no-such-reference.json"
  assert_dir_empty out
}

@test "score: missing stage file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --reference "$REF" --spec "$RUN/spec.json" \
    --solution no-such-solution.json -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "no-such-solution.json"
  assert_dir_empty out
}

@test "score: --help ends with an e.g. line" {
  contract_help score
}

@test "score: --version" {
  contract_version score
}

@test "score: malformed --reference JSON -> exit 3, nothing written" {
  printf '{"schema": "helios/reference", ' >ref.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --reference ref.json --spec "$RUN/spec.json" -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "ref.json" "malformed JSON"
  assert_dir_empty out
}

@test "score: malformed --spec JSON -> exit 3, nothing written" {
  printf '{"schema": "helios/spec"' >spec.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --reference "$REF" --spec spec.json -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "spec.json" "malformed JSON"
  assert_dir_empty out
}

@test "score: spec schema violation (thrust_N = -1) -> exit 3 naming the field path" {
  jq '.spacecraft.thrust_N = -1' "$RUN/spec.json" >spec.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-score" --reference "$REF" --spec spec.json -o out/score.json
  assert_one_error_line score
  assert_stderr_contains "spec.json"
  [[ $stderr == *"/spacecraft/thrust_N"* ]]
  assert_dir_empty out
}

@test "score: reference without its result -> exit 3 naming /result" {
  jq 'del(.result)' "$REF" >ref.json
  run -3 --separate-stderr "$BIN/helios-score" --reference ref.json --spec "$RUN/spec.json"
  assert_one_error_line score
  assert_stderr_contains "ref.json" "/result"
}

@test "score: derivation schema violation (no hamiltonian) -> exit 3" {
  jq 'del(.hamiltonian)' "$RUN/derivation.json" >derivation.json
  run -3 --separate-stderr "$BIN/helios-score" --reference "$REF" --derivation derivation.json
  assert_one_error_line score
  assert_stderr_contains "hamiltonian"
}

@test "score: wrong artifact kind (a spec as --solution, a spec as --reference) -> exit 3" {
  run -3 --separate-stderr "$BIN/helios-score" --reference "$REF" --solution "$RUN/spec.json" -o score.json
  assert_one_error_line score
  assert_stderr_contains "helios/spec" "helios/solution"
  run -3 --separate-stderr "$BIN/helios-score" --reference "$RUN/spec.json" -o score.json
  assert_one_error_line score
  [[ ! -e score.json ]]
  assert_no_temp_files .
}

# ---- scoring -----------------------------------------------------------------------------------

@test "score: the full S01 chain scores 100" {
  run -0 --separate-stderr score_full -o score.json
  [[ -z $output && -z $stderr ]]
  assert_jq score.json '.schema == "helios/score" and .scenario == "S01"'
  assert_jq score.json '.total == 100 and .max_total == 100'
  assert_jq score.json '.dimensions | [.[].points] == [30, 20, 20, 20, 10]'
  assert_jq score.json '.inputs == {"spec": true, "derivation": true, "verify": true, "solution": true}'
  assert_jq score.json '.measured.shooting_variables == 8 and (.measured.error_kg | fabs) <= 0.01'
  assert_no_temp_files .
}

@test "score: omitting --solution scores 0 on d3, d4 and d5" {
  run -0 --separate-stderr "$BIN/helios-score" --reference "$REF" --spec "$RUN/spec.json" \
    --derivation "$RUN/derivation.json" --verify "$RUN/verify.json" -o score.json
  assert_jq score.json '.inputs.solution == false'
  assert_jq score.json '.dimensions.d3_compile.points == 0 and .dimensions.d4_converge.points == 0 and .dimensions.d5_accuracy.points == 0'
  assert_jq score.json '.dimensions.d1_parse.points == 30 and .dimensions.d2_derive.points == 20'
  assert_jq score.json '.total == 50'
  assert_jq score.json '.measured.final_mass_kg == null'
}

@test "score: only a reference scores 0" {
  run -0 --separate-stderr "$BIN/helios-score" --reference "$REF"
  jq -e '.total == 0 and (.inputs | all(. == false))' <<<"$output"
}

@test "score: a failed verification costs d2 points" {
  jq '.costate_odes[0].rhs |= "-(" + . + ")"' "$RUN/derivation.json" >derivation.json
  "$BIN/helios-verify" --advisory derivation.json -o verify.json
  run -0 --separate-stderr "$BIN/helios-score" --reference "$REF" --spec "$RUN/spec.json" \
    --derivation derivation.json --verify verify.json -o score.json
  assert_jq score.json '.dimensions.d2_derive.points < 20'
}

@test "score: reads the reference from stdin with -" {
  run -0 --separate-stderr bash -c '"$BIN/helios-score" --reference - --spec "$RUN/spec.json" <"$S01/reference.json"'
  jq -e '.dimensions.d1_parse.points == 30' <<<"$output"
}

@test "score: the scoreboard is Markdown with an S01 row" {
  mkdir -p runs/S01
  score_full -o runs/S01/score.json
  run -0 --separate-stderr "$BIN/helios-score" --scoreboard runs -o scoreboard.md
  grep -q '^|' scoreboard.md
  grep -q '^| S01 |' scoreboard.md
  grep -q '| 100 |' scoreboard.md
  assert_no_temp_files .
}

@test "score: --scoreboard of a missing folder -> exit 3 naming it" {
  run -3 --separate-stderr "$BIN/helios-score" --scoreboard no-such-runs -o scoreboard.md
  assert_one_error_line score
  assert_stderr_contains "no-such-runs"
  [[ ! -e scoreboard.md ]]
}

#!/usr/bin/env bats
# The hostile-input corpus (tests/hostile): every case gives its documented exit code and one
# clean error line, with no signal, no hang and no file outside its output.

load test_helper

setup() {
  common_setup
  require_tool parse derive verify gen solve score
}

@test "hostile corpus: every case is refused cleanly, as documented" {
  run tests_hostile
  echo "$output" | tail -n 12
  [ "$status" -eq 0 ]
  [[ $output == *"hostile corpus: "*" cases, 0 failed"* ]]
  local cases=${output##*hostile corpus: }
  [ "${cases%% cases*}" -ge 200 ]
}

tests_hostile() { "$ROOT/tests/hostile/run.sh" "$BIN" "$BATS_TEST_TMPDIR/hostile"; }

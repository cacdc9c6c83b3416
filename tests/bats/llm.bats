#!/usr/bin/env bats
# The llm backend against a scripted fake OpenAI-compatible server (build/bin/fake-llm).
#
# setup_file runs S01 twice through make into a private runs tree ($BATS_FILE_TMPDIR/runs, via
# RUNS_ROOT): once with the builtin backend, once with BACKEND=llm and a scripted model whose
# first derivation has a sign error in the l_rx costate equation and whose first program defines
# functions twice. runs/ of the repository is never touched. The tests then read those runs; the
# others call the tools directly, each with its own script.

load test_helper
load llm_helper

BATS_NO_PARALLELIZE_WITHIN_FILE=true

setup_file() {
  require_tool parse derive verify gen solve score
  [[ -x $FAKE_LLM ]] || { echo "missing $FAKE_LLM: run 'make unit' (or cmake --build build) first" >&2; return 1; }
  export FX="$BATS_FILE_TMPDIR/fx" RUNS_ROOT="$BATS_FILE_TMPDIR/runs" LLM_CACHE="$BATS_FILE_TMPDIR/cache"
  export RUN="$BATS_FILE_TMPDIR/runs/llm/S01"
  mkdir -p "$FX"
  make_fixtures "$FX"
  cat >"$FX/s01.json" <<'JSON'
{"replies": [
  {"content_file": "spec.txt", "model": "fake-model-1", "usage": {"prompt_tokens": 2100, "completion_tokens": 420}},
  {"content_file": "derive_bad.txt", "model": "fake-model-1", "usage": {"prompt_tokens": 7000, "completion_tokens": 3600}},
  {"content_file": "derive_good.txt", "match": "## Round 2", "model": "fake-model-1", "usage": {"prompt_tokens": 11000, "completion_tokens": 3600}},
  {"content_file": "codegen_dup.txt", "match": "four modules", "model": "fake-model-1", "usage": {"prompt_tokens": 9000, "completion_tokens": 3100}},
  {"content_file": "codegen_good.txt", "match": "does not compile", "model": "fake-model-1", "usage": {"prompt_tokens": 13000, "completion_tokens": 2900}}
]}
JSON
  BATS_TEST_TMPDIR="$BATS_FILE_TMPDIR" llm_env
  export HELIOS_LLM_API_KEY
  BATS_TEST_TMPDIR="$BATS_FILE_TMPDIR" start_fake "$FX/s01.json" "$BATS_FILE_TMPDIR/s01-requests.jsonl"
  local rc=0
  lmake scenario=S01 BACKEND=builtin >"$BATS_FILE_TMPDIR/make-builtin.log" 2>&1 || rc=$?
  lmake scenario=S01 BACKEND=llm >"$BATS_FILE_TMPDIR/make-llm.log" 2>&1 || rc=$?
  stop_fake
  if ((rc != 0)); then
    cat "$BATS_FILE_TMPDIR"/make-*.log >&2
    return 1
  fi
}

teardown_file() {
  stop_fake
}

setup() {
  common_setup
  llm_env
}

teardown() {
  stop_fake
}

# make on the private runs tree, isolated from an enclosing make and from tool rebuilds.
lmake() {
  isolated_make "$RUNS_ROOT" "$LLM_CACHE" "$@"
}

# script FILE JSON: a script for fake-llm whose content_file paths are relative to $FX.
script() {
  echo "$2" >"$FX/$1"
  echo "$FX/$1"
}

# ---- S01 through make --------------------------------------------------------------------------

@test "llm: round 1 fails verification with a sentence naming the l_rx costate equation" {
  assert_jq "$RUN/derivation.r1.json" '.producer.backend == "llm" and .producer.model == "fake-model-1"'
  assert_jq "$RUN/verify.r1.json" '.verdict == "fail" and .summary.failed == 1'
  assert_jq "$RUN/verify.r1.json" '.checks[] | select(.verdict == "fail") | .id == "costate_ode:l_rx"'
  assert_jq "$RUN/verify.r1.json" '.feedback | test("l_rx") and test("sign")'
}

@test "llm: round 2 is asked with the verifier's feedback and passes; round 3 is round 2 unchanged" {
  local sentence
  sentence="$(jq -r '.checks[] | select(.verdict == "fail") | .feedback' "$RUN/verify.r1.json")"
  jq -e --arg s "$sentence" '.turns[0].request.messages[-1].content | contains($s)' "$RUN/derivation.r2.transcript.json"
  assert_jq "$RUN/derivation.r2.transcript.json" '.round == 2 and .purpose == "derive" and .outcome == "accepted"'
  assert_jq "$RUN/verify.r2.json" '.verdict == "pass"'
  cmp "$RUN/derivation.r2.json" "$RUN/derivation.r3.json"
  [[ ! -e $RUN/derivation.r3.transcript.json ]]
  [[ $(readlink "$RUN/derivation.json") == derivation.r3.json ]]
  assert_jq "$RUN/verify.json" '.verdict == "pass"'
}

@test "llm: a duplicate definition is repaired in round 2 from the compiler's message" {
  assert_jq "$RUN/compile.r1.json" '.ok == false and .errors > 0 and (.diagnostics | test("redefinition"))'
  assert_jq "$RUN/shoot.r2.transcript.json" '.purpose == "repair" and .round == 2'
  # The repair request carries the compiler's message.
  jq -e '.turns[0].request.messages[-1].content | test("redefinition")' "$RUN/shoot.r2.transcript.json"
  assert_jq "$RUN/compile.r2.json" '.ok == true and .errors == 0'
  cmp "$RUN/shoot.r2.cpp" "$RUN/shoot.r3.cpp"
  cmp "$RUN/shoot.r2.cpp" "$RUN/shoot.r4.cpp"
  [[ ! -e $RUN/shoot.r3.transcript.json && ! -e $RUN/shoot.r4.transcript.json ]]
  [[ $(readlink "$RUN/shoot.cpp") == shoot.r4.cpp ]]
  # the model's modules are in the program's map like the builtin ones
  assert_file_map "$RUN/shoot.r2.cpp" "module DYNAMICS" "module SWITCH" "module RESIDUAL" "module SOLVE"
}

@test "llm: the solve converges to the builtin m_f and scores 100" {
  local builtin="$RUNS_ROOT/builtin/S01/solution.json"
  assert_jq "$RUN/solution.json" '.status == "converged" and .max_residual < 1e-10 and .producer.backend == "llm"'
  jq -e --slurpfile b "$builtin" '(.final_mass_kg - $b[0].final_mass_kg) | fabs < 1e-6' "$RUN/solution.json"
  assert_jq "$RUN/solution.json" '(.final_mass_kg - 603.94) | fabs < 0.01'
  assert_jq "$RUN/score.json" '.total == 100 and .producer.backend == "llm" and .producer.model == "fake-model-1"'
}

@test "llm: the model's derivation gets the same report.md, verify's verdicts beside its conditions" {
  grep -qF 'Derivation by helios-derive' "$RUN/report.md"
  grep -qF '(llm backend)' "$RUN/report.md"
  grep -qF '> helios-verify: `hamiltonian` pass' "$RUN/report.md"
  grep -qF '## Solution (solution.json)' "$RUN/report.md"
}

@test "llm: transcripts hold token counts, latency and model; no file under runs/ holds the API key" {
  local t n=0
  for t in "$RUN"/*.transcript.json; do
    n=$((n + 1))
    assert_jq "$t" '.schema == "helios/transcript" and .producer.model == "fake-model-1"'
    assert_jq "$t" '.usage.prompt_tokens > 0 and .usage.completion_tokens > 0'
    assert_jq "$t" '.usage.total_tokens == .usage.prompt_tokens + .usage.completion_tokens'
    assert_jq "$t" '[.turns[] | .latency_s >= 0 and .http_status == 200 and (.reply.content | length > 0)] | all'
  done
  ((n == 5)) || { echo "expected 5 transcripts (spec, derivation r1 r2, shoot r1 r2), found $n" >&2; false; }
  # The key went to the server as a header ...
  [[ $(jq -r .authorization "$BATS_FILE_TMPDIR/s01-requests.jsonl" | sort -u) == "Bearer $HELIOS_LLM_API_KEY" ]]
  # ... and nowhere into the runs tree.
  run -1 grep -r -l -F -- "$HELIOS_LLM_API_KEY" "$RUNS_ROOT"
  run -1 grep -r -l -F -- "secret" "$RUNS_ROOT"
}

@test "llm: a second make does nothing" {
  run -0 lmake -q scenario=S01 BACKEND=llm
  run -0 lmake scenario=S01 BACKEND=llm
  [[ $output == *"Nothing to be done"* ]] || { echo "$output" >&2; false; }
}

@test "llm: a prompt edit re-runs the llm rules that send it and no builtin rule" {
  local prompts="$BATS_TEST_TMPDIR/prompts"
  cp -a "$ROOT/prompts" "$prompts"
  run -0 lmake -q scenario=S01 BACKEND=builtin HELIOS_PROMPTS_DIR="$prompts"
  run -0 lmake -q scenario=S01 BACKEND=llm HELIOS_PROMPTS_DIR="$prompts"
  sleep 0.05 # past the file system's timestamp granularity
  touch "$prompts/pmp_derive.txt"
  run -0 lmake -q scenario=S01 BACKEND=builtin HELIOS_PROMPTS_DIR="$prompts"
  run -0 lmake -n scenario=S01 BACKEND=llm HELIOS_PROMPTS_DIR="$prompts"
  [[ $output == *"helios-derive' --backend llm --round 1 "* && $output != *"helios-parse"* ]] || { echo "$output" >&2; false; }
  touch "$prompts/parse.txt"
  run -0 lmake -q scenario=S01 BACKEND=builtin HELIOS_PROMPTS_DIR="$prompts"
  run -0 lmake -n scenario=S01 BACKEND=llm HELIOS_PROMPTS_DIR="$prompts"
  [[ $output == *"helios-parse' --backend llm"* ]] || { echo "$output" >&2; false; }
}

@test "llm: an interrupted run resumes at the first missing round and redoes nothing before it" {
  local copy="$BATS_TEST_TMPDIR/runs"
  mkdir -p "$copy/llm"
  cp -a "$RUN" "$copy/llm/S01"
  # The state of a run stopped while round 2 was asked.
  (cd "$copy/llm/S01" && rm -f derivation.r2* verify.r2.json derivation.r3.json derivation.json verify.json \
    shoot.* compile.* solution.json report.md score.json trajectory.* throttle_mass.png)
  local before
  before="$(cd "$copy/llm/S01" && stat -c '%n %.9Y' spec.json derivation.r1.json verify.r1.json)"
  start_fake "$(script resume.json '{"replies": [
    {"content_file": "derive_good.txt", "match": "## Round 2"},
    {"content_file": "codegen_good.txt", "match": "four modules"}]}')" requests.jsonl
  run -0 isolated_make "$copy" "$LLM_CACHE" scenario=S01 BACKEND=llm
  [[ $output != *"helios-parse"* && $output != *"helios-derive' --backend llm --round 1 "* ]] || { echo "$output" >&2; false; }
  [[ $output == *"helios-derive' --backend llm --round 2"* ]]
  [[ $(cd "$copy/llm/S01" && stat -c '%n %.9Y' spec.json derivation.r1.json verify.r1.json) == "$before" ]]
  [[ $(wc -l <requests.jsonl) -eq 2 ]]
  assert_jq "$copy/llm/S01/score.json" '.total == 100'
}

@test "llm: replay answers from the recorded transcripts byte for byte, without network" {
  local copy="$BATS_TEST_TMPDIR/runs"
  export HELIOS_LLM_REPLAY="$RUNS_ROOT/llm"
  export HELIOS_LLM_BASE_URL="http://127.0.0.1:9/v1"
  unset HELIOS_LLM_MODEL HELIOS_LLM_API_KEY
  run -0 isolated_make "$copy" "$LLM_CACHE" scenario=S01 BACKEND=llm
  local f
  for f in spec.json derivation.r1.json derivation.r2.json derivation.r3.json shoot.r1.cpp shoot.r2.cpp; do
    cmp "$RUN/$f" "$copy/llm/S01/$f"
  done
  assert_jq "$copy/llm/S01/derivation.r2.transcript.json" '.endpoint == "replay" and ([.turns[].replayed] | all)'
  jq -e --slurpfile a "$RUN/derivation.r2.transcript.json" '.usage == $a[0].usage' "$copy/llm/S01/derivation.r2.transcript.json"
  assert_jq "$copy/llm/S01/score.json" '.total == 100'
}

@test "llm: make scoreboard renders the three tables for a runs tree with two backends" {
  run -0 lmake scoreboard BACKEND=llm
  local md="$RUNS_ROOT/scoreboard.md"
  [[ -s $md && -s $RUNS_ROOT/llm/scoreboard.md ]]
  grep -q '^## Table 1: per-scenario comparison' "$md"
  grep -q '^## Table 2: token consumption' "$md"
  grep -q '^## Table 3: effect of the compile-repair loop' "$md"
  grep -q '^| S01 | builtin | 1 | 100.0 | 1/1 | 1/1 |$' "$md"
  grep -q '^| S01 | llm (fake-model-1) | 1 | 100.0 | 1/1 | 1/1 |$' "$md"
  # Tokens: the sums of the transcripts (input 42,100, output 13,620 as scripted).
  grep -q '^| llm (fake-model-1) | 1 | 5 | 42,100 | 13,620 | 55,720 | 55,720 |$' "$md"
  grep -q '^| builtin | 1 | 0 | 0 | 0 | 0 | 0 |$' "$md"
  # The repair loop: the first program did not compile, the repaired one did.
  grep -q '^| llm (fake-model-1) | 1 | 0/1 | 1/1 | 1 | 1 |$' "$md"
  grep -q '^| builtin | 1 | 1/1 | 1/1 | 0 | no loop |$' "$md"
}

@test "llm: VERIFY_MODE=strict stops when the last round still fails; nothing is generated" {
  local copy="$BATS_TEST_TMPDIR/runs"
  start_fake "$(script strict.json '{"replies": [{"content_file": "spec.txt"}, {"content_file": "derive_bad.txt"},
    {"content_file": "derive_bad.txt"}, {"content_file": "derive_bad.txt"}]}')" requests.jsonl
  run -2 isolated_make "$copy" "$LLM_CACHE" scenario=S01 BACKEND=llm VERIFY_MODE=strict
  [[ $output == *"helios-verify: error: verdict fail"* ]] || { echo "$output" >&2; false; }
  ls "$copy/llm/S01"/derivation.r{1,2,3}.transcript.json
  [[ ! -e $copy/llm/S01/verify.json && ! -e $copy/llm/S01/shoot.r1.cpp ]]
  [[ $(wc -l <requests.jsonl) -eq 4 ]]
}

# ---- the client: malformed replies, retries, errors ---------------------------------------------

@test "llm: a reply that is not JSON is fed back and the next reply is used" {
  start_fake "$(script notjson.json '{"replies": [{"content": "I would rather explain it in words."},
    {"content_file": "spec.txt"}]}')" requests.jsonl
  run -0 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_jq spec.json '.producer.backend == "llm" and .problem.id == "S01"'
  assert_jq spec.transcript.json '[.turns[].outcome] == ["rejected", "accepted"]'
  assert_jq spec.transcript.json '.turns[0].error | test("not valid JSON")'
  # The second request repeats the conversation with the error as the last message.
  assert_jq spec.transcript.json '.turns[1].request.messages[-1].content | test("could not be used: your reply is not valid JSON")'
  assert_jq spec.transcript.json '.turns[1].request.messages[-2] == {"role": "assistant", "content": "I would rather explain it in words."}'
}

@test "llm: no usable reply in HELIOS_LLM_MAX_TURNS turns -> exit 3, transcript kept, no artifact" {
  start_fake "$(script never.json '{"replies": [{"content": "no"}, {"content": "{\"problem\": 1}"}]}')" requests.jsonl
  HELIOS_LLM_MAX_TURNS=2 run -3 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "in 2 turns" "spec schema violation" "spec.transcript.json"
  [[ ! -e spec.json ]]
  assert_jq spec.transcript.json '.outcome == "failed" and ([.turns[].outcome] == ["rejected", "rejected"])'
}

@test "llm: HTTP 429 then 200 is retried after a back-off" {
  start_fake "$(script 429.json '{"replies": [{"status": 429, "retry_after": "0"}, {"status": 503},
    {"content_file": "spec.txt"}]}')" requests.jsonl
  run -0 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_jq spec.transcript.json '[.turns[0].attempts[].http_status] == [429, 503, 200]'
  assert_jq spec.transcript.json '.turns[0].attempts[0].error | test("429")'
  assert_jq spec.transcript.json '.turns[0].attempts[1].wait_s > 0'
  assert_jq spec.json '.problem.id == "S01"'
}

@test "llm: a request that times out is retried" {
  start_fake "$(script timeout.json '{"replies": [{"content_file": "spec.txt", "delay_s": 3},
    {"content_file": "spec.txt"}]}')" requests.jsonl
  HELIOS_LLM_TIMEOUT_S=0.5 run -0 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_jq spec.transcript.json '.turns[0].attempts[0].http_status == 0 and (.turns[0].attempts[0].error | test("timed out"))'
  assert_jq spec.transcript.json '.turns[0].attempts[1].http_status == 200'
}

@test "llm: retries are bounded: every attempt timing out -> exit 1 naming the endpoint" {
  start_fake "$(script timeouts.json '{"replies": [{"content": "x", "delay_s": 2}, {"content": "x", "delay_s": 2}]}')" requests.jsonl
  HELIOS_LLM_TIMEOUT_S=0.3 HELIOS_LLM_MAX_RETRIES=1 run -1 --separate-stderr \
    "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "POST $HELIOS_LLM_BASE_URL/chat/completions failed 2 times" "timed out" "HELIOS_LLM_MAX_RETRIES"
  [[ ! -e spec.json ]]
}

@test "llm: HTTP 401 -> exit 1 at once, naming the URL and HELIOS_LLM_API_KEY but not the key" {
  start_fake "$(script 401.json '{"replies": [{"status": 401}, {"content_file": "spec.txt"}]}')" requests.jsonl
  run -1 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "$HELIOS_LLM_BASE_URL/chat/completions returned HTTP 401 (unauthorized)" "HELIOS_LLM_API_KEY"
  [[ $stderr != *"$HELIOS_LLM_API_KEY"* ]]
  [[ $(wc -l <requests.jsonl) -eq 1 ]]
  run -1 grep -r -F --exclude=requests.jsonl -- "$HELIOS_LLM_API_KEY" "$BATS_TEST_TMPDIR"
}

@test "llm: HTTP 404 -> exit 1 naming HELIOS_LLM_BASE_URL" {
  start_fake "$(script 404.json '{"replies": [{"status": 404}]}')" requests.jsonl
  run -1 --separate-stderr "$BIN/helios-derive" --backend llm "$FX/builtin/spec.json" -o derivation.json
  assert_one_error_line derive
  assert_stderr_contains "returned HTTP 404 (not found)" "HELIOS_LLM_BASE_URL" "HELIOS_LLM_MODEL=fake-model"
}

@test "llm: no HELIOS_LLM_BASE_URL -> exit 2 naming the variable; builtin-only options are refused" {
  unset HELIOS_LLM_BASE_URL
  run -2 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "HELIOS_LLM_BASE_URL is not set"
  run -2 --separate-stderr "$BIN/helios-derive" --feedback x.json "$FX/builtin/spec.json"
  assert_stderr_contains "--feedback needs --backend llm"
  run -2 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt"
  assert_stderr_contains "--transcript"
}

@test "llm: a 300 MB reply is refused at the limit while it is read, in bounded memory, once" {
  start_fake "$(script flood.json '{"replies": [{"flood_bytes": 300000000}, {"content_file": "spec.txt"}]}')" requests.jsonl
  # (within a memory budget of 600 MB: reading the whole reply took 1.24 GB)
  run -3 --separate-stderr "$BIN/helios-parse" --backend llm --memory-limit 600 "$S01/problem.txt" -o spec.json
  assert_one_error_line parse
  assert_stderr_contains "POST $HELIOS_LLM_BASE_URL/chat/completions: the reply is larger than the limit of an llm reply (67108864 bytes"
  [[ ! -e spec.json && $(wc -l <requests.jsonl) -eq 1 ]]
  assert_jq spec.transcript.json '.outcome == "failed" and (.turns | length) == 1 and .turns[0].reply == null'
  assert_jq spec.transcript.json '.turns[0].attempts[0].error | test("larger than 67108864 bytes")'
  [[ $(wc -c <spec.transcript.json) -lt 100000 ]]
}

@test "llm: an unusable reply goes back to the model cut to 256 KiB, and into the transcript once" {
  start_fake "$(script long.json '{"replies": [{"content_bytes": 10000000}, {"content_file": "spec.txt"}]}')" requests.jsonl
  run -0 --separate-stderr "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
  assert_jq spec.transcript.json '[.turns[].outcome] == ["rejected", "accepted"]'
  assert_jq spec.transcript.json '.turns[1].request.messages[-2].content | length <= 262144 and
    endswith("[... the rest of this reply is not repeated: 10000000 bytes in all]")'
  # The second request carried the cut reply, not the 10 MB; the transcript holds the reply once.
  [[ $(sed -n 2p requests.jsonl | wc -c) -lt 1000000 ]]
  [[ $(wc -c <spec.transcript.json) -lt 11000000 ]]
}

@test "llm: a numeric variable out of its range is refused in one line naming it" {
  local v
  for v in HELIOS_LLM_MAX_RETRIES=1e10 HELIOS_LLM_MAX_RETRIES=-1 HELIOS_LLM_MAX_TURNS=1000 HELIOS_LLM_TIMEOUT_S=1e300 \
    HELIOS_LLM_BACKOFF_MAX_S=inf; do
    run -2 --separate-stderr env "$v" "$BIN/helios-parse" --backend llm "$S01/problem.txt" -o spec.json
    assert_one_error_line parse
    assert_stderr_contains "$v is not a" "number in [" "], fix or unset it"
  done
  [[ ! -e spec.json && ! -e spec.transcript.json ]]
}

# A model's derivation with intermediates (S15's solar-electric engine keeps its input power P_in and
# the partials dP_in_drx, ... by name): round 1 has a wrong partial, which verify fails by its own
# check and names in the costate row that uses it; round 2, asked with that feedback, passes.
@test "llm: a derivation with intermediates: a wrong partial fails its own check, the next round is asked with it" {
  "$BIN/helios-parse" "$ROOT/scenarios/S15/problem.txt" -o spec.json
  "$BIN/helios-derive" spec.json -o builtin.json
  jq 'del(.schema, .schema_version, .producer, .units, .times, .parameters)' builtin.json >good.json
  jq '(.intermediates[] | select(.name == "dP_in_dry") | .expression) |= "1.01*(" + . + ")"' good.json >bad.json
  fence good.json >"$FX/s15_good.txt"
  fence bad.json >"$FX/s15_bad.txt"
  start_fake "$(script s15.json '{"replies": [{"content_file": "s15_bad.txt"},
    {"content_file": "s15_good.txt", "match": "## Round 2"}]}')" requests.jsonl
  "$BIN/helios-derive" --backend llm --round 1 spec.json -o d1.json
  assert_jq d1.json '[.intermediates[].name] == ["P_in", "dP_in_drx", "dP_in_dry", "dP_in_drz"]'
  "$BIN/helios-verify" --advisory d1.json -o v1.json
  assert_jq v1.json '.verdict == "fail" and ([.checks[] | select(.verdict == "fail") | .id] == ["intermediate:dP_in_dry", "costate_ode:l_ry"])'
  assert_jq v1.json '.checks[] | select(.id == "costate_ode:l_ry") | .feedback | test("It names dP_in_dry, which fails its own check")'
  "$BIN/helios-derive" --backend llm --round 2 --previous d1.json --feedback v1.json spec.json -o d2.json
  jq -e '.turns[0].request.messages[-1].content | test("intermediates\\[dP_in_dry\\]: expected dP_in/dry")' d2.transcript.json
  "$BIN/helios-verify" d2.json -o v2.json
  assert_jq v2.json '.verdict == "pass" and ([.checks[] | select(.category == "intermediates")] | length) == 3'
  jq -e --slurpfile b builtin.json '.intermediates == $b[0].intermediates and .costate_odes == $b[0].costate_odes' d2.json
}

# ---- untrusted code ----------------------------------------------------------------------------

@test "solve: a generated program that never terminates is killed at its limit, reported, and scored" {
  local copy="$BATS_TEST_TMPDIR/runs"
  start_fake "$(script forever.json '{"replies": [{"content_file": "derive_good.txt"},
    {"content_file": "codegen_forever.txt"}]}')" requests.jsonl
  run -0 isolated_make "$copy" "$BATS_TEST_TMPDIR/cache" scenario=S01 BACKEND=llm \
    PARSE_BACKEND=builtin SOLVE_TIME_LIMIT=2
  local sol="$copy/llm/S01/solution.json"
  assert_jq "$sol" '.status == "timeout" and .compile.ok == true'
  # Its children die with the sandbox's PID namespace (no leftover is counted outside it; a run
  # without the sandbox counts and kills them: sandbox_test's AProgramThatExitsButLeavesADaemon).
  assert_jq "$sol" '.status_detail | test("^killed after 2 s wall clock")'
  assert_jq "$sol" '.timings.run_s >= 2 and .timings.run_s < 10'
  assert_jq "$copy/llm/S01/score.json" '.dimensions.d3_compile.points == 20 and .dimensions.d4_converge.points == 0'
  # Nothing it started is still running (it forked children that left its process group).
  run -1 pgrep -f "$BATS_TEST_TMPDIR/cache"
}

# Fixtures and the fake server for the llm backend's Bats tests (tests/bats/llm.bats).
#
# The scripted "model" answers with artifacts of the builtin backend (made at test time), so the
# fixtures follow the tools as they change; the deliberate flaws (a sign error, a duplicate
# definition, a program that never ends) are edits of those.

FAKE_LLM="$BIN/fake-llm"
export FAKE_LLM

# fence FILE: FILE's text inside a ```json fence, as a model would write it.
fence() {
  printf 'Here is the result.\n\n```json\n%s\n```\n' "$(cat "$1")"
}

# make_fixtures DIR: DIR/{spec,derive_bad,derive_good,codegen_good,codegen_dup,codegen_forever}.txt
# (reply contents) from the builtin S01 artifacts.
make_fixtures() {
  local dir="$1" work="$1/builtin"
  mkdir -p "$work"
  "$BIN/helios-parse" "$S01/problem.txt" -o "$work/spec.json"
  "$BIN/helios-derive" "$work/spec.json" -o "$work/derivation.json"
  "$BIN/helios-gen" --modules generated "$work/derivation.json" -o "$work/shoot.cpp"
  jq 'del(.schema, .schema_version, .producer)' "$work/spec.json" >"$work/spec_reply.json"
  jq 'del(.schema, .schema_version, .producer, .units, .times, .parameters)' "$work/derivation.json" \
    >"$work/derive_good.json"
  # The sign error: lambda_rx' = +dH/drx instead of -dH/drx.
  jq '(.costate_odes[] | select(.costate == "l_rx") | .rhs) |= "-(" + . + ")"' "$work/derive_good.json" \
    >"$work/derive_bad.json"
  # The four modules of the builtin program, without their namespace lines and banners.
  awk -v dir="$work" '
    /^\/\/ ----- modules DYNAMICS \+ SWITCH/ { m = "DYNAMICS"; next }
    /^\/\/ ----- module RESIDUAL/ { m = "RESIDUAL"; next }
    /^\/\/ ----- module SOLVE/ { m = "SOLVE"; next }
    /^\/\/ -----------/ { if (m == "SOLVE") m = ""; next }
    /^void direction_control\(/ && m == "DYNAMICS" { m = "SWITCH" }
    /^namespace helios_rt \{$/ || /^\}  \/\/ namespace helios_rt$/ { next }
    m != "" { print > (dir "/" m ".cpp") }
  ' "$work/shoot.cpp"
  local m
  for m in DYNAMICS SWITCH RESIDUAL SOLVE; do [[ -s $work/$m.cpp ]] || { echo "no module $m in the builtin program" >&2; return 1; }; done
  # A duplicate definition: SWITCH's functions pasted into DYNAMICS as well.
  cat "$work/DYNAMICS.cpp" "$work/SWITCH.cpp" >"$work/DYNAMICS_dup.cpp"
  # A program that never ends, and leaves children that left its process group.
  cat >"$work/SOLVE_forever.cpp" <<'CPP'
extern "C" int fork();
extern "C" int setsid();
Result solve_problem(const Settings& settings) {
  (void)settings;
  for (int i = 0; i < 3; ++i)
    if (fork() == 0) {
      setsid();
      break;
    }
  volatile unsigned long spin = 0;
  while (true) ++spin;
}
constexpr ModuleTable kModuleTable = [] {
  ModuleTable t;
  t.throttle_slopes = &throttle_slopes;
  return t;
}();
HELIOS_MODULE_TABLE(kModuleTable);
CPP
  modules_json() {
    jq -n --rawfile d "$work/$1.cpp" --rawfile s "$work/SWITCH.cpp" --rawfile r "$work/RESIDUAL.cpp" \
      --rawfile v "$work/$2.cpp" '{modules: {DYNAMICS: $d, SWITCH: $s, RESIDUAL: $r, SOLVE: $v}}'
  }
  modules_json DYNAMICS SOLVE >"$work/codegen_good.json"
  modules_json DYNAMICS_dup SOLVE >"$work/codegen_dup.json"
  modules_json DYNAMICS SOLVE_forever >"$work/codegen_forever.json"
  local f
  for f in spec_reply derive_good derive_bad codegen_good codegen_dup codegen_forever; do
    fence "$work/$f.json" >"$dir/${f%_reply}.txt"
  done
}

# start_fake SCRIPT LOG: starts fake-llm, exports HELIOS_LLM_BASE_URL; FAKE_PID is its pid.
start_fake() {
  local script="$1" log="$2" portfile
  portfile="$(mktemp -u "$BATS_TEST_TMPDIR/port.XXXXXX")"
  "$FAKE_LLM" --script "$script" --port-file "$portfile" --log "$log" --lifetime 300 >/dev/null 3>&- &
  FAKE_PID=$!
  local i
  for i in $(seq 1 100); do
    [[ -s $portfile ]] && break
    sleep 0.05
  done
  [[ -s $portfile ]] || { echo "fake-llm did not start" >&2; return 1; }
  export HELIOS_LLM_BASE_URL="http://127.0.0.1:$(cat "$portfile")/v1"
}

stop_fake() {
  if [[ -n ${FAKE_PID:-} ]]; then
    kill "$FAKE_PID" 2>/dev/null || true
    wait "$FAKE_PID" 2>/dev/null || true
    FAKE_PID=
  fi
}

# llm_env: the client settings every test uses (fast back-off, a key to look for).
llm_env() {
  export HELIOS_LLM_MODEL=fake-model
  export HELIOS_LLM_API_KEY="sk-helios-test-7f3a9c-secret"
  export HELIOS_LLM_BACKOFF_S=0.01
  export HELIOS_LLM_TIMEOUT_S=20
  unset HELIOS_LLM_REPLAY HELIOS_PROMPTS_DIR
}

#!/usr/bin/env bats
# helios-gen: derivation.json -> shoot.cpp

load test_helper

setup() {
  common_setup
  require_tool parse derive gen
}

# The flags of helios-solve's compile (against the runtime's header beside the tools), made strict.
syntax_check() {
  g++ -std=c++17 -O2 -Wall -Wextra -Werror -I"$HELIOS_BUILD_DIR/include/helios-runtime" -fsyntax-only "$1"
}

# ---- shared contract -------------------------------------------------------------------------

@test "gen: no arguments -> exit 2, one error line" {
  contract_no_args gen
}

@test "gen: unknown option -> exit 2" {
  s01_derivation
  contract_bad_option gen derivation.json
}

@test "gen: a bad --modules value -> exit 2, nothing written" {
  s01_derivation
  mkdir out
  run -2 --separate-stderr "$BIN/helios-gen" --modules sometimes derivation.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "sometimes"
  assert_dir_empty out
}

@test "gen: shoot.cpp opens with a map of its parts, each line number at that part's banner" {
  s01_shoot
  assert_file_map shoot.cpp "modules DYNAMICS + SWITCH" "module RESIDUAL" "module SOLVE"
}

@test "gen: the program holds no runtime: the prebuilt runtime's header, the problem, modules, entry point" {
  s01_shoot
  grep -qx '#include "helios_runtime.hpp"' shoot.cpp
  # Of templates/runtime only the entry point is in the file; none of the runtime's headers is
  # pasted (their banners, the integrator, the propagator, the solver calls, the JSON writer).
  [[ $(grep -o 'templates/runtime/[a-z0-9_]*\.hpp' shoot.cpp | sort -u) == templates/runtime/main.hpp ]]
  run -1 grep -nE 'HELIOS shooting runtime, [a-z]+ \(templates/runtime/[a-z0-9_]+\.hpp\): [a-z]' shoot.cpp
  run -1 grep -nE 'class (Propagator|Dop853|Shooter|MultiStart)|dop853_coeffs|hybrd1?\(|nlohmann|#include <' shoot.cpp
  # The problem and its modules are about 400 lines; the runtime alone is thousands.
  (($(wc -l <shoot.cpp) < 500))
}

@test "gen: --backend other than builtin -> exit 2" {
  s01_derivation
  run -2 --separate-stderr "$BIN/helios-gen" --backend nope derivation.json
  assert_one_error_line gen
}

@test "gen: missing input file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-gen" no-such-derivation.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "no-such-derivation.json"
  assert_dir_empty out
}

@test "gen: --help ends with an e.g. line" {
  contract_help gen
}

@test "gen: --version" {
  contract_version gen
}

@test "gen: malformed JSON -> exit 3, nothing written" {
  printf '[{"schema": "helios/derivation"}' >broken.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-gen" broken.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "broken.json"
  assert_dir_empty out
}

@test "gen: schema violation (derivation without hamiltonian) -> exit 3 naming the field" {
  s01_derivation
  jq 'del(.hamiltonian)' derivation.json >bad.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-gen" bad.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "bad.json" "hamiltonian"
  assert_dir_empty out
}

@test "gen: schema violation (shooting equation without expression) -> exit 3 naming the field path" {
  s01_derivation
  jq 'del(.shooting.equations[2].expression)' derivation.json >bad.json
  run -3 --separate-stderr "$BIN/helios-gen" bad.json
  assert_one_error_line gen
  assert_stderr_contains "expression"
  [[ $stderr == *"/shooting/equations/2"* ]]
}

@test "gen: wrong artifact kind (a spec) -> exit 3, nothing written" {
  s01_spec
  mkdir out
  run -3 --separate-stderr "$BIN/helios-gen" spec.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "helios/spec" "helios/derivation"
  assert_dir_empty out
}

@test "gen: wrong artifact kind (settings.json, no schema field) -> exit 3" {
  run -3 --separate-stderr "$BIN/helios-gen" "$S01/settings.json"
  assert_one_error_line gen
  assert_stderr_contains "/schema"
}

@test "gen: an unparsable expression -> exit 3, one error line naming where, nothing written" {
  s01_derivation
  jq '.shooting.equations[0].expression = "rx_tf +* 2"' derivation.json >bad.json
  mkdir out
  run -3 --separate-stderr "$BIN/helios-gen" bad.json -o out/shoot.cpp
  assert_one_error_line gen
  assert_stderr_contains "rx_tf +* 2"
  [[ $stderr == *"field /shooting/equations/0/expression"* ]]
  assert_dir_empty out
}

@test "gen: an expression with an unknown symbol -> exit 3 (generated modules)" {
  s01_derivation
  jq '.costate_odes[0].rhs = "foo + l_vx"' derivation.json >bad.json
  run -3 --separate-stderr "$BIN/helios-gen" --modules generated bad.json
  assert_one_error_line gen
  assert_stderr_contains "foo"
}

# ---- generated program -----------------------------------------------------------------------

@test "gen: the S01 program has the RESIDUAL and SOLVE modules and compiles cleanly" {
  s01_derivation
  run -0 --separate-stderr "$BIN/helios-gen" derivation.json -o shoot.cpp
  [[ -z $output && -z $stderr ]]
  grep -q "module RESIDUAL" shoot.cpp
  grep -q "module SOLVE" shoot.cpp
  # auto policy: S01 is the template's model, so DYNAMICS + SWITCH come from the template.
  grep -q "modules DYNAMICS + SWITCH" shoot.cpp
  run -1 grep -q "modules DYNAMICS + SWITCH (generated" shoot.cpp
  assert_no_temp_files .
  syntax_check shoot.cpp
}

@test "gen: --modules generated generates DYNAMICS + SWITCH and compiles cleanly" {
  s01_derivation
  run -0 --separate-stderr "$BIN/helios-gen" --modules generated derivation.json -o shoot.cpp
  grep -q "modules DYNAMICS + SWITCH (generated" shoot.cpp
  grep -q "module RESIDUAL" shoot.cpp
  grep -q "module SOLVE" shoot.cpp
  syntax_check shoot.cpp
}

@test "gen: a module table without throttle_slopes, for a problem with a throttle, fails to compile naming it" {
  s01_derivation
  run -0 "$BIN/helios-gen" derivation.json -o shoot.cpp
  grep -q '^  t.throttle_slopes = &throttle_slopes;$' shoot.cpp
  syntax_check shoot.cpp
  # The SWITCH module still defines the function: only the declaration is missing.
  grep -v '^  t.throttle_slopes = &throttle_slopes;$' shoot.cpp >lacking.cpp
  run -1 syntax_check lacking.cpp
  [[ $output == *"the problem has a throttle but the table names no throttle_slopes"* ]]
}

@test "gen: a module table without shooting_legs (events) or coast_dynamics (coasting target) fails to compile naming it" {
  local id entry need
  for id in S04:shooting_legs:events S06:coast_dynamics:"a coasting target"; do
    IFS=: read -r id entry need <<<"$id"
    "$BIN/helios-parse" "$ROOT/scenarios/$id/problem.txt" -o "$id.spec.json"
    "$BIN/helios-derive" "$id.spec.json" -o "$id.derivation.json"
    "$BIN/helios-gen" "$id.derivation.json" -o "$id.cpp"
    grep -q "^  t.$entry = &$entry;$" "$id.cpp"
    grep -v "^  t.$entry = &$entry;$" "$id.cpp" >"$id.lacking.cpp"
    run -1 syntax_check "$id.lacking.cpp"
    [[ $output == *"the problem has $need but the table names no $entry"* ]]
  done
}

@test "gen: a module table naming a module the program does not define fails to link naming it" {
  s01_derivation
  run -0 "$BIN/helios-gen" derivation.json -o shoot.cpp
  # S01 has no coasting target, so no coast_dynamics: the table claims one (as a misspelt
  # definition would leave it).
  sed 's/^  t.throttle_slopes = &throttle_slopes;$/&\n  t.coast_dynamics = \&coast_dynamics;/' shoot.cpp >claims.cpp
  grep -q '^  t.coast_dynamics = &coast_dynamics;$' claims.cpp
  syntax_check claims.cpp
  run -1 g++ -std=c++17 -O0 -pthread -I"$HELIOS_BUILD_DIR/include/helios-runtime" claims.cpp \
    "$HELIOS_BUILD_DIR/lib/libhelios-runtime.a" -lcminpack -o claims
  [[ $output == *"undefined reference to"*"coast_dynamics"* ]]
  [[ ! -e claims ]]
}

@test "gen: stdin input and stdout output give the same program as files" {
  s01_derivation
  "$BIN/helios-gen" derivation.json -o from-file.cpp
  "$BIN/helios-gen" - <derivation.json >from-stdin.cpp
  cmp from-file.cpp from-stdin.cpp
}

@test "gen: output is byte-identical across runs" {
  s01_derivation
  "$BIN/helios-gen" derivation.json -o a.cpp
  "$BIN/helios-gen" derivation.json -o b.cpp
  cmp a.cpp b.cpp
}

# GiNaC's term order follows the address of its type names: with address randomization on, S11's
# sail Jacobian came out in one of two forms, 3 runs in 12 the other one (symbolic::fix_expression_order).
@test "gen: a sail's Jacobian is the same text in every run, whatever the address layout" {
  "$BIN/helios-parse" "$ROOT/scenarios/S11/problem.txt" -o spec.json
  "$BIN/helios-derive" spec.json -o derivation.json
  "$BIN/helios-gen" derivation.json -o first.cpp
  local i
  for i in $(seq 1 12); do
    "$BIN/helios-gen" derivation.json -o again.cpp
    cmp first.cpp again.cpp
  done
}

@test "gen: every scenario's program (generated modules) unpacks only the locals it uses and compiles cleanly" {
  local dir id
  for dir in "$ROOT"/scenarios/S*; do
    id="$(basename "$dir")"
    echo "scenario $id"
    "$BIN/helios-parse" "$dir/problem.txt" -o "$id.spec.json"
    "$BIN/helios-derive" "$id.spec.json" -o "$id.derivation.json"
    "$BIN/helios-gen" --modules generated "$id.derivation.json" -o "$id.cpp"
    run -1 grep -n "maybe_unused" "$id.cpp"
    syntax_check "$id.cpp"
  done
}

@test "gen: an id or a shooting name that is not a plain name -> exit 3 naming the field, nothing written" {
  s01_derivation
  mkdir out
  jq '.problem.id = "S01\"; inline int pwn = std::system(\"touch marker\"); //"' derivation.json >hostile.json
  run -3 --separate-stderr "$BIN/helios-gen" hostile.json -o out/shoot.cpp
  [[ $stderr == *"hostile.json"*"/problem/id"* ]] || { echo "$stderr" >&2; false; }
  [[ $(wc -l <<<"$stderr") -eq 1 ]]
  jq '.shooting.variables[0].name = "x; int y"' derivation.json >hostile.json
  run -3 --separate-stderr "$BIN/helios-gen" hostile.json -o out/shoot.cpp
  [[ $stderr == *"/shooting/variables/0/name"* ]] || { echo "$stderr" >&2; false; }
  [[ -z $(ls -A out) && ! -e marker ]]
}

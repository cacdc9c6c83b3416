#!/usr/bin/env bats
# The generated JACOBIAN module (issue 15): the exact first derivatives of the right-hand side,
# of the direction law and of the throttle slopes against central finite differences of the
# program's own DYNAMICS and SWITCH modules (tests/bats/jacobian_check.cpp), for every scenario
# at 20 random points.
# Tolerance: every entry within 1e-6 of the difference, relative to 1 + its row's largest entry
# (central differences with h = 1e-6 (1 + |y_j|) agree to ~1e-9 here).

load test_helper

setup() {
  common_setup
  require_tool parse derive gen
}

# check_program SHOOT_CPP -> builds ./jacobian_check against it and runs it (20 points, seed 1)
check_program() {
  g++ -std=c++17 -O1 -pthread -DSHOOT_CPP="\"$1\"" -I"$HELIOS_BUILD_DIR/include/helios-runtime" \
    "$ROOT/tests/bats/jacobian_check.cpp" "$HELIOS_BUILD_DIR/lib/libhelios-runtime.a" -lcminpack -o jacobian_check
  ./jacobian_check 20 1
}

# program SCENARIO POLICY -> SCENARIO.cpp (helios-gen --modules POLICY)
program() {
  "$BIN/helios-parse" "$ROOT/scenarios/$1/problem.txt" -o "$1.spec.json"
  "$BIN/helios-derive" "$1.spec.json" -o "$1.derivation.json"
  "$BIN/helios-gen" --jacobian --modules "$2" "$1.derivation.json" -o "$1.cpp"
}

@test "jacobian: every scenario's generated Jacobian agrees with central differences of its dynamics" {
  local s
  for s in $(ls "$ROOT/scenarios" | grep -E '^S[0-9]+$'); do
    program "$s" auto
    run check_program "$PWD/$s.cpp"
    echo "$s: $output"
    [ "$status" -eq 0 ]
    [[ $output == *"max_error "* ]]
  done
}

@test "jacobian: S01's Jacobian also agrees with its generated (not template) dynamics" {
  program S01 generated
  run check_program "$PWD/S01.cpp"
  echo "$output"
  [ "$status" -eq 0 ]
}

@test "jacobian: helios-gen adds the module only with --jacobian (the runtime does not use it yet)" {
  program S01 auto
  grep -q '^void dynamics_jacobian(' S01.cpp
  "$BIN/helios-gen" S01.derivation.json -o plain.cpp
  run -1 grep -n 'jacobian' plain.cpp
}

@test "jacobian: a sign flipped in one generated derivative fails the check" {
  program S01 generated
  grep -q '^  dfdy\[3\] = ' S01.cpp
  sed -i '0,/^  dfdy\[[0-9]*\] = /s/^\(  dfdy\[[0-9]*\] = \)\(.*\);$/\1-(\2);/' S01.cpp
  run check_program "$PWD/S01.cpp"
  echo "$output"
  [ "$status" -eq 1 ]
  [[ $output == "max_error "* ]]
  # and one flipped entry of the direction law's derivative
  program S01 generated
  sed -i '0,/^  dcontrol_dy\[[0-9]*\] = /s/^\(  dcontrol_dy\[[0-9]*\] = \)\(.*\);$/\1-(\2);/' S01.cpp
  run check_program "$PWD/S01.cpp"
  echo "$output"
  [ "$status" -eq 1 ]
  # and one of the throttle slopes' gradients
  program S01 generated
  sed -i '0,/^  d_upper\[[0-9]*\] = /s/^\(  d_upper\[[0-9]*\] = \)\(.*\);$/\1-(\2);/' S01.cpp
  run check_program "$PWD/S01.cpp"
  echo "$output"
  [ "$status" -eq 1 ]
}

#!/usr/bin/env bats
# The exact Jacobians (issue 15), for every scenario:
#   - the generated JACOBIAN module: the first derivatives of the right-hand side in z = (y,
#     lambda0), of the direction law and of the throttle slopes against central finite differences
#     of the program's own DYNAMICS and SWITCH modules (tests/bats/jacobian_check.cpp), at 20
#     random points; every entry within 1e-6 of the difference, relative to 1 + its row's largest
#     entry (central differences with h = 1e-6 (1 + |y_j|) agree to ~1e-9 here);
#   - the shooting Jacobian (the RESIDUAL module on dual numbers: the variational equations, the
#     switches' and the free times' corrections) against finite differences of the shooting
#     function (tests/bats/shooting_jacobian_check.cpp), at random starts at eps = 1 (smooth) and
#     eps = 0 (bang-bang: switching arcs), and at the scenario's solution
#     (tests/fixtures/solutions); within 1e-6 relative to 1 + the row's largest entry; and for
#     S07, S10 and S13 (no events) the multiple-shooting system's (nodes.hpp: the state and
#     costates at the nodes as variables, their continuity as rows).

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
  "$BIN/helios-gen" --modules "$2" "$1.derivation.json" -o "$1.cpp"
}

# build_shooting_check SHOOT_CPP -> ./shooting_jacobian_check built against it (once per program:
# the compile is most of a check's time)
build_shooting_check() {
  g++ -std=c++17 -O2 -fno-math-errno -pthread -DSHOOT_CPP="\"$1\"" -I"$HELIOS_BUILD_DIR/include/helios-runtime" \
    "$ROOT/tests/bats/shooting_jacobian_check.cpp" "$HELIOS_BUILD_DIR/lib/libhelios-runtime.a" -lcminpack \
    -o shooting_jacobian_check
}

# shooting_check SHOOT_CPP ARGS... -> builds ./shooting_jacobian_check against it and runs it
shooting_check() {
  build_shooting_check "$1"
  shift
  ./shooting_jacobian_check "$@"
}

# one_point_agrees LABEL ARGS... -> the built ./shooting_jacobian_check on exactly one point, which agrees
one_point_agrees() {
  local label=$1
  shift
  run ./shooting_jacobian_check "$@"
  echo "$label: $output"
  [ "$status" -eq 0 ]
  [[ $output == "points 1 skipped 0 "* ]]
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

@test "jacobian: helios-gen --jacobian finite-difference leaves out the module and shooting_jacobian" {
  program S01 auto
  grep -q '^void dynamics_jacobian(' S01.cpp
  grep -q '^void shooting_jacobian(' S01.cpp
  "$BIN/helios-gen" --jacobian finite-difference S01.derivation.json -o plain.cpp
  run -1 grep -n 'jacobian' plain.cpp
  run -2 --separate-stderr "$BIN/helios-gen" --jacobian analytic S01.derivation.json -o bad.cpp
  [[ $stderr == *"--jacobian analytic is not one of exact, finite-difference"* ]]
  [[ ! -e bad.cpp ]]
}

@test "jacobian: every scenario's shooting Jacobian agrees with finite differences at random starts and at its solution" {
  local s eps x
  for s in $(ls "$ROOT/scenarios" | grep -E '^S[0-9]+$'); do
    program "$s" auto
    build_shooting_check "$PWD/$s.cpp"
    for eps in 1 0; do
      one_point_agrees "$s eps $eps" "$eps" 1 1
    done
    read -r -a x < "$ROOT/tests/fixtures/solutions/$s.txt"
    one_point_agrees "$s at its solution" 0 0 1 "${x[@]}"
  done
}

@test "jacobian: the multiple-shooting system's Jacobian (nodes at the events and inside the arcs) agrees with finite differences" {
  local s x
  export HELIOS_NODE_SEGMENTS=3
  for s in S07 S10 S13; do
    program "$s" auto
    build_shooting_check "$PWD/$s.cpp"
    one_point_agrees "$s with nodes, a random start" 0 1 1
    read -r -a x < "$ROOT/tests/fixtures/solutions/$s.txt"
    one_point_agrees "$s with nodes, at its solution" 0 0 1 "${x[@]}"
  done
}

@test "jacobian: a sign flipped in one entry of the variational equations fails the shooting check" {
  program S01 generated
  sed -i '0,/^  dfdz\[[0-9]*\] = /s/^\(  dfdz\[[0-9]*\] = \)\(.*\);$/\1-(\2);/' S01.cpp
  run shooting_check "$PWD/S01.cpp" 0 2 1
  echo "$output"
  [ "$status" -eq 1 ]
  [[ $output == "points 2 skipped 0 max_error "* ]]
}

@test "jacobian: a sign flipped in one generated derivative fails the check" {
  program S01 generated
  grep -q '^  dfdz\[3\] = ' S01.cpp
  sed -i '0,/^  dfdz\[[0-9]*\] = /s/^\(  dfdz\[[0-9]*\] = \)\(.*\);$/\1-(\2);/' S01.cpp
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

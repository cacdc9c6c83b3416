#!/usr/bin/env bats
# The Makefile's interface: the spellings of its variables, its errors for an unknown scenario or
# sweep, names and folders that are refused, and make help. make runs with -n (nothing is built or
# run) into a private RUNS_ROOT, but where a test needs the recipes run.

load test_helper

setup() {
  common_setup
}

# mk ARGS...: make -n in the repository, isolated from an enclosing make.
mk() {
  unnested_make -n RUNS_ROOT="$BATS_TEST_TMPDIR/runs" "$@"
}

@test "make: SCENARIO= and scenario= are one variable; two different values are refused" {
  run -0 mk SCENARIO=S07
  [[ $output == *"helios-parse' --backend builtin 'scenarios/S07/problem.txt'"* ]] || { echo "$output" >&2; false; }
  [[ $output != *"/S01/"* ]]
  run -0 mk scenario=S07 SCENARIO=S07
  [[ $output == *"scenarios/S07/problem.txt"* ]]
  run -2 --separate-stderr mk scenario=S07 SCENARIO=S01
  [[ ${#stderr_lines[@]} -eq 1 && $stderr == *"scenario=S07 and SCENARIO=S01 differ: give one of them"* ]] || { echo "$stderr" >&2; false; }
}

@test "make: an unknown scenario or sweep is one line that lists the known ones" {
  local known
  known=$(cd "$ROOT/scenarios" && ls -d S[0-9]* | sort | tr '\n' ' ')
  run -2 --separate-stderr mk scenario=S99
  [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
  assert_stderr_contains "scenario=S99 is not a scenario of scenarios/: use one of ${known% }" "P01"
  run -2 --separate-stderr mk sweep SWEEP=P99
  [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
  assert_stderr_contains "sweep=P99 is not a sweep of scenarios/ (no sweep.json): use one of P01"
  # A goal that runs no scenario does not check it.
  run -0 mk help scenario=S99
  [[ ! -e $BATS_TEST_TMPDIR/runs ]]
}

@test "make: a scenario of SCENARIOS_DIR is made from there" {
  mkdir -p mine/X01
  cp "$S01"/{problem.txt,settings.json,reference.json} mine/X01/
  run -0 mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X01
  [[ $output == *"helios-parse' --backend builtin '$BATS_TEST_TMPDIR/mine/X01/problem.txt' -o '$BATS_TEST_TMPDIR/runs/builtin/X01/spec.json'"* ]] ||
    { echo "$output" >&2; false; }
  run -2 --separate-stderr mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=S01
  assert_stderr_contains "scenario=S01 is not a scenario of $BATS_TEST_TMPDIR/mine/: use one of X01"
  # a folder without settings.json solves with the solver's defaults, one without reference.json
  # is scored without a reference
  mkdir -p mine/X02
  cp "$S01"/problem.txt mine/X02/
  run -0 --separate-stderr mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X02
  [[ $output == *"helios-solve' --backend builtin '$BATS_TEST_TMPDIR/runs/builtin/X02/shoot.cpp'"* ]] ||
    { echo "$output" >&2; false; }
  [[ $output == *"--spec '$BATS_TEST_TMPDIR/runs/builtin/X02/spec.json'"* ]] || { echo "$output" >&2; false; }
  [[ $output != *"--settings"* && $output != *"--reference"* ]] || { echo "$output" >&2; false; }
  [[ $output == *"helios-score' --no-reference 'X02'"* ]] || { echo "$output" >&2; false; }
  cp "$S01"/settings.json mine/X02/
  run -0 mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X02
  [[ $output == *"--settings '$BATS_TEST_TMPDIR/mine/X02/settings.json'"* ]] || { echo "$output" >&2; false; }
}

@test "make: problem=PATH runs any folder with a problem.txt, a P name too; a sweep is told by its sweep.json" {
  mkdir -p elsewhere/P4
  cp "$S01"/problem.txt elsewhere/P4/
  run -0 --separate-stderr mk problem="$BATS_TEST_TMPDIR/elsewhere/P4"
  [[ $output == *"helios-parse' --backend builtin '$BATS_TEST_TMPDIR/elsewhere/P4/problem.txt' -o '$BATS_TEST_TMPDIR/runs/builtin/P4/spec.json'"* ]] ||
    { echo "$output" >&2; false; }
  [[ $output == *"--no-reference 'P4'"* && $output == *"/runs/builtin/P4/report.md"* ]] || { echo "$output" >&2; false; }
  # a trailing slash, and the same folder named by SCENARIOS_DIR and scenario
  run -0 mk problem="$BATS_TEST_TMPDIR/elsewhere/P4/"
  [[ $output == *"'$BATS_TEST_TMPDIR/elsewhere/P4/problem.txt'"* ]] || { echo "$output" >&2; false; }
  run -0 mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/elsewhere" scenario=P4
  [[ $output == *"'$BATS_TEST_TMPDIR/elsewhere/P4/problem.txt'"* ]] || { echo "$output" >&2; false; }
  # a folder with a sweep.json is a sweep, whatever its name
  mkdir -p elsewhere/Q7
  cp "$ROOT"/scenarios/P01/{problem.txt,settings.json,sweep.json} elsewhere/Q7/
  run -2 --separate-stderr mk problem="$BATS_TEST_TMPDIR/elsewhere/Q7"
  [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
  assert_stderr_contains "$BATS_TEST_TMPDIR/elsewhere/Q7 is a sweep (it has a sweep.json): use make sweep sweep=Q7"
  # no problem.txt, two names for one problem, and a path that is not plain: one line each
  mkdir -p elsewhere/Empty
  run -2 --separate-stderr mk problem="$BATS_TEST_TMPDIR/elsewhere/Empty"
  assert_stderr_contains "problem=$BATS_TEST_TMPDIR/elsewhere/Empty: $BATS_TEST_TMPDIR/elsewhere/Empty/problem.txt is missing"
  run -2 --separate-stderr mk problem=elsewhere/P4
  assert_stderr_contains "problem=elsewhere/P4: elsewhere/P4/problem.txt is missing (a relative path starts at $ROOT)"
  run -2 --separate-stderr mk problem="$BATS_TEST_TMPDIR/elsewhere/P4" scenario=S01
  assert_stderr_contains "problem=$BATS_TEST_TMPDIR/elsewhere/P4 and scenario=S01 both name the problem: give one of them"
  run -2 --separate-stderr mk problem='$(shell id>X)/P4'
  [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
  assert_stderr_contains "problem='\$(shell id>X)/P4' is not a plain folder"
  [[ ! -e X && ! -e $ROOT/X ]]
}

@test "make: a scenario folder named like shell code is refused in one line and its code never runs" {
  local name='S9$(id>X)'
  mkdir -p "mine/$name" mine/X01
  cp "$S01"/{problem.txt,settings.json,reference.json} "mine/$name/"
  cp "$S01"/{problem.txt,settings.json,reference.json} mine/X01/
  # make for real (the recipes would run), the tools as they are.
  run -2 --separate-stderr unnested_make -o build/tools.stamp SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" \
    RUNS_ROOT="$BATS_TEST_TMPDIR/runs" all
  [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
  assert_stderr_contains "$BATS_TEST_TMPDIR/mine/$name is not a scenario name: rename the folder to A-Z a-z 0-9 _ - only"
  [[ ! -e $ROOT/X && ! -e X && ! -e $BATS_TEST_TMPDIR/runs ]]
  # The other folders of such a SCENARIOS_DIR are not made either, and a name with a blank, a quote
  # or a newline is refused the same way (a control byte shown as '?').
  run -2 --separate-stderr mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X01
  assert_stderr_contains "mine/$name is not a scenario name"
  rm -r "mine/$name"
  local bad
  for bad in 'S9 x' "S9'x" 'S9"x' $'S9\nx' 'S9;x' 'S9`x`'; do
    mkdir "mine/$bad"
    run -2 --separate-stderr mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X01
    [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
    assert_stderr_contains "mine/${bad//$'\n'/?} is not a scenario name"
    rm -r "mine/$bad"
  done
  # A hidden folder is no scenario, and a plain one is made.
  mkdir "mine/.git x"
  run -0 mk SCENARIOS_DIR="$BATS_TEST_TMPDIR/mine" scenario=X01
  [[ $output == *"'$BATS_TEST_TMPDIR/mine/X01/problem.txt'"* ]] || { echo "$output" >&2; false; }
}

@test "make: a folder variable or a name with a blank, a quote or \$ is refused in one line naming it" {
  local v value
  for v in RUNS_ROOT SCENARIOS_DIR CACHE; do
    for value in "$BATS_TEST_TMPDIR/my runs" "$BATS_TEST_TMPDIR/it's" "$BATS_TEST_TMPDIR/a\"b" '$(shell id>X)' 'a;id'; do
      run -2 --separate-stderr mk "$v=$value"
      [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
      assert_stderr_contains "$v='$value' is not a plain folder: use only A-Z a-z 0-9 _ - . / +"
    done
  done
  for v in scenario RUN_TAG sweep SWEEP_GRID; do
    run -2 --separate-stderr mk "$v=S0 1"
    [[ ${#stderr_lines[@]} -eq 1 ]] || { echo "$stderr" >&2; false; }
    assert_stderr_contains "$v='S0 1' is not a"
  done
  run -2 --separate-stderr mk SOLVE_TIME_LIMIT='1;id'
  assert_stderr_contains "SOLVE_TIME_LIMIT='1;id' is not a count: use only digits"
  run -2 --separate-stderr mk PARSE_BACKEND=magic
  assert_stderr_contains "PARSE_BACKEND=magic is not a backend of this build"
  [[ ! -e X && ! -e $ROOT/X ]]
  # An environment variable is checked by its text too, before make would expand it.
  RUNS_ROOT='r$(shell id>X)' run -2 --separate-stderr unnested_make -n
  assert_stderr_contains "RUNS_ROOT='r\$(shell id>X)' is not a plain folder"
  [[ ! -e X && ! -e $ROOT/X ]]
}

@test "make help: lists the main targets and variables" {
  run -0 --separate-stderr unnested_make help
  local word
  for word in "make [scenario=S01]" "make test" "make all" "make scoreboard" "make sweep sweep=P01" "make bench" \
    "make test-sanitized" "make fuzz" "BACKEND=builtin|llm" "VERIFY_MODE" "LAUNCH=" "RUNS_ROOT" "SCENARIOS_DIR" "SCENARIO"; do
    [[ $output == *"$word"* ]] || { echo "make help does not mention '$word':" >&2; echo "$output" >&2; false; }
  done
  [[ -z $stderr ]]
}

#!/usr/bin/env bats
# A user's own problem: a folder outside the repository holding only problem.txt runs with one
# make (any valid name, one starting with P too) to report.md, scored "no reference"; helios-solve
# writes only where it is told; the output speaks the problem's units (hours for a GTO-to-GEO
# transfer, calendar dates for epochs).
#
# make runs with `-o build/tools.stamp` (the tools taken as built, as pipeline.bats) into private
# RUNS_ROOT and CACHE folders.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve score
  export OWN_CACHE="$BATS_FILE_TMPDIR/cache"
}

setup() {
  common_setup
}

# own_make ARGS...: make into the test's runs tree (isolated_make).
own_make() {
  isolated_make "$BATS_TEST_TMPDIR/runs" "$OWN_CACHE" "$@"
}

# chain DIR PROBLEM.txt -> DIR/spec.json, derivation.json, shoot.cpp
chain() {
  local dir="$1" problem="$2"
  mkdir -p "$dir"
  "$BIN/helios-parse" "$problem" -o "$dir/spec.json"
  "$BIN/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$BIN/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
}

@test "own problem: a folder P4 outside the repository with only problem.txt runs with one make to report.md" {
  mkdir -p mine/P4
  sed 's/^Problem S01:/Problem P4:/' "$S01/problem.txt" >mine/P4/problem.txt
  local before
  before=$(git -C "$ROOT" status --porcelain --untracked-files=all)
  run -0 own_make problem="$BATS_TEST_TMPDIR/mine/P4"
  local run="$BATS_TEST_TMPDIR/runs/builtin/P4"
  for f in spec.json derivation.json verify.json shoot.cpp solution.json trajectory.csv trajectory.png \
    throttle_mass.png trajectory.oem report.md score.json; do
    [[ -s $run/$f ]] || { echo "missing $run/$f" >&2; echo "$output" >&2; false; }
  done
  [[ $(jq -r .status "$run/solution.json") == converged ]]
  # without settings.json: the solver's defaults (seed 1), recorded
  [[ $(jq -r .seed "$run/solution.json") == 1 ]]
  # without reference.json: scored on what needs none, the rest says "no reference"
  [[ $(jq -r '.reference' "$run/score.json") == null ]]
  [[ $(jq -r '.dimensions.d5_accuracy.details[0].verdict' "$run/score.json") == no_reference ]]
  [[ $(jq -r '.dimensions.d5_accuracy.details[0].note' "$run/score.json") == "no reference: "* ]]
  [[ $(jq -r '.max_total' "$run/score.json") == 44 && $(jq -r '.total' "$run/score.json") == 44 ]]
  # the report shows the plots
  grep -qF '](trajectory.png)' "$run/report.md"
  grep -qF '](throttle_mass.png)' "$run/report.md"
  # nothing was written into the folder of the problem or into the repository
  [[ $(ls -A mine/P4) == problem.txt ]]
  [[ $(git -C "$ROOT" status --porcelain --untracked-files=all) == "$before" ]]
  # a second make does nothing
  run -0 own_make -q problem="$BATS_TEST_TMPDIR/mine/P4"
}

@test "own problem: helios-solve without --trajectory writes beside -o, never into the working directory" {
  chain "$BATS_TEST_TMPDIR/s01" "$S01/problem.txt"
  mkdir work out
  cd work
  run -0 --separate-stderr "$BIN/helios-solve" ../s01/shoot.cpp --settings "$S01/settings.json" \
    --cache-dir "$OWN_CACHE" -o ../out/solution.json
  [[ -z $(ls -A .) ]] || { echo "left in the working directory:" >&2; ls -A >&2; false; }
  [[ -s ../out/trajectory.csv && $(jq -r .files.trajectory ../out/solution.json) == trajectory.csv ]]
  [[ $(ls -A ../out | sort | tr '\n' ' ') == "solution.json trajectory.csv " ]]
  # -o - (stdout): no trajectory is kept, and still nothing lands here
  run -0 --separate-stderr "$BIN/helios-solve" ../s01/shoot.cpp --settings "$S01/settings.json" \
    --cache-dir "$OWN_CACHE" -o -
  [[ $(jq -r .status <<<"$output") == converged && $(jq -r '.files.trajectory // "none"' <<<"$output") == none ]]
  [[ -z $(ls -A .) ]] || { echo "left in the working directory:" >&2; ls -A >&2; false; }
}

@test "own problem: S14 (GTO to GEO, hours) has tof_hours, its plots and progress in hours" {
  chain s14 "$ROOT/scenarios/S14/problem.txt"
  run -0 --separate-stderr "$BIN/helios-solve" s14/shoot.cpp --settings "$ROOT/scenarios/S14/settings.json" \
    --spec s14/spec.json --cache-dir "$OWN_CACHE" --plots s14/ -o s14/solution.json
  [[ $(jq -r .status s14/solution.json) == converged ]]
  jq -e '(.tof_hours - .tof_days * 24 | fabs) < 1e-9 and .tof_hours > 10 and .tof_hours < 20' s14/solution.json
  # the reference's 14.800364 h
  jq -e '(.tof_hours - 14.800364354648908 | fabs) < 1e-4' s14/solution.json
  [[ $stderr == *"problem S14: time of flight free, at most 48.00 h"* ]] || { echo "$stderr" >&2; false; }
  [[ $stderr == *"converged: time of flight 14.8004 h"* ]] || { echo "$stderr" >&2; false; }
  [[ -s s14/trajectory.png && -s s14/throttle_mass.png ]]
  # no calendar date for a problem without an epoch
  jq -e 'has("departure_date_tdb") | not' s14/solution.json
}

@test "own problem: every epoch has its ISO calendar date (TDB) in solution.json, the report and the progress" {
  sed 's/^Problem S01:/Problem E01:/; s/departs at t = 0 days from/departs at MJD2000 400 from/' "$S01/problem.txt" >problem.txt
  grep -q 'departs at MJD2000 400 from' problem.txt
  chain e01 problem.txt
  run -0 --separate-stderr "$BIN/helios-solve" e01/shoot.cpp --settings "$S01/settings.json" --spec e01/spec.json \
    --cache-dir "$OWN_CACHE" --plots e01/ -o e01/solution.json
  [[ $(jq -r .status e01/solution.json) == converged ]]
  [[ $(jq -r .departure_mjd2000 e01/solution.json) == 400 ]]
  [[ $(jq -r .departure_date_tdb e01/solution.json) == 2001-02-04T00:00:00 ]]
  jq -e '(.arrival_mjd2000 - 748.795 | fabs) < 1e-9' e01/solution.json
  [[ $(jq -r .arrival_date_tdb e01/solution.json) == 2002-01-18T19:04:48 ]]
  jq -e 'has("tof_hours") | not' e01/solution.json  # 348.8 days is said in days
  [[ $stderr == *"problem E01: departure 2001-02-04T00:00:00 TDB; time of flight 348.80 days"* ]] || { echo "$stderr" >&2; false; }
  [[ $stderr == *"converged: time of flight 348.7950 days, departure 2001-02-04T00:00:00 TDB (MJD2000 400), arrival 2002-01-18T19:04:48 TDB (MJD2000 748.795)"* ]] ||
    { echo "$stderr" >&2; false; }
  "$BIN/helios-verify" e01/derivation.json -o e01/verify.json
  "$BIN/helios-score" --report --problem problem.txt --spec e01/spec.json --derivation e01/derivation.json \
    --verify e01/verify.json --solution e01/solution.json -o e01/report.md
  grep -qF '| `departure_date_tdb` | 2001-02-04T00:00:00 |' e01/report.md
  grep -qF '| `arrival_date_tdb` | 2002-01-18T19:04:48 |' e01/report.md
  grep -qF '| 400 (2001-02-04T00:00:00 TDB) | MJD2000 |' e01/report.md
}

#!/usr/bin/env bats
# The solve step on a real single-node Slurm cluster (tests/slurm/cluster.sh): S01 made through the
# Makefile with LAUNCH="srun -n1 -c1 ..." runs its solve as a Slurm job step and gives the same
# objective, to 1e-9 relative, as S01 made without LAUNCH.
#
# Needs root (the cluster's daemons run as root) and Slurm installed or installable by apt-get
# (cluster.sh start installs it); otherwise every test skips and says why. Under CI (CI set, as
# .ci/run sets it) as root nothing skips: a cluster that does not start fails the file.
# A cluster that was already up is used and left up; one this file started is stopped at the end.
# A lock (/tmp/helios-bats-slurm.lock) serializes concurrent runs of this file, which share the
# cluster. Runs go to private RUNS_ROOTs under $BATS_FILE_TMPDIR, sharing one compile cache.

load test_helper

BATS_NO_PARALLELIZE_WITHIN_FILE=true

CLUSTER="$ROOT/tests/slurm/cluster.sh"
SLURM_LOCK=/tmp/helios-bats-slurm.lock
SLURM_LOCK_FD=202

# Bats 1.8 (Debian 12) cannot skip from setup_file: setup_file names the reason in SLURM_SKIP and
# setup skips each test with it.
setup_file() {
  require_tool parse derive verify gen solve score
  export SLURM_SKIP=""
  if [[ $(id -u) -ne 0 ]]; then
    SLURM_SKIP="needs root: tests/slurm/cluster.sh runs slurmctld, slurmd and munged as root"
    return 0
  fi
  if [[ -z ${CI:-} ]] && ! command -v srun >/dev/null && ! command -v apt-get >/dev/null; then
    SLURM_SKIP="Slurm is not installed and there is no apt-get to install it (tools/install-deps.sh --slurm)"
    return 0
  fi
  eval "exec $SLURM_LOCK_FD>\"\$SLURM_LOCK\""
  flock -w 600 "$SLURM_LOCK_FD" || { echo "another run of slurm.bats holds $SLURM_LOCK" >&2; return 1; }
  eval "$("$CLUSTER" env)"
  export SLURM_CONF
  if "$CLUSTER" status >/dev/null 2>&1; then
    export SLURM_STARTED_HERE=0
  else
    export SLURM_STARTED_HERE=1
    local t0=$SECONDS
    if ! "$CLUSTER" start 2>"$BATS_FILE_TMPDIR/start.err"; then
      if [[ -n ${CI:-} ]]; then
        echo "CI: the Slurm cluster did not start:" >&2
        cat "$BATS_FILE_TMPDIR/start.err" >&2
        return 1
      fi
      SLURM_SKIP="the Slurm cluster did not start on this machine (CI unset): $(head -n 1 "$BATS_FILE_TMPDIR/start.err")"
      return 0
    fi
    echo "# slurm: cluster started in $((SECONDS - t0)) s" >&3
  fi

  # The step recorder LAUNCH runs under srun: it writes the Slurm variables of the step it runs in
  # to slurm-step.env beside the run (the folder of the solve's -o), then becomes the solve.
  RECORD_STEP="$BATS_FILE_TMPDIR/record-step"
  cat >"$RECORD_STEP" <<'EOF'
#!/usr/bin/env bash
out= prev=
for arg in "$@"; do
  [[ $prev == -o ]] && out=$arg
  prev=$arg
done
[[ -n $out ]] || { echo "record-step: no -o in: $*" >&2; exit 2; }
env | grep -E '^(SLURM_JOB_ID|SLURM_STEP_ID|SLURM_NTASKS|SLURM_CPUS_PER_TASK|SLURMD_NODENAME)=' >"$(dirname "$out")/slurm-step.env"
exec "$@"
EOF
  chmod +x "$RECORD_STEP"
  export RECORD_STEP
  export SLURM_RUNS="$BATS_FILE_TMPDIR/slurm" PLAIN_RUNS="$BATS_FILE_TMPDIR/plain" SHARED_CACHE="$BATS_FILE_TMPDIR/cache"
}

teardown_file() {
  if [[ ${SLURM_STARTED_HERE:-0} == 1 ]]; then
    "$CLUSTER" stop
  fi
  eval "exec $SLURM_LOCK_FD>&-"
}

setup() {
  [[ -z ${SLURM_SKIP:-} ]] || skip "$SLURM_SKIP"
  common_setup
}

# smake RUNS_ROOT [VAR=VALUE...]: make S01 into RUNS_ROOT, isolated from an enclosing make and from
# tool rebuilds (as pipeline.bats does), with the shared compile cache.
smake() {
  local runs="$1"
  shift
  isolated_make "$runs" "$SHARED_CACHE" scenario=S01 "$@"
}

slurm_make() {
  smake "$SLURM_RUNS" LAUNCH="srun -n1 -c1 $RECORD_STEP"
}

@test "slurm: the cluster is up, a second start is a quiet no-op, srun runs a step" {
  run -0 "$CLUSTER" start
  [[ -z $output ]] || { echo "start on a running cluster printed: $output" >&2; false; }
  run -0 "$CLUSTER" status
  [[ $output == *"node $(hostname -s): idle"* ]] || { echo "$output" >&2; false; }
  run -0 srun -n1 -c1 printenv SLURM_JOB_ID SLURM_STEP_ID
  [[ ${lines[0]} =~ ^[0-9]+$ && ${lines[1]} =~ ^[0-9]+$ ]] || { echo "srun printed: $output" >&2; false; }
}

@test "slurm: S01 made with LAUNCH=\"srun -n1 -c1\" solves as a Slurm job step" {
  run -0 slurm_make
  local dir="$SLURM_RUNS/builtin/S01"
  assert_jq "$dir/solution.json" '.status == "converged"'
  assert_jq "$dir/score.json" '.total == 100'
  [[ -s $dir/slurm-step.env ]] || { echo "no slurm-step.env: the solve did not run through the recorder" >&2; false; }
  cat "$dir/slurm-step.env" >&2
  local job step
  job="$(sed -n 's/^SLURM_JOB_ID=//p' "$dir/slurm-step.env")"
  step="$(sed -n 's/^SLURM_STEP_ID=//p' "$dir/slurm-step.env")"
  [[ $job =~ ^[0-9]+$ && $step =~ ^[0-9]+$ ]] || { echo "no job or step id in the solve's environment" >&2; false; }
  grep -qx 'SLURM_NTASKS=1' "$dir/slurm-step.env"
  grep -qx 'SLURM_CPUS_PER_TASK=1' "$dir/slurm-step.env"
  grep -qx "SLURMD_NODENAME=$(hostname -s)" "$dir/slurm-step.env"
  # srun -c1 gave the step one CPU: the search ran on one thread, not on every core.
  assert_jq "$dir/solution.json" '.settings.threads == 1 and .search.threads == 1'
  # The controller saw that job finish: its job completion log (the cluster keeps no accounting
  # database) has a line for it, written when the job ends (a moment after srun returns).
  local jobcomp i
  jobcomp="$(scontrol show config | awk '$1 == "JobCompLoc" { print $3 }')"
  for ((i = 0; i < 50; i++)); do
    grep -q "^JobId=$job .*JobState=COMPLETED .*ExitCode=0:0" "$jobcomp" 2>/dev/null && break
    sleep 0.2
  done
  grep "^JobId=$job " "$jobcomp" >&2 || true
  grep -q "^JobId=$job .*JobState=COMPLETED .*ExitCode=0:0" "$jobcomp" ||
    { echo "job $job is not COMPLETED with exit 0 in $jobcomp" >&2; false; }
}

@test "slurm: the objective through Slurm equals the one without LAUNCH (1e-9 relative)" {
  # make is incremental: the Slurm run of the test above is reused when it is complete.
  run -0 slurm_make
  run -0 smake "$PLAIN_RUNS"
  local s="$SLURM_RUNS/builtin/S01/solution.json" p="$PLAIN_RUNS/builtin/S01/solution.json"
  [[ ! -e $PLAIN_RUNS/builtin/S01/slurm-step.env ]]
  assert_jq "$p" '.status == "converged"'
  # S01 minimizes fuel: the objective is the returned extremal's (propellant / initial mass);
  # final_mass_kg and propellant_kg are the same number in kg.
  local filter='[(.search.returned as $r | .search.extremals[] | select(.id == $r) | .objective), .final_mass_kg, .propellant_kg]'
  local a b
  a="$(jq -c "$filter" "$s")"
  b="$(jq -c "$filter" "$p")"
  echo "through Slurm: $a, without: $b" >&2
  jq -en --argjson a "$a" --argjson b "$b" \
    '($a | length) == 3 and ([range(3) | (($a[.] - $b[.]) | fabs) <= 1e-9 * ($b[.] | fabs)] | all)' >/dev/null
}

@test "slurm: the P01 sweep with LAUNCH=\"srun -n1 -c1\" solves every cell, boundary and cross-check try as a Slurm step, objectives as without LAUNCH" {
  run -0 sweep_make "$SLURM_RUNS" LAUNCH="srun -n1 -c1 $RECORD_STEP"
  run -0 sweep_make "$PLAIN_RUNS"
  local s="$SLURM_RUNS/builtin/P01" p="$PLAIN_RUNS/builtin/P01" cell jobs=()
  [[ $(tail -n +2 "$s/sweep.csv" | wc -l) -eq 9 ]]
  for cell in $(tail -n +2 "$s/sweep.csv" | cut -d, -f3); do
    [[ -s $s/$cell/slurm-step.env ]] || { echo "$cell: no slurm-step.env, its solve was no Slurm step" >&2; false; }
    [[ ! -e $p/$cell/slurm-step.env ]]
    grep -Eq '^SLURM_JOB_ID=[0-9]+$' "$s/$cell/slurm-step.env"
    grep -Eq '^SLURM_STEP_ID=[0-9]+$' "$s/$cell/slurm-step.env"
    grep -qx 'SLURM_CPUS_PER_TASK=1' "$s/$cell/slurm-step.env"
    jobs+=("$(sed -n 's/^SLURM_JOB_ID=//p' "$s/$cell/slurm-step.env")")
    assert_jq "$s/$cell/solution.json" '.settings.threads == 1'
  done
  # Each cell was its own srun (job): nine distinct job ids.
  [[ $(printf '%s\n' "${jobs[@]}" | sort -u | wc -l) -eq 9 ]]
  # So were the boundaries' minimum-time solves and the cross-check's tries.
  local f tries=0
  for f in "$s"/b*/solution.json "$s"/*/crosscheck/*/solution.json; do
    [[ -s $(dirname "$f")/slurm-step.env ]] || { echo "$f: its solve was no Slurm step" >&2; false; }
    [[ $f == */crosscheck/* ]] && tries=$((tries + 1))
  done
  ((tries == 24)) || { echo "$tries cross-check tries" >&2; false; }
  # Same cells, same status and start, objectives within 1e-9 relative.
  paste -d, <(tail -n +2 "$s/sweep.csv" | cut -d, -f3,4,5,7) <(tail -n +2 "$p/sweep.csv" | cut -d, -f3,4,5,7) |
    awk -F, '{ d = $3 - $7; if (d < 0) d = -d
               if ($1 != $5 || $2 != "converged" || $2 != $6 || $4 != $8 || d > 1e-9 * $7) { print "differs: " $0; bad = 1 } }
             END { exit bad }' >&2
}

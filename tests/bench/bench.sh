#!/usr/bin/env bash
# Benchmark: wall time of each stage of one scenario on the builtin backend, from a cold start
# (fresh output folder, empty compile cache), then a warm solve (compile cache hit).
# usage: tests/bench/bench.sh [SCENARIO]   (run from the repository root; needs `make tools`)
set -euo pipefail
scenario=${1:-S01}
bin=build/bin
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
declare -A seconds
stage() {
  local name=$1
  shift
  local t0
  t0=$(now)
  "$@"
  seconds[$name]=$(echo "$(now) - $t0" | bc -l)
  printf '%-28s %8.3f s\n' "$name" "${seconds[$name]}"
}

echo "HELIOS benchmark, scenario $scenario, $(nproc) cores, $(date -u +%FT%TZ)"
stage parse "$bin/helios-parse" "scenarios/$scenario/problem.txt" -o "$work/spec.json"
stage derive "$bin/helios-derive" "$work/spec.json" -o "$work/derivation.json"
stage verify "$bin/helios-verify" "$work/derivation.json" -o "$work/verify.json"
stage gen "$bin/helios-gen" "$work/derivation.json" -o "$work/shoot.cpp"
stage "solve (cold: compile+run)" "$bin/helios-solve" "$work/shoot.cpp" --settings "scenarios/$scenario/settings.json" \
  --cache-dir "$work/cache" --trajectory "$work/trajectory.csv" --plots "$work/" -o "$work/solution.json"
stage "solve (warm: cached binary)" "$bin/helios-solve" "$work/shoot.cpp" --settings "scenarios/$scenario/settings.json" \
  --cache-dir "$work/cache" --trajectory "$work/trajectory.csv" -o "$work/solution2.json"
stage score "$bin/helios-score" --reference "scenarios/$scenario/reference.json" --spec "$work/spec.json" \
  --derivation "$work/derivation.json" --verify "$work/verify.json" --solution "$work/solution.json" -o "$work/score.json"

front=$(echo "${seconds[parse]} + ${seconds[derive]} + ${seconds[verify]}" | bc -l)
printf '%-28s %8.3f s   (target < 1 s: ratio %.3f)\n' "parse+derive+verify" "$front" "$(echo "$front / 1" | bc -l)"
printf '%-28s %8.3f s   (target < 30 s: ratio %.3f)\n' "solve cold" "${seconds[solve (cold: compile+run)]}" \
  "$(echo "${seconds[solve (cold: compile+run)]} / 30" | bc -l)"
jq -r '"compile \(.timings.compile_s) s, run \(.timings.run_s) s, status \(.status), m_f \(.final_mass_kg) kg, max|F| \(.max_residual), evaluations \(.function_evaluations), restarts \(.restarts)"' "$work/solution.json"
jq -r '"score total \(.total)"' "$work/score.json"

#!/usr/bin/env bash
# The search audit: does the default search return the best extremal an exhaustive one finds?
# For each case the default search (the runtime's defaults, settings {"seed": s}) runs at every
# seed of SEEDS, and an exhaustive one at every seed of EXHAUSTIVE_SEEDS: ten times the starts the
# default drew (at least 1280), no saturation stop (search_saturation 0), every distinct extremal
# continued (search_continue_all) and no budget but the time limit. The exhaustive best is the best
# objective over its seeds; a default run "equals" it when within 1e-6 relative. Prints a line per
# case and seed (default objective and wall time, exhaustive best, equal or not), then the counts.
# An exhaustive minimum-time search costs minutes (its thousands of random starts mostly fail
# slowly), so one exhaustive seed is the default: EXHAUSTIVE_SEEDS="1 2 3 4 5" for all five.
#
# Cases: the scenarios with more than one extremal (S13, S02), the many-revolution stress case
# tests/bench/audit/D01 (Earth to Dionysus, 3534 days), S11's sail at other departures, and P01's
# problem with the time of flight free and minimized (window 50-700 days) at the departures
# MJD2000 9400 ... 10180 every 60 days.
# usage: tests/bench/search_audit.sh [CASE...]   (from the repository root; needs `make tools`;
#   HELIOS_BUILD_DIR: another build tree, default build)
#   CASE: S13 S02 D01 SAIL<MJD> MT<MJD2000>; default: all of them
#   SEEDS="1 2 3 4 5" (default), EXHAUSTIVE_SEEDS="1" (default)
set -euo pipefail
bin=${HELIOS_BUILD_DIR:-build}/bin
seeds=${SEEDS:-1 2 3 4 5}
exhaustive_seeds=${EXHAUSTIVE_SEEDS:-1}
if (($# == 0)); then
  set -- S13 S02 D01 SAIL61200 SAIL61650 SAIL61950 $(seq -f 'MT%g' 9400 60 10180)
fi
work=$(mktemp -d)
[[ -n ${KEEP:-} ]] || trap 'rm -rf "$work"' EXIT
echo "search audit work folder: $work" >&2

# problem CASE DIR: writes DIR/problem.txt
problem() {
  local case=$1 dir=$2
  case $case in
    S[0-9]*) cp "scenarios/$case/problem.txt" "$dir/" ;;
    D01) cp tests/bench/audit/D01/problem.txt "$dir/" ;;
    SAIL*) sed -e "s/MJD 61500/MJD ${case#SAIL}/" scenarios/S11/problem.txt >"$dir/problem.txt" ;;
    MT*)
      sed -e "s/@DEPARTURE_MJD2000@/${case#MT}/" \
        -e 's/^The time of flight is .*/The time of flight is free, between 50 days and 700 days./' \
        -e 's/^Minimize the fuel consumption\./Minimize the time of flight./' scenarios/P01/problem.txt >"$dir/problem.txt"
      ;;
    *) echo "search_audit: unknown case $case" >&2 && return 2 ;;
  esac
}

# solve DIR NAME SETTINGS_JSON: DIR/NAME.json from DIR/shoot.cpp; prints objective and wall seconds
solve() {
  local dir=$1 name=$2 t0
  echo "$3" >"$dir/$name.settings.json"
  t0=$(date +%s.%N)
  "$bin/helios-solve" --quiet "$dir/shoot.cpp" --settings "$dir/$name.settings.json" --cache-dir "$work/cache" \
    --plots "" --trajectory "$dir/$name.csv" -o "$dir/$name.json"
  echo "$(jq -r 'if .status == "converged" then (.search.extremals[.search.returned].objective) else "none" end' \
    "$dir/$name.json") $(echo "$(date +%s.%N) - $t0" | bc -l)"
}

# in_units DIR NAME: the returned extremal's objective in kg or days ("none": no solution)
in_units() {
  jq -r 'if .status != "converged" then "none" else .search.extremals[.search.returned] |
    if .propellant_kg then "\(.propellant_kg * 1000 | round / 1000) kg" else "\(.tof_days * 1000 | round / 1000) d" end end' \
    "$1/$2.json"
}

echo "HELIOS search audit, $(nproc) cores, $(date -u +%FT%TZ); seeds: $seeds; exhaustive seeds: $exhaustive_seeds"
printf '%-10s %4s %14s %9s %7s %8s %14s %9s %s\n' case seed default default_s starts saturated exhaustive_best exhaust_s equal
equal=0 runs=0 slowest=0
for case in "$@"; do
  dir="$work/$case"
  mkdir -p "$dir"
  problem "$case" "$dir"
  "$bin/helios-parse" "$dir/problem.txt" -o "$dir/spec.json"
  "$bin/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$bin/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
  declare -A default_objective=() default_seconds=()
  most_starts=0
  for seed in $seeds; do
    read -r default_objective[$seed] default_seconds[$seed] < <(solve "$dir" "default-$seed" "{\"seed\": $seed}")
    most_starts=$(jq --argjson m "$most_starts" '[.search.starts, $m] | max' "$dir/default-$seed.json")
  done
  best=none best_name="" exhaustive_s=0
  starts=$((most_starts * 10 > 1280 ? most_starts * 10 : 1280))
  for seed in $exhaustive_seeds; do
    read -r objective seconds < <(solve "$dir" "exhaustive-$seed" "{\"seed\": $seed, \"search_starts\": $starts, \
      \"search_saturation\": 0, \"search_continue_all\": true, \"time_limit_s\": 3600}")
    exhaustive_s=$(echo "$exhaustive_s + $seconds" | bc -l)
    if [[ $objective != none ]] && { [[ $best == none ]] || (($(echo "$objective < $best" | bc -l))); }; then
      best=$objective best_name="exhaustive-$seed"
    fi
  done
  for seed in $seeds; do
    objective=${default_objective[$seed]}
    same=no
    if [[ $objective != none && $best != none ]] &&
      awk -v a="$objective" -v b="$best" 'BEGIN { d = a - b; exit !((d < 0 ? -d : d) <= 1e-6 * (b < 0 ? -b : b)) }'; then
      same=yes
      equal=$((equal + 1))
    fi
    runs=$((runs + 1))
    (($(echo "${default_seconds[$seed]} > $slowest" | bc -l))) && slowest=${default_seconds[$seed]}
    printf '%-10s %4s %14s %9.2f %7s %8s %14s %9.1f %s\n' "$case" "$seed" "$(in_units "$dir" "default-$seed")" \
      "${default_seconds[$seed]}" "$(jq .search.starts "$dir/default-$seed.json")" \
      "$(jq .search.saturated "$dir/default-$seed.json")" \
      "$([[ -n $best_name ]] && in_units "$dir" "$best_name" || echo none)" "$exhaustive_s" "$same"
  done
  unset default_objective default_seconds
done
echo "search audit: the default equals the exhaustive best in $equal of $runs runs; slowest default solve $slowest s"

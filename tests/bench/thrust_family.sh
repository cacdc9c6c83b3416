#!/usr/bin/env bash
# The GTO -> GEO minimum-time family t_f(T_max): S14's problem text at 60, 20, 10, 5, 2, 1 and
# 0.5 N (the thrust and the final time's window, 1.6 x 888 N h / T, changed in its sentences,
# nothing else), each cold from its own search with an empty compile cache. Prints per thrust t_f,
# the product t_f T (nearly constant at low thrust in the literature on this transfer: a check),
# the revolutions, max|F|, the wall time and how the returned extremal was reached (the search
# itself, or the thrust continuation from the raised thrust it started at, with its steps).
# usage: tests/bench/thrust_family.sh [THRUST_N...]   (run from the repository root; needs `make tools`)
set -euo pipefail
bin=build/bin
if (($# == 0)); then thrusts=(60 20 10 5 2 1 0.5); else thrusts=("$@"); fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A larger budget than S14's: the low-thrust transfers integrate for weeks of flight per evaluation.
# Over tens of revolutions single shooting resolves F only to about 1e-9 (its sensitivity), so the
# search accepts its extremals there and the returned one is polished by multiple shooting with a
# node a day (flights shorter than a day keep single shooting): max|F| is then the multiple-shooting
# system's, and "SS max|F|" the single-shooting residual of the same point.
jq '.time_limit_s = 3000 | .search_time_s = 500 | .final_residual = 1e-9 | .node_spacing_days = 1' \
  scenarios/S14/settings.json >"$work/settings.json"

printf '%-8s %-12s %-10s %-8s %-10s %-10s %-8s %s\n' "T [N]" "t_f [h]" "t_f T [N h]" "revs" "max|F|" "SS max|F|" "wall [s]" "reached by"
for thrust in "${thrusts[@]}"; do
  dir="$work/T$thrust"
  mkdir -p "$dir"
  window=$(echo "1.6 * 888 / $thrust / 24" | bc -l | xargs printf '%.1f')
  sed -e "s/a maximum thrust of 60 N/a maximum thrust of $thrust N/" \
    -e "s/The time of flight is free, at most 2 days./The time of flight is free, at most $window days./" \
    scenarios/S14/problem.txt >"$dir/problem.txt"
  grep -q "maximum thrust of $thrust N" "$dir/problem.txt"
  "$bin/helios-parse" "$dir/problem.txt" -o "$dir/spec.json"
  "$bin/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$bin/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
  t0=$(date +%s.%N)
  "$bin/helios-solve" "$dir/shoot.cpp" --settings "$work/settings.json" --time-limit 3100 --cache-dir "$dir/cache" \
    --plots "" --trajectory "$dir/trajectory.csv" -o "$dir/solution.json" 2>"$dir/stderr" || true
  wall=$(echo "$(date +%s.%N) - $t0" | bc -l)
  jq -r --arg T "$thrust" --arg wall "$wall" '
    (.search.returned // -1) as $k
    | [$T, .status, (.tof_days // 0) * 24,
       (if $k >= 0 then .search.extremals[$k].revolutions else 0 end), (.max_residual // 0),
       (.multiple_shooting.single_shooting_max_residual // .max_residual // 0), $wall,
       (if (.continuation // []) | any(.stage | startswith("maximum thrust"))
        then "thrust continuation from \(.continuation | map(select(.stage | startswith("raised thrust")))[-1].value | floor) N, \(.continuation | map(select(.stage | startswith("maximum thrust"))) | length) steps"
        else "the search" end)]
    | @tsv' "$dir/solution.json" | awk -F'\t' '{
      if ($2 == "converged") printf "%-8s %-12.7f %-10.2f %-8.2f %-10.2e %-10.2e %-8.1f %s\n", $1, $3, $3 * $1, $4, $5, $6, $7, $8
      else printf "%-8s %-12s %-10s %-8s %-10s %-10s %-8.1f %s\n", $1, $2, "-", "-", "-", "-", $7, $8 }'
done

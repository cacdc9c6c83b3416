#!/usr/bin/env bash
# The GTO -> GEO minimum-time family t_f(T_max): S14's problem text at 60, 20, 10, 5, 2, 1 and
# 0.5 N with the loose bound a user would write, "at most 100 days", at every thrust (the thrust
# and that sentence changed, nothing else), each cold from its own search with an empty compile
# cache and the default settings (only a seed). Prints per thrust t_f, the product t_f T (nearly
# constant at low thrust in the literature on this transfer), its change from the row above (the
# family must not get worse by more than 0.1 % toward the lower thrust unless the record shows
# why), the revolutions, max|F| (multiple shooting's where the polish kept it) and the
# single-shooting max|F| of the same point, the wall time, the t_f T of the branches the returned
# path reached at that thrust ("branches": its own / the next one's, thrust.hpp: past the thrust
# onto a cheaper branch below it, and back; "-" where none) and how the
# returned extremal was reached (the search itself, or the thrust continuation from the thrust it
# started at).
# usage: tests/bench/thrust_family.sh [THRUST_N...]   (run from the repository root; needs `make tools`)
set -euo pipefail
bin=build/bin
if (($# == 0)); then thrusts=(60 20 10 5 2 1 0.5); else thrusts=("$@"); fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo '{"seed": 1}' >"$work/settings.json"

printf '%-8s %-12s %-11s %-9s %-8s %-10s %-10s %-8s %-23s %s\n' "T [N]" "t_f [h]" "t_f T [N h]" "change" "revs" "max|F|" "SS max|F|" "wall [s]" "branches" "reached by"
previous=""
for thrust in "${thrusts[@]}"; do
  dir="$work/T$thrust"
  mkdir -p "$dir"
  sed -e "s/a maximum thrust of 60 N/a maximum thrust of $thrust N/" \
    -e "s/The time of flight is free, at most 2 days./The time of flight is free, at most 100 days./" \
    scenarios/S14/problem.txt >"$dir/problem.txt"
  grep -q "maximum thrust of $thrust N" "$dir/problem.txt"
  "$bin/helios-parse" "$dir/problem.txt" -o "$dir/spec.json"
  "$bin/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
  "$bin/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
  t0=$(date +%s.%N)
  "$bin/helios-solve" "$dir/shoot.cpp" --settings "$work/settings.json" --cache-dir "$dir/cache" \
    --plots "" --trajectory "$dir/trajectory.csv" -o "$dir/solution.json" 2>"$dir/stderr" || true
  wall=$(echo "$(date +%s.%N) - $t0" | bc -l)
  jq -r --arg T "$thrust" --arg wall "$wall" --arg previous "$previous" '
    (.search.returned // -1) as $k
    | [$T, .status, (.tof_days // 0) * 24,
       (if $k >= 0 then .search.extremals[$k].revolutions else 0 end), (.max_residual // 0),
       (.multiple_shooting.single_shooting_max_residual // .max_residual // 0), $wall,
       ([("maximum thrust [N], the final time'"'"'s window scaled inversely",
          "the next branch: maximum thrust [N] below and back") as $stage
         | [.continuation[]? | select(.stage == $stage and .converged and ((.value - ($T | tonumber)) | fabs) < 1e-9)
             | .tf_days * 24 * ($T | tonumber)] | last // null | if . == null then "-" else (. * 100 | round / 100 | tostring) end]
        | join("/")),
       (if $k < 0 then "-" elif .search.extremals[$k].route == "thrust continuation"
        then "thrust continuation from \(.continuation | map(select(.stage | startswith("raised thrust")))[-1].value | floor) N, \(.continuation | map(select(.stage | startswith("maximum thrust"))) | length) steps"
        else .search.extremals[$k].route end), $previous]
    | @tsv' "$dir/solution.json" | awk -F'\t' '{
      if ($2 == "converged") {
        change = $10 == "" ? "" : sprintf("%+.3f%%", 100 * ($3 * $1 / $10 - 1))
        printf "%-8s %-12.7f %-11.2f %-9s %-8.2f %-10.2e %-10.2e %-8.1f %-23s %s\n", $1, $3, $3 * $1, change, $4, $5, $6, $7, $8, $9
      } else printf "%-8s %-12s %-11s %-9s %-8s %-10s %-10s %-8.1f %-23s %s\n", $1, $2, "-", "-", "-", "-", "-", $7, $8, $9 }'
  previous=$(jq -r --arg T "$thrust" 'if .status == "converged" then (.tof_days * 24 * ($T | tonumber)) else "" end' "$dir/solution.json")
done

#!/usr/bin/env bash
# Minimum fuel at 1.5 t_min from the minimum time: S14's GTO -> GEO transfer with the fuel
# minimized in one and a half times the minimum time of the bench's thrust family (t_min(T) =
# 888.02 N h / T at 60 N; 846.2 N h / T at 20 and 10 N, measured by make bench-thrust), at 60, 20
# and 10 N, each cold from its own search, with the route from the minimum-time extremals off
# (search_fuel_from_time "never"), as the search decides ("auto") and always. Prints per thrust
# and setting the propellant, the revolutions, the minimum times the route reached (h) and the
# wall time. Less propellant than the minimum-time flight (Tmax/(Isp g0) t_min) is a check: the
# minimum-time flight is admissible at 1.5 t_min (it coasts on the final orbit).
# usage: tests/bench/fuel_from_time.sh [THRUST_N...]   (run from the repository root; needs `make tools`)
set -euo pipefail
bin=build/bin
if (($# == 0)); then thrusts=(60 20 10); else thrusts=("$@"); fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

printf '%-6s %-7s %-12s %-14s %-8s %-22s %s\n' "T [N]" "route" "tof [h]" "propellant [kg]" "revs" "t_min reached [h]" "wall [s]"
for thrust in "${thrusts[@]}"; do
  product=$([[ $thrust == 60 ]] && echo 888.02 || echo 846.2)
  tof_days=$(echo "1.5 * $product / $thrust / 24" | bc -l | xargs printf '%.9f')
  for route in never auto always; do
    dir="$work/T$thrust-$route"
    mkdir -p "$dir"
    sed -e "s/a maximum thrust of 60 N/a maximum thrust of $thrust N/" \
      -e "s/The time of flight is free, at most 2 days./The time of flight is $tof_days days./" \
      -e 's/Minimize the time of flight./Minimize the fuel consumption./' \
      scenarios/S14/problem.txt >"$dir/problem.txt"
    jq --arg route "$route" '.search_fuel_from_time = $route | .time_limit_s = 1200' scenarios/S14/settings.json \
      >"$dir/settings.json"
    "$bin/helios-parse" "$dir/problem.txt" -o "$dir/spec.json"
    "$bin/helios-derive" "$dir/spec.json" -o "$dir/derivation.json"
    "$bin/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp"
    t0=$(date +%s.%N)
    "$bin/helios-solve" "$dir/shoot.cpp" --settings "$dir/settings.json" --time-limit 1300 --cache-dir "$dir/cache" \
      --plots "" --trajectory "$dir/trajectory.csv" -o "$dir/solution.json" 2>"$dir/stderr" || true
    wall=$(echo "$(date +%s.%N) - $t0" | bc -l)
    jq -r --arg T "$thrust" --arg route "$route" --arg wall "$wall" --arg tof "$(echo "$tof_days * 24" | bc -l)" '
      (.search.returned // -1) as $k
      | [$T, $route, $tof, .status, (.propellant_kg // 0),
         (if $k >= 0 then .search.extremals[$k].revolutions else 0 end),
         ([.search.minimum_time_route.paths[]? | select(.minimum_tf_days != null) | .minimum_tf_days * 24 * 1000 | round / 1000]
          | unique | map(tostring) | join(" ")), $wall]
      | @tsv' "$dir/solution.json" | awk -F'\t' '{
        if ($4 == "converged") printf "%-6s %-7s %-12.4f %-14.3f %-8.2f %-22s %.1f\n", $1, $2, $3, $5, $6, ($7 == "" ? "-" : $7), $8
        else printf "%-6s %-7s %-12.4f %-14s %-8s %-22s %.1f\n", $1, $2, $3, $4, "-", ($7 == "" ? "-" : $7), $8 }'
  done
done

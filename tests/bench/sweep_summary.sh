#!/usr/bin/env bash
# sweep_summary.sh DIR WALL_S: one finished sweep folder's figures for make bench-sweep: the cells
# converged, infeasible and failed, how they started, the cross-check, the programs' summed run time
# against the wall time, and the compiles (solution.json files whose program was not in the cache).
set -euo pipefail
dir="$1" wall="$2"
echo "  cells: $(tail -n +2 "$dir/sweep.csv" | cut -d, -f4 | sed 's/^\(not_converged\|crashed\|timeout\|missing\)$/failed (&)/' | sort | uniq -c | awk '{ $1 = $1; print }' | paste -sd, | sed 's/,/, /g')"
echo "  starts: $(tail -n +2 "$dir/sweep.csv" | cut -d, -f7 | grep . | sort | uniq -c | awk '{ $1 = $1; print }' | paste -sd, | sed 's/,/, /g')"
jq -r '"  cross-check: \(.rounds) rounds, \(.runs) warm solves (\(.reused) reused), \(.improved | length) cells improved\(if (.improved | length) > 0 then ": " + (.improved | join(" ")) else "" end)"' "$dir/crosscheck.json"
# Every program of the sweep: the boundaries, the cells and the cross-check's tries.
find "$dir" -name solution.json -print0 | xargs -0 jq -s --argjson wall "$wall" -r '
  (map(.timings.run_s) | add) as $run | (map(.timings.compile_s) | add) as $compile
  | "  programs: \(length) runs, \($run * 10 | round / 10) s of run time; wall / run time = \($wall / $run * 100 | round / 100); " +
    "compiles: \(map(select(.compile.cached | not)) | length) (\($compile * 10 | round / 10) s)"'
awk -F, 'NR > 1 && $10 != "" && !seen[$1]++ { printf "%s%s:%s%s", (n++ ? ", " : "  boundary t_min [d]: "), $1, $10, ($11 == "true" ? "" : " (not saturated)") } END { if (n) print "" }' "$dir/sweep.csv"

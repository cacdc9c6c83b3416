#!/usr/bin/env bash
# Benchmark of the builtin backend, from a cold start (fresh output folder, empty compile cache):
# per scenario the wall time of each stage, the solve's cost against its integrations (compile,
# run, Jacobian and residual evaluations, integrations per second, run time over integration
# time, and the run with finite-difference Jacobians instead of exact ones), the global search's cost (starts or attempts, distinct
# extremals at eps = 0, its wall time), legs solved alone (problems with interior events: every
# leg attempt before the legs were joined), homotopy steps of the returned solution, passes over
# the bounds, and the result; then a warm solve of the first scenario (compile cache hit), for the
# J2 scenarios the m_f of the same problem without J2 (the J2 sentence removed), and S13's search
# over seeds 1-5 (median cold solve; target <= 60 s on 2 cores), with the start strategies
# compared at equal cost (tests/bench/search_methods.cpp).
# usage: tests/bench/bench.sh [SCENARIO...]   (default: every scenario; run from the repository root; needs `make tools`)
set -euo pipefail
bin=build/bin
if (($# == 0)); then
  mapfile -t scenarios < <(ls scenarios | grep -E '^S[0-9]+$')
else
  scenarios=("$@")
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
# seconds CMD...: runs CMD, prints its wall time in seconds
seconds() {
  local t0
  t0=$(now)
  "$@"
  echo "$(now) - $t0" | bc -l
}
ratio() { echo "$1 / $2" | bc -l; }

# chain DIR PROBLEM SETTINGS: parse, derive, verify, gen, cold solve; sets the stage times t_*
chain() {
  local dir=$1 problem=$2 settings=$3
  mkdir -p "$dir"
  t_parse=$(seconds "$bin/helios-parse" "$problem" -o "$dir/spec.json")
  t_derive=$(seconds "$bin/helios-derive" "$dir/spec.json" -o "$dir/derivation.json")
  t_verify=$(seconds "$bin/helios-verify" --advisory "$dir/derivation.json" -o "$dir/verify.json")
  t_gen=$(seconds "$bin/helios-gen" "$dir/derivation.json" -o "$dir/shoot.cpp")
  t_solve=$(seconds "$bin/helios-solve" --quiet "$dir/shoot.cpp" --settings "$settings" --cache-dir "$dir/cache" \
    --trajectory "$dir/trajectory.csv" -o "$dir/solution.json")
}

echo "HELIOS benchmark, builtin backend, $(nproc) cores, $(date -u +%FT%TZ)"
printf '%-5s %7s %7s %7s %7s %8s %8s %8s %6s %4s %8s %5s %5s %4s  %-13s %s\n' scen parse derive verify gen compile run solve \
  starts ext search_s legs homot pass status result
for s in "${scenarios[@]}"; do
  chain "$work/$s" "scenarios/$s/problem.txt" "scenarios/$s/settings.json"
  "$bin/helios-score" --reference "scenarios/$s/reference.json" --spec "$work/$s/spec.json" \
    --derivation "$work/$s/derivation.json" --verify "$work/$s/verify.json" --solution "$work/$s/solution.json" \
    -o "$work/$s/score.json"
  printf '%-5s %7.3f %7.3f %7.3f %7.3f %8.3f %8.3f %8.3f %6s %4s %8.3f %5s %5s %4s  %-13s %s\n' "$s" "$t_parse" "$t_derive" \
    "$t_verify" "$t_gen" "$(jq .timings.compile_s "$work/$s/solution.json")" "$(jq .timings.run_s "$work/$s/solution.json")" \
    "$t_solve" "$(jq '.search.starts // "-"' "$work/$s/solution.json")" "$(jq '.search.extremals // [] | length' "$work/$s/solution.json")" \
    "$(jq '.search.seconds // 0' "$work/$s/solution.json")" "$(jq '.legs // [] | length' "$work/$s/solution.json")" \
    "$(jq '.homotopy | length' "$work/$s/solution.json")" "$(jq '.passes // 1' "$work/$s/solution.json")" \
    "$(jq -r .status "$work/$s/solution.json")" \
    "$(jq -r 'if .final_mass_kg then "m0 \(.initial_mass_kg) kg, m_f \(.final_mass_kg) kg" else "tof \(.tof_days) d" end + ", max|F| \(.max_residual) (noise \(.residual_noise))"' \
      "$work/$s/solution.json"), verify $(jq -r .verdict "$work/$s/verify.json"), score $(jq .total "$work/$s/score.json")"
  # The solve's cost against its integrations (solution.json's "integration", the runtime's
  # counters): the exact Jacobians, the finite-difference ones (the homotopies without an exact
  # Jacobian; n residual evaluations each), the integrations per second of integration time, and
  # the program's wall time over that time (1 is the floor: a solve that does nothing but
  # integrate; with several search threads the summed integration time can exceed the wall time,
  # so the ratio can fall below 1).
  sol="$work/$s/solution.json"
  printf '      compile %.3f s, run %.3f s; Jacobian %s: %s exact, %s finite-difference (%s of the %s residual evaluations); %s integrations, %.1f per s; run / integrations %.3f\n' \
    "$(jq .timings.compile_s "$sol")" "$(jq .timings.run_s "$sol")" "$(jq -r '.integration.jacobian // "-"' "$sol")" \
    "$(jq '.integration.exact_jacobian_evaluations // 0' "$sol")" \
    "$(jq '.integration.jacobian_evaluations // 0' "$sol")" "$(jq '.integration.jacobian_residual_evaluations // 0' "$sol")" \
    "$(jq '.integration.residual_evaluations // 0' "$sol")" "$(jq '.integration.integrations // 0' "$sol")" \
    "$(jq '(.integration.integrations // 0) / ([.integration.integration_s // 0, 1e-9] | max)' "$sol")" \
    "$(jq '.timings.run_s / ([.integration.integration_s // 0, 1e-9] | max)' "$sol")"
  # The same program with hybrd's finite differences everywhere (settings jacobian =
  # finite-difference; a compile cache hit): the exact Jacobian's gain, measured in the same run.
  jq '. + {jacobian: "finite-difference"}' "scenarios/$s/settings.json" >"$work/$s/settings-fd.json"
  "$bin/helios-solve" --quiet "$work/$s/shoot.cpp" --settings "$work/$s/settings-fd.json" --cache-dir "$work/$s/cache" \
    --plots "" --trajectory "$work/$s/trajectory-fd.csv" -o "$work/$s/solution-fd.json"
  fd="$work/$s/solution-fd.json"
  printf '      finite-difference: run %.3f s (exact / finite-difference %.3f), %s, max|F| %s, objective difference %s relative\n' \
    "$(jq .timings.run_s "$fd")" "$(ratio "$(jq .timings.run_s "$sol")" "$(jq .timings.run_s "$fd")")" \
    "$(jq -r .status "$fd")" "$(jq -r .max_residual "$fd")" \
    "$(jq -n --slurpfile a "$sol" --slurpfile b "$fd" '[("initial_mass_kg", "final_mass_kg", "tof_days") as $k |
       select($a[0][$k] and $b[0][$k]) | (($a[0][$k] - $b[0][$k]) / $a[0][$k] | fabs)] | max // "-"')"
  front=$(echo "$t_parse + $t_derive + $t_verify" | bc -l)
  printf '      parse+derive+verify %.3f s (target < 1 s: ratio %.3f); verify %.3f s (target < 1 s: ratio %.3f); solve cold %.3f s (target < 30 s: ratio %.3f)\n' \
    "$front" "$(ratio "$front" 1)" "$t_verify" "$(ratio "$t_verify" 1)" "$t_solve" "$(ratio "$t_solve" 30)"
done

first=${scenarios[0]}
t_warm=$(seconds "$bin/helios-solve" --quiet "$work/$first/shoot.cpp" --settings "scenarios/$first/settings.json" \
  --cache-dir "$work/$first/cache" --trajectory "$work/$first/trajectory2.csv" -o "$work/$first/solution2.json")
printf 'warm solve of %s (cached binary): %.3f s\n' "$first" "$t_warm"

# J2 on/off: the same problem text without the sentence that adds J2.
for s in "${scenarios[@]}"; do
  grep -q "include the J2 perturbation" "scenarios/$s/problem.txt" || continue
  grep -v "include the J2 perturbation" "scenarios/$s/problem.txt" > "$work/$s-noJ2.txt"
  chain "$work/$s-noJ2" "$work/$s-noJ2.txt" "scenarios/$s/settings.json"
  jq -rn --slurpfile on "$work/$s/solution.json" --slurpfile off "$work/$s-noJ2/solution.json" --arg s "$s" \
    '"\($s) J2 on: m_f \($on[0].final_mass_kg) kg, J2 off: \($off[0].final_mass_kg) kg (\($off[0].status)), difference \(($on[0].final_mass_kg - $off[0].final_mass_kg) * 1000) g"'
done

# S13: the search over seeds 1-5, each a cold solve (its own empty compile cache), and the start
# strategies at equal cost.
if [[ " ${scenarios[*]} " == *" S13 "* ]]; then
  times=()
  for seed in 1 2 3 4 5; do
    jq ".seed = $seed" scenarios/S13/settings.json >"$work/S13-seed$seed.json"
    rm -rf "$work/S13/cache-seed"
    t=$(seconds "$bin/helios-solve" --quiet "$work/S13/shoot.cpp" --settings "$work/S13-seed$seed.json" \
      --cache-dir "$work/S13/cache-seed" --trajectory "$work/S13/trajectory-seed.csv" -o "$work/S13/solution-seed$seed.json")
    times+=("$t")
    jq -r --arg seed "$seed" --arg t "$t" '"S13 seed \($seed): m_f \(.final_mass_kg) kg, max|F| \(.max_residual), \(.search.starts) starts, \(.search.extremals | length) extremals at eps = 0 (\([.search.extremals[].propellant_kg | . * 1000 | round / 1000])) kg of propellant, cold solve \($t) s"' \
      "$work/S13/solution-seed$seed.json"
  done
  median=$(printf '%s\n' "${times[@]}" | sort -g | sed -n 3p)
  printf 'S13 median cold solve over seeds 1-5: %.3f s (target <= 60 s: ratio %.3f)\n' "$median" "$(ratio "$median" 60)"
  g++ -std=c++17 -O2 -fno-math-errno -pthread -DSHOOT_CPP="\"$work/S13/shoot.cpp\"" -Itemplates/runtime -Itools/lib/include \
    tests/bench/search_methods.cpp -o "$work/search_methods" -lcminpack
  "$work/search_methods" 10 6000
fi

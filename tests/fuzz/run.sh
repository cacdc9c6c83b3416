#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time (make fuzz runs each of them).
# usage: tests/fuzz/run.sh BUILD_DIR TARGET SECONDS MAX_LEN DICT SEED...
# The corpus grows in BUILD_DIR/corpus/TARGET (the seeds copied in first), findings go to
# BUILD_DIR/findings/TARGET/ and the fuzzer's output to BUILD_DIR/TARGET.log. Prints the run's
# executions, coverage and findings in one line; exits 1 when there is any finding.
set -uo pipefail
build=$1 target=$2 seconds=$3 max_len=$4 dict=$5
shift 5
corpus=$build/corpus/$target findings=$build/findings/$target log=$build/$target.log
mkdir -p "$corpus" "$findings"
for seed in "$@"; do
  if [[ -d $seed ]]; then cp -n "$seed"/* "$corpus"/ 2>/dev/null || true; else cp "$seed" "$corpus/seed-$(echo "$seed" | tr / _)"; fi
done
"$build/bin/fuzz-$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" \
  -dict="$dict" -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1
status=$?
execs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$log" | tail -1)
last=$(grep -E '^#[0-9]+' "$log" | tail -1)
cov=$(sed -nE 's/.* cov: ([0-9]+) ft: ([0-9]+).*/cov \1 ft \2/p' <<<"$last")
count=$(find "$findings" -type f | wc -l)
echo "fuzz $target: ${seconds} s, ${execs:-?} executions, ${cov:-coverage ?}, corpus $(find "$corpus" -type f | wc -l), $count finding(s)"
if ((count > 0 || status != 0)); then
  echo "fuzz $target: exit $status, findings in $findings/ (log $log):" >&2
  grep -E '^(==[0-9]+==ERROR|FUZZ FINDING|SUMMARY|.*runtime error)' "$log" | head -5 >&2
  exit 1
fi

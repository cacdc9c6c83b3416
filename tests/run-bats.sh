#!/usr/bin/env bash
# Runs the Bats suite and closes with one 'N passed, N failed' line.
set -uo pipefail
log=$(mktemp)
trap 'rm -f "$log"' EXIT
bats --formatter tap "$@" | tee "$log"
status=${PIPESTATUS[0]}
passed=$(grep -c '^ok ' "$log" || true)
failed=$(grep -c '^not ok ' "$log" || true)
echo "bats: $passed passed, $failed failed"
exit "$status"

#!/usr/bin/env bash
# Runs the Bats suite and closes with one 'N passed, N failed' line. The files run BATS_JOBS (2) at
# a time, each file's tests in order (bats --jobs, which needs GNU parallel; without it, one at a
# time): the files share nothing but the built tools.
set -uo pipefail
log=$(mktemp)
trap 'rm -f "$log"' EXIT
jobs=()
if [[ ${BATS_JOBS:-2} -gt 1 ]] && parallel --version 2>/dev/null | grep -q GNU; then
  jobs=(--jobs "${BATS_JOBS:-2}" --no-parallelize-within-files)
fi
bats --formatter tap "${jobs[@]}" "$@" | tee "$log"
status=${PIPESTATUS[0]}
passed=$(grep -c '^ok ' "$log" || true)
failed=$(grep -c '^not ok ' "$log" || true)
echo "bats: $passed passed, $failed failed"
exit "$status"

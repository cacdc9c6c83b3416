#!/usr/bin/env bash
# After make test-sanitized: every sanitized process wrote its sanitizer report to DIR/report.<pid>
# (ASAN_OPTIONS=log_path). The one accepted content is LSan's table of the suppression used,
# CLN's single allocation of 26 bytes (tests/sanitize/lsan.supp); any other line is a finding, or
# a suppression that hid more than that leak. Prints each such report; exits 1 when there is one.
# usage: tests/sanitize/check-logs.sh DIR
set -uo pipefail
dir=$1
bad=0 reports=0
for f in "$dir"/report.*; do
  [[ -e $f ]] || continue
  reports=$((reports + 1))
  if grep -v -x -E -e '-+' -e 'Suppressions used:' -e ' +count +bytes +template' -e ' +1 +26 +libcln\.so' -e '' \
    "$f" >/dev/null; then
    echo "sanitizer report $f:" >&2
    cat "$f" >&2
    bad=$((bad + 1))
  fi
done
echo "sanitizer reports: $reports processes, $bad with findings"
((bad == 0))

#!/usr/bin/env bats
# tools/install-deps.sh against a fake apt-get and id on a PATH of its own: the tools it probes as
# commands (g++, cmake, ...) are not on that PATH, so it installs them. Nothing is installed.

load test_helper

setup() {
  common_setup
  FAKE="$BATS_TEST_TMPDIR/bin"
  mkdir -p "$FAKE"
  local cmd
  for cmd in bash cat grep mktemp rm sleep; do ln -s "$(command -v "$cmd")" "$FAKE/$cmd"; done
  # id -u: FAKE_UID. apt-get: logs its arguments; FAKE_APT_UPDATE_LOCKS=N fails the first N updates
  # on a held lock, FAKE_APT_INSTALL=lock fails an install on the dpkg lock (apt's exit 100).
  printf '#!%s\necho "${FAKE_UID:-0}"\n' "$(command -v bash)" >"$FAKE/id"
  cat >"$FAKE/apt-get" <<APT
#!$(command -v bash)
echo "\$*" >>"$BATS_TEST_TMPDIR/apt.log"
if [[ " \$* " == *" update "* ]]; then
  n=\$(grep -c ' update ' "$BATS_TEST_TMPDIR/apt.log")
  if ((n <= \${FAKE_APT_UPDATE_LOCKS:-0})); then
    echo "E: Could not get lock /var/lib/apt/lists/lock. It is held by process 1 (apt-get)" >&2
    exit 100
  fi
  exit 0
fi
if [[ \${FAKE_APT_INSTALL:-} == lock ]]; then
  echo "E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by process 1 (apt-get)" >&2
  exit 100
fi
exit 0
APT
  chmod +x "$FAKE/id" "$FAKE/apt-get"
}

deps() {
  PATH="$FAKE" "$ROOT/tools/install-deps.sh" "$@"
}

# The one error line: stderr has exactly one "install-deps: error: " line, and it is the last.
assert_one_deps_error() {
  local errors
  errors=$(grep -c '^install-deps: error: ' <<<"$stderr" || true)
  ((errors == 1)) || { echo "expected one error line, got $errors: $stderr" >&2; return 1; }
  [[ ${stderr_lines[-1]} == "install-deps: error: "* ]] || { echo "the error is not the last line: $stderr" >&2; return 1; }
}

@test "install-deps: a failed install exits 1 with one error line, and every apt-get waits for the lock" {
  FAKE_APT_INSTALL=lock run -1 --separate-stderr deps
  assert_one_deps_error
  assert_stderr_contains "Could not get lock /var/lib/dpkg/lock-frontend" "apt-get install failed (exit 100)" \
    "(to install: g++ cmake "
  [[ -z $output ]]
  local calls
  calls=$(wc -l <apt.log)
  ((calls == 2)) || { cat apt.log >&2; false; }
  ! grep -v -- '-o DPkg::Lock::Timeout=600 ' apt.log || { echo "an apt-get call without the lock timeout" >&2; false; }
}

@test "install-deps: an update on a held lock is retried; packages still missing after apt-get are an error" {
  FAKE_APT_UPDATE_LOCKS=1 run -1 --separate-stderr deps
  [[ $(grep -c ' update ' apt.log) == 2 ]] || { cat apt.log >&2; false; }
  assert_one_deps_error
  assert_stderr_contains "after apt-get, still missing: g++ cmake"
}

@test "install-deps: not root, it names the command to run and installs nothing" {
  FAKE_UID=1000 run -1 --separate-stderr deps --slurm
  assert_one_deps_error
  assert_stderr_contains "run: sudo apt-get install g++ cmake"
  [[ ! -e apt.log ]]
}

@test "install-deps: make stops when install-deps fails, before it builds or runs anything" {
  local cmd
  for cmd in env make find seq; do ln -s "$(command -v "$cmd")" "$FAKE/$cmd"; done
  FAKE_APT_INSTALL=lock PATH="$FAKE" run -2 --separate-stderr \
    unnested_make scenario=S01 RUNS_ROOT="$BATS_TEST_TMPDIR/runs"
  [[ ${stderr_lines[-2]} == "install-deps: error: apt-get install failed (exit 100)"* ]] || { echo "$stderr" >&2; false; }
  [[ ${stderr_lines[-1]} == "make: *** ["*": deps] Error 1" ]] || { echo "$stderr" >&2; false; }
  [[ -z $output && ! -e $BATS_TEST_TMPDIR/runs ]]
}

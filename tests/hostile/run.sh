#!/usr/bin/env bash
# The hostile-input corpus: malformed, hostile and absurd inputs for every tool, generated here
# (deterministically: the large ones are built by a recipe, nothing big is checked in) and run
# one by one. Each case states the exit code it must give and a pattern its error must match;
# every case must also
#   - finish within 60 s (a hang is a failure) and end by exit, not by a signal;
#   - print, when it fails, exactly one line on stderr, "helios-TOOL: error: ...", with no
#     control byte in it;
#   - leave no file but its output (written only on success, or with exit 4 the report of the
#     failed check) in its folder or in TMPDIR;
#   - leave an output that is not a regular file (a FIFO, a device) the node it was.
# usage: tests/hostile/run.sh BIN_DIR WORK_DIR   (prints the outcome table; exit 1 on a failure)
set -uo pipefail
BIN=$(cd "$1" && pwd)
WORK=$2
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)

failures=0
declare -A outcome  # "tool exit" -> count
total=0

# Base artifacts of S01, which the JSON cases mutate.
BASE=$WORK/base
mkdir -p "$BASE"
"$BIN/helios-parse" "$ROOT/scenarios/S01/problem.txt" -o "$BASE/spec.json"
"$BIN/helios-derive" "$BASE/spec.json" -o "$BASE/derivation.json"
"$BIN/helios-parse" "$ROOT/scenarios/S12/problem.txt" -o "$BASE/s12-spec.json"
cp "$ROOT/scenarios/S01/settings.json" "$BASE/settings.json"
cp "$ROOT/scenarios/S01/problem.txt" "$BASE/problem.txt"

CASE=""
# case ID: starts case ID in its own folder (the working directory until the next case).
case_dir() {
  CASE=$1
  mkdir -p "$WORK/cases/$CASE/tmp"
  cd "$WORK/cases/$CASE" || exit 1
}

# The files (and FIFOs, devices) of the case's folder, but its TMPDIR and the tool's captured output.
case_files() { find . -path ./tmp -prune -o ! -type d -print | grep -v -e '^./stdout.log$' -e '^./stderr.log$' | sort; }
# The node ./out is (its links followed): kind, inode and device numbers; empty when it is none.
out_node() { stat -L -c '%F %i %t:%T' out 2>/dev/null; }

# expect EXIT PATTERN TOOL ARGS...: runs helios-TOOL ARGS -o out (in the case's folder) and
# checks the rules above; PATTERN (grep -E) must match the error line (ignored for exit 0).
expect() {
  local want=$1 pattern=$2 tool=$3
  shift 3
  local before expected after rc line lines node=""
  before=$(case_files)
  [[ -e out && ! -f out ]] && node=$(out_node)
  TMPDIR=$PWD/tmp timeout -s KILL 60 "$BIN/helios-$tool" "$@" -o out >stdout.log 2>stderr.log
  rc=$?
  total=$((total + 1))
  outcome["$tool $rc"]=$((${outcome["$tool $rc"]:-0} + 1))
  local why=""
  if [[ $rc -ge 128 ]]; then
    why="killed by signal $((rc - 128))"
  elif [[ $rc -ne $want ]]; then
    why="exit $rc, expected $want"
  fi
  if [[ -z $why && $rc -ne 0 ]]; then
    lines=$(wc -l <stderr.log)
    line=$(head -n 1 stderr.log)
    if [[ $lines -ne 1 ]]; then
      why="$lines lines on stderr"
    elif [[ $line != "helios-$tool: error: "* ]]; then
      why="error line does not start with 'helios-$tool: error: '"
    elif LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' stderr.log || [[ $(tr -d '\000' <stderr.log | wc -c) -ne $(wc -c <stderr.log) ]]; then
      why="control byte on stderr"
    elif ! grep -Eq -- "$pattern" stderr.log; then
      why="error does not match /$pattern/"
    fi
  fi
  after=$(case_files)
  expected=$before
  # Exit 4 (a check failed) writes the artifact saying why, as success does.
  [[ $rc -eq 0 || $rc -eq 4 ]] && expected=$(printf '%s\n./out\n' "$before" | sed '/^$/d' | sort -u)
  if [[ -z $why && -n $node && $(out_node) != "$node" ]]; then
    why="the output ./out ($node) was replaced: $(out_node)"
  fi
  if [[ -z $why && "$after" != "$expected" ]]; then
    why="files changed: $(diff <(printf '%s\n' "$expected") <(printf '%s\n' "$after") | grep '^[<>]' | tr '\n' ' ')"
  fi
  if [[ -z $why && -n $(ls -A tmp) ]]; then why="left files in TMPDIR: $(ls -A tmp | tr '\n' ' ')"; fi
  if [[ -n $why ]]; then
    failures=$((failures + 1))
    echo "FAIL $CASE (helios-$tool): $why"
    head -c 400 stderr.log | cat -v | sed 's/^/    stderr: /'
  fi
}

# stream_case KIND EXIT PATTERN TOOL ARGS...: expect with ./out a FIFO (KIND fifo, read by cat,
# which must receive the output) or a private character device like /dev/null (KIND device, made by
# mknod; root only, else the case is skipped).
stream_case() {
  local kind=$1 reader=""
  shift
  if [[ $kind == device ]]; then
    [[ $EUID -eq 0 ]] || return 0
    mknod out c 1 3
  else
    mkfifo out
    mkdir -p "$WORK/streams"
    timeout 20 cat out >"$WORK/streams/$CASE" &
    reader=$!
  fi
  expect "$@"
  [[ -z $reader ]] || holds "the FIFO's reader received the output" eval "wait $reader && [[ -s $WORK/streams/$CASE ]]"
}

# holds WHAT COMMAND...: after an expect, COMMAND (in the case's folder) must succeed; else the case
# fails saying WHAT did not hold.
holds() {
  local what=$1
  shift
  if ! "$@" >/dev/null 2>&1; then
    failures=$((failures + 1))
    echo "FAIL $CASE: not so: $what"
  fi
}

# Text and JSON helpers.
s01_text() { cat "$BASE/problem.txt"; }
# with_sentence TEXT: S01's problem with TEXT in place of its objective sentence.
with_sentence() { grep -v '^Minimize' "$BASE/problem.txt"; printf '%s\n' "$1"; }
# jq_spec [JQ OPTIONS] FILTER (also jq_derivation, jq_settings): a mutated base artifact on stdout.
jq_spec() { jq "$@" "$BASE/spec.json"; }
jq_derivation() { jq "$@" "$BASE/derivation.json"; }
jq_settings() { jq "$@" "$BASE/settings.json"; }
nested() { printf "%${1}s" | tr ' ' '['; printf "%${1}s" | tr ' ' ']'; }

source "$ROOT/tests/hostile/cases.sh"

cd "$WORK" || exit 1
echo
echo "hostile corpus: $total cases, $failures failed"
echo "| tool | exit 0 | exit 1 | exit 2 | exit 3 | exit 4 | other |"
echo "|---|---|---|---|---|---|---|"
for tool in parse derive verify gen solve score; do
  other=0
  for key in "${!outcome[@]}"; do
    [[ ${key% *} == "$tool" && ! ${key#* } =~ ^[0-4]$ ]] && other=$((other + outcome[$key]))
  done
  echo "| helios-$tool | ${outcome["$tool 0"]:-0} | ${outcome["$tool 1"]:-0} | ${outcome["$tool 2"]:-0} | ${outcome["$tool 3"]:-0} | ${outcome["$tool 4"]:-0} | $other |"
done
[[ $failures -eq 0 ]]

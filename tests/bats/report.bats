#!/usr/bin/env bats
# helios-score --report: a run's artifacts -> report.md, the derivation as LaTeX mathematics.
# Every scenario's report has its mathematics compiled by a real TeX engine (pdflatex, from
# tests/report/latex_document.awk's standalone document), so a broken formula fails here. Only
# parse, derive and verify run (a few seconds per scenario); the solution part uses the OEM
# fixture's S08 solution.

load test_helper

LATEX_DOCUMENT="$ROOT/tests/report/latex_document.awk"

setup() {
  common_setup
  require_tool parse derive verify score
  command -v pdflatex >/dev/null || { echo "pdflatex missing: run tools/install-deps.sh (texlive-latex-base)" >&2; return 1; }
}

# derived S DIR: DIR/{spec,derivation,verify}.json of scenario S.
derived() {
  mkdir -p "$2"
  "$BIN/helios-parse" "$ROOT/scenarios/$1/problem.txt" -o "$2/spec.json"
  "$BIN/helios-derive" "$2/spec.json" -o "$2/derivation.json"
  "$BIN/helios-verify" "$2/derivation.json" -o "$2/verify.json"
}

# report S DIR [ARGS...]: DIR/report.md of scenario S from DIR's artifacts.
report() {
  local s="$1" dir="$2"
  shift 2
  "$BIN/helios-score" --report --problem "$ROOT/scenarios/$s/problem.txt" --spec "$dir/spec.json" \
    --derivation "$dir/derivation.json" --verify "$dir/verify.json" "$@" -o "$dir/report.md"
}

# compiles MD: the mathematics of MD compiles with pdflatex -halt-on-error (the log on failure).
# The document is data: no shell escape, no file read or written outside its folder (TeX's
# paranoid openin_any/openout_any), and a minute at most.
compiles() {
  local md="$1" tex="${1%.md}.tex"
  awk -f "$LATEX_DOCUMENT" "$md" >"$tex"
  (cd "$(dirname "$tex")" && openin_any=p openout_any=p timeout 60 pdflatex -no-shell-escape -interaction=nonstopmode \
    -halt-on-error "$(basename "$tex")" >/dev/null 2>&1) || {
    grep -A3 '^!' "${tex%.tex}.log" >&2
    return 1
  }
}

@test "report: every scenario's report compiles with pdflatex, and has every section" {
  local s n=0
  for s in $(cd "$ROOT/scenarios" && ls -d S[0-9]*); do
    derived "$s" "$s"
    report "$s" "$s"
    compiles "$s/report.md" || { echo "$s: the LaTeX of report.md does not compile" >&2; return 1; }
    local section
    for section in '## The problem' '## Specification' '### Hamiltonian' '### State equations' '### Costate equations' \
      '### Optimal control' '### Boundary conditions and transversality' '### Shooting variables and equations' \
      '## Verification'; do
      grep -qF "$section" "$s/report.md" || { echo "$s: no '$section'" >&2; return 1; }
    done
    # One display block per shooting equation.
    [[ $(grep -c '^F_{[0-9]*} = \|^F_{[0-9]*} ={}' "$s/report.md") -eq $(jq '.shooting.equations | length' "$s/derivation.json") ]] \
      || { echo "$s: not one F_k per shooting equation" >&2; return 1; }
    n=$((n + 1))
  done
  [[ $n -ge 13 ]]
}

@test "report: a broken formula fails the LaTeX check (the check can fail)" {
  derived S01 r
  report S01 r
  compiles r/report.md
  # An unbalanced brace in the first formula with a fraction.
  awk '/\\frac\{/ && !done { sub(/\\frac\{/, "\\frac{{"); done = 1 } { print }' r/report.md >r/broken.md
  run cmp -s r/report.md r/broken.md
  [[ $status -eq 1 ]]
  run compiles r/broken.md
  [[ $status -ne 0 ]]
}

@test "report: S10's periapsis row is typeset in a tenth of its stored length, its norms named" {
  derived S10 r
  report S10 r
  local stored typeset
  stored=$(jq -r '.events[0].psi[5]' r/derivation.json | wc -c)
  # The display block of psi_6 in the section of the event mars (the periapsis condition).
  awk '/^#### mars /{ e = 1 } e && /^\\psi_\{6\} /{ p = 1 } p && /^\$\$$/{ exit } p' r/report.md >psi6.tex
  typeset=$(wc -c <psi6.tex)
  [[ $stored -gt 5000 && $typeset -gt 100 && $typeset -lt $((stored / 10)) ]] || { echo "stored $stored, typeset $typeset" >&2; false; }
  grep -qF 'rmin' psi6.tex
  grep -qF '### Named quantities' r/report.md
  grep -qF 'r = \sqrt{r_{x}^{2} + r_{y}^{2} + r_{z}^{2}}' r/report.md
}

@test "report: the same artifacts give the same bytes" {
  # GiNaC's term order follows memory addresses, which change from process to process: S05's and
  # S06's costate rows (J2) were grouped differently in 2 of 5 runs before factors were expanded.
  local s i
  for s in S05 S06 S10; do
    derived "$s" "$s"
    report "$s" "$s"
    cp "$s/report.md" "$s/first.md"
    for i in 1 2 3 4 5; do
      report "$s" "$s"
      cmp "$s/first.md" "$s/report.md" || { echo "$s: run $i differs" >&2; return 1; }
    done
  done
}

@test "report: a failed check of verify stands beside the condition it concerns" {
  derived S01 r
  jq '(.checks[] | select(.id == "hamiltonian")) |= (.verdict = "fail" | .feedback = "H differs at 3 of 25 points")
      | .verdict = "fail"' r/verify.json >r/failed.json
  mv r/failed.json r/verify.json
  report S01 r
  awk '/^### Hamiltonian/ { h = 1 } h && /^### State equations/ { exit } h' r/report.md >hamiltonian.md
  grep -qF '`hamiltonian` **fail**' hamiltonian.md
  grep -qF 'H differs at 3 of 25 points' hamiltonian.md
  grep -qF 'verification **fail**' r/report.md
}

@test "report: with a solution, its table, switches and plots; without, it says so" {
  local fixtures="$ROOT/tests/fixtures/oem"
  mkdir r
  cp "$fixtures/spec.json" r/
  "$BIN/helios-derive" r/spec.json -o r/derivation.json
  "$BIN/helios-verify" r/derivation.json -o r/verify.json
  jq '.files = {"trajectory": "trajectory.csv", "trajectory_plot": "trajectory.png"}' "$fixtures/solution.json" >r/solution.json
  report S08 r --solution r/solution.json
  grep -qF '## Solution (solution.json)' r/report.md
  grep -qF '| `final_mass_kg` | 1500' r/report.md
  grep -qF '### Switches' r/report.md
  grep -qF '![trajectory\_plot](trajectory.png)' r/report.md
  run grep -cF '](trajectory.csv)' r/report.md
  [[ $output == 0 ]]
  compiles r/report.md
  report S08 r
  grep -qF 'not solved (no solution.json given)' r/report.md
}

@test "report: usage and input errors -> exit 2 / 3, one line, nothing written" {
  derived S01 r
  run -2 --separate-stderr "$BIN/helios-score" --report --spec r/spec.json --derivation r/derivation.json -o out.md
  assert_one_error_line score
  [[ $stderr == *"--report needs --problem"* ]]
  run -2 --separate-stderr "$BIN/helios-score" --problem "$S01/problem.txt" --reference "$S01/reference.json" -o out.md
  [[ $stderr == *"--problem goes with --report"* ]]
  run -3 --separate-stderr "$BIN/helios-score" --report --problem "$S01/problem.txt" --spec r/spec.json \
    --derivation r/missing.json -o out.md
  assert_one_error_line score
  [[ $stderr == *"r/missing.json"* ]]
  [[ ! -e out.md ]]
}

@test "report: hostile strings in the artifacts stay text: no math, TeX, HTML or link is made of them" {
  local fixtures="$ROOT/tests/fixtures/oem"
  local evil='3 $\input{/etc/hostname}$ <script>alert(1)</script> `x` [a](http://e) |'
  mkdir r
  cp "$fixtures/spec.json" r/
  "$BIN/helios-derive" r/spec.json -o r/derivation.json
  "$BIN/helios-verify" r/derivation.json -o r/verify.json
  jq --arg e "$evil" '.checks[0].verdict = "fail" | .checks[0].id = $e | .checks[0].feedback = ($e + "\n# heading")' r/verify.json >r/v.json
  mv r/v.json r/verify.json
  # The keys the report prints as numbers are numbers by the schema: a string there is refused.
  jq --arg e "$evil" '.homotopy = [{"eps": 0, "converged": true, "evaluations": $e}]' "$fixtures/solution.json" >r/solution.json
  run -3 --separate-stderr report S08 r --solution r/solution.json
  [[ $stderr == *"r/solution.json: solution schema violation at /homotopy/0/evaluations"* ]]
  jq --arg e "$evil" '.method = $e | .timings[$e] = 1
    | .search = {"method": $e, "threads": 1, "starts": 2, "converged_at_eps_start": 1, "continued": 1,
                 "converged_at_eps_0": 1, "seconds": 1, "cut_by_time": false, "saturated": false, "stopped": $e,
                 "reason": $e, "extremals_at_eps_start": [], "extremals": [],
                 "family": [{"from": 0, "direction": 1, "revolutions": 2, "how": $e}]}
    | .files = {"trajectory_plot": "../../etc/x.png", ($e): "trajectory.png"}' "$fixtures/solution.json" >r/solution.json
  report S08 r --solution r/solution.json
  # Not one unescaped character of the hostile string opens markup: with the backslash escapes and
  # the code spans taken out (left to right, as Markdown reads them), no math, HTML or link is left.
  perl -pe 's/\\.|`[^`]*`//g' r/report.md >r/outside_code.md
  run grep -nF -e '<script' -e '/etc/hostname}$' -e '](http' r/outside_code.md
  [[ $status -eq 1 ]] || { echo "$output" >&2; false; }
  grep -qF '`../../etc/x.png`' r/report.md
  run grep -cF '](../../etc/x.png)' r/report.md
  [[ $output == 0 ]]
  # The LaTeX document holds only the derivation's formulas, and compiles without reading a host file.
  compiles r/report.md
  run grep -c 'input\|hostname' r/report.tex
  [[ $output == 0 ]]
  run grep -F "$(cat /etc/hostname)" r/report.log
  [[ $status -eq 1 || -z $(cat /etc/hostname) ]]
}

@test "report: the LaTeX check lifts no formula out of a code block or a code span" {
  printf '%s\n' '# t' '```text' 'a $\input{/etc/hostname}$ b' '~~~' '$x$ still code' '```' \
    'text `$\input{/etc/passwd}$` and $y$ and \$z\$' '~~~~' '$w$' '~~~~' >doc.md
  awk -f "$LATEX_DOCUMENT" doc.md >doc.tex
  [[ $(grep -c 'par$' doc.tex) == 1 ]]
  grep -qxF '$y$\par' doc.tex
  run grep -c 'input\|\$x\$\|\$w\$\|\$z' doc.tex
  [[ $output == 0 ]]
  printf '%s\n' '```' 'never closed' >open.md
  run awk -f "$LATEX_DOCUMENT" open.md
  [[ $status -eq 1 ]]
}

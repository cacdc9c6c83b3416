# The cases of the hostile corpus (sourced by tests/hostile/run.sh, which defines case_dir,
# expect and the helpers). Each: case_dir ID; build the input; expect EXIT PATTERN TOOL ARGS.
# shellcheck shell=bash disable=SC2154

# ---- helios-parse: problem texts -------------------------------------------------------------

# s01_edited ID SED PATTERN: S01's problem text edited by SED must be refused (exit 3) with PATTERN.
s01_edited() {
  case_dir "$1"
  s01_text | sed "$2" >p.txt
  expect 3 "$3" parse p.txt
}

# Encoding and bytes.
case_dir parse-empty; : >p.txt; expect 3 'never states its name' parse p.txt
case_dir parse-comments-only; printf '# a comment\n# another\n' >p.txt; expect 3 'never states its name' parse p.txt
case_dir parse-whitespace-only; printf ' \n\t\n\n' >p.txt; expect 3 'never states its name' parse p.txt
case_dir parse-nul-byte; { s01_text; printf 'The \000thrust.\n'; } >p.txt; expect 3 'NUL|control' parse p.txt
case_dir parse-nul-first; printf '\000' >p.txt; expect 3 'NUL|control' parse p.txt
case_dir parse-escape-sequence; { s01_text; printf 'The \033[31mred\033[0m sentence.\n'; } >p.txt
expect 3 'control' parse p.txt
case_dir parse-bell; { s01_text; printf 'Ring\a.\n'; } >p.txt; expect 3 'control' parse p.txt
case_dir parse-del; { s01_text; printf 'Del\177.\n'; } >p.txt; expect 3 'control' parse p.txt
case_dir parse-backspace; { s01_text; printf 'Back\b\b.\n'; } >p.txt; expect 3 'control' parse p.txt
for bad in 'lone-continuation:\x80' 'overlong-slash:\xc0\xaf' 'surrogate:\xed\xa0\x80' 'truncated:\xe2\x82' \
  'beyond-unicode:\xf4\x90\x80\x80' 'ff-byte:\xff' 'latin1:caf\xe9'; do
  case_dir "parse-utf8-${bad%%:*}"; { s01_text; printf "Word ${bad#*:} here.\n"; } >p.txt; expect 3 'UTF-8' parse p.txt
done
case_dir parse-binary-elf; head -c 4096 "$BIN/helios-parse" >p.txt; expect 3 'UTF-8|control|NUL' parse p.txt
for seed in 1 2 3 4 5 6 7 8; do
  case_dir "parse-random-bytes-$seed"
  awk -v s="$seed" 'BEGIN { srand(s); for (i = 0; i < 3000; i++) printf "%c", int(rand() * 256) }' >p.txt
  expect 3 'p.txt:1: the problem text is not valid UTF-8|NUL|control' parse p.txt
done
for seed in 1 2 3 4 5 6; do
  case_dir "parse-random-words-$seed"
  awk -v s="$seed" 'BEGIN { srand(s); split("the spacecraft thrust of N kg km s days at from with position velocity and is a Minimize fuel MJD2000 [ ] , 0.5 1e3 -7 . Sun Earth Mars departs rendezvouses", w, " ");
    for (i = 0; i < 400; i++) printf "%s%s", w[int(rand() * length(w)) + 1], (rand() < 0.1 ? ".\n" : " ") }' >p.txt
  expect 3 '.' parse p.txt
done
case_dir parse-crlf; s01_text | sed 's/$/\r/' >p.txt; expect 0 '' parse p.txt
case_dir parse-no-final-newline; s01_text | head -c -1 >p.txt; expect 0 '' parse p.txt
case_dir parse-stdin-missing-file; expect 3 'no-such|No such|cannot' parse no-such.txt
case_dir parse-directory; mkdir d; expect 3 'd|directory|read' parse d

# Sizes.
case_dir parse-over-1MiB; { s01_text; awk 'BEGIN { for (i = 0; i < 30000; i++) print "# padding comment line of forty chars" }'; } >p.txt
expect 3 'MiB|bytes|limit' parse p.txt
case_dir parse-line-5000; { s01_text; printf '# %05000d\n' 0; } >p.txt; expect 3 '4096|limit' parse p.txt
case_dir parse-sentence-30KB; { s01_text; printf 'The spacecraft %s.\n' "$(printf 'very %.0s' $(seq 6000))"; } >p.txt
expect 3 '4096|limit' parse p.txt
case_dir parse-sentence-multiline-long; { s01_text; for i in $(seq 800); do echo "word word"; done; echo "."; } >p.txt
expect 3 '4096|limit' parse p.txt
case_dir parse-many-duplicates; { s01_text; for i in $(seq 3000); do echo "The time of flight is 348.795 days."; done; } >p.txt
expect 3 'twice|again|duplicate|already' parse p.txt

# Numbers.
for n in 'huge:1e400' 'tiny:1e-400' 'digits:1'"$(printf '0%.0s' $(seq 400))" 'hex:0x1p3' 'nan:NaN' 'inf:inf'; do
  case_dir "parse-number-${n%%:*}"; with_sentence "Minimize the fuel consumption." | sed "s/0.5 N/${n#*:} N/" >p.txt
  expect 3 'p.txt:4: .*(outside the range of a double|cannot read .a maximum thrust of)' parse p.txt
done
s01_edited parse-thrust-zero 's/0.5 N/0 N/' 'thrust'
s01_edited parse-thrust-negative 's/0.5 N/-0.5 N/' 'thrust'
s01_edited parse-isp-zero 's/2000 s/0 s/' 'impulse|Isp'
s01_edited parse-mass-zero 's/1000 kg/0 kg/' 'mass'
s01_edited parse-mass-negative 's/1000 kg/-1000 kg/' 'mass'
s01_edited parse-tof-zero 's/348.795 days/0 days/' 'flight|positive'
s01_edited parse-tof-negative 's/348.795 days/-348.795 days/' 'flight|positive'
s01_edited parse-mu-negative 's/1.32712440018e11/-1.32712440018e11/' 'gravitational|positive'
s01_edited parse-unit-typo 's/0.5 N/0.5 NN/' 'unit|NN'
s01_edited parse-unit-wrong-dimension 's/0.5 N/0.5 kg/' 'unit|kg'
s01_edited parse-unit-missing 's/0.5 N/0.5/' 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-two 's/\[-140699693, -51614428, 980\]/[-140699693, -51614428]/' 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-four 's/\[-140699693, -51614428, 980\]/[1, 2, 3, 4]/' 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-nested 's/\[-140699693, -51614428, 980\]/[[1], 2, 3]/' 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-deep "s/\[-140699693, -51614428, 980\]/$(nested 500)/" 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-unclosed 's/\[-140699693, -51614428, 980\]/[1, 2, 3/' 'p.txt:[0-9]+: cannot use sentence'
s01_edited parse-vector-words 's/\[-140699693, -51614428, 980\]/[a, b, c]/' 'p.txt:[0-9]+: cannot use sentence'

# Facts: missing, twice, contradictory, unknown.
for drop in 'thrust:maximum thrust' 'departure:departs' 'arrival:rendezvouses' 'objective:Minimize' \
  'central:central body' 'flight:time of flight'; do
  case_dir "parse-missing-${drop%%:*}"; s01_text | grep -v "${drop#*:}" >p.txt; expect 3 '.' parse p.txt
done
case_dir parse-objective-twice; { s01_text; echo "Minimize the flight time."; } >p.txt; expect 3 '.' parse p.txt
case_dir parse-central-twice; { s01_text; echo "The central body is the Earth."; } >p.txt; expect 3 '.' parse p.txt
case_dir parse-thrust-twice; { s01_text; echo "The spacecraft has a maximum thrust of 0.6 N."; } >p.txt; expect 3 '.' parse p.txt
case_dir parse-unknown-body; s01_text | sed 's/the Sun with gravitational parameter 1.32712440018e11 km^3\/s^2/the Vulcan/' >p.txt
expect 3 'Vulcan|body|gravitational' parse p.txt
s01_edited parse-unknown-target 's/with position \[-172682023.*$/with Planet X./' 'p.txt:[0-9]+: cannot use sentence'
case_dir parse-unknown-sentence; { s01_text; echo "Please compute the best trajectory."; } >p.txt; expect 3 'cannot use sentence' parse p.txt
case_dir parse-no-period; { s01_text; printf 'The spacecraft waits'; } >p.txt; expect 3 '.' parse p.txt
case_dir parse-only-periods; printf '....\n.\n' >p.txt; expect 3 '.' parse p.txt
case_dir parse-table-row-alone; printf '| a | b |\n' >p.txt; expect 3 '.' parse p.txt
s01_edited parse-mjd-nan 's/at t = 0 days/at MJD2000 nan/' 'p.txt:[0-9]+: cannot use sentence'
case_dir parse-flyby-unknown; { s01_text; echo "The spacecraft flies by Nibiru on the way."; } >p.txt; expect 3 '.' parse p.txt

# Equations of the final state: a value beyond a double where it is written or in its unit, a
# power beyond a double, a unit power beyond an int (each was a raw "stod"/"stoi", exit 1).
s01_final() { grep -v -e '^At the final time' -e '^Minimize' "$BASE/problem.txt"; printf '%s\nMinimize the fuel consumption.\n' "$1"; }
for c in 'overflow:r = 1e400 km:the number 1e400 is outside the range of a double' \
  'underflow:r = 1e-400 km:the number 1e-400 is outside the range of a double' \
  'unit-overflow:r^40 = 1e300 AU^40:.1e300 AU\^40. in km\^40 is beyond the range of a double' \
  'unit-underflow:r^2 = 1e-305 m^2:.1e-305 m\^2. in km\^2 is beyond the range of a double' \
  'power-digits:r = 1 km^'"$(printf '9%.0s' $(seq 400))"':the number 9+ is outside the range of a double'; do
  IFS=: read -r name sentence pattern <<<"$c"
  case_dir "parse-final-state-$name"; s01_final "At the final time $sentence." >p.txt
  expect 3 "p.txt:7: cannot use sentence .At the final time .*: $pattern" parse p.txt
done
s01_edited parse-unit-power-beyond-int 's/0.5 N/0.5 N^99999999999/' 'p.txt:4: cannot use sentence'
# An orbit on the way named "geostationary": its spec is the schema's (it was not).
case_dir parse-geostationary-on-the-way; sed 's/^The time of flight is free, at most 2 days./&\nThe spacecraft passes through geostationary orbit between day 0.1 and day 0.5./' \
  "$ROOT/scenarios/S14/problem.txt" >p.txt
expect 0 '' parse p.txt
# A final orbit given a radius and an altitude that disagree: refused, neither kept silently.
case_dir parse-radius-and-altitude-disagree
sed 's/^At the final time the spacecraft is on .*/At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km at an altitude of 400 km./' \
  "$ROOT/scenarios/S14/problem.txt" >p.txt
expect 3 'radius 42165 km and its altitude 400 km .* disagree' parse p.txt

# User-written accelerations (parsed as text here; helios-derive reads them).
for a in 'unbalanced:(x+' 'deep:'"$(printf '(%.0s' $(seq 300))"'x'"$(printf ')%.0s' $(seq 300))" 'unknown-symbol:q*x' \
  'empty:' 'quote:x"; system("id")'; do
  case_dir "parse-acceleration-${a%%:*}"
  with_sentence "The dynamics include a perturbing acceleration a of [${a#*:}, 0, 0] mm/s^2." >p.txt
  echo "Minimize the fuel consumption." >>p.txt
  expect 3 '.' parse p.txt
done
case_dir parse-acceleration-bomb-power
with_sentence "The dynamics include a perturbing acceleration a of [(x+y+z+vx+vy+vz)^40, 0, 0] mm/s^2." >p.txt
echo "Minimize the fuel consumption." >>p.txt
expect 3 'p.txt:8: .*would expand to about 1.2e\+06 terms' parse p.txt
# GiNaC computes 3^(10^10) exactly while reading it: the CPU-time budget stops it.
case_dir parse-acceleration-bomb-numeric
with_sentence "The dynamics include a perturbing acceleration a of [3^(10^10)*x, 0, 0] mm/s^2." >p.txt
echo "Minimize the fuel consumption." >>p.txt
expect 1 'CPU-time budget of 2 s' parse p.txt --time-limit 2

# Command line.
# Problem ids become file names and C++ literals downstream: only a plain identifier is taken.
for id in 'quote:S01"; system("id")' 'path:../../etc/passwd' 'space:S 01' 'semicolon:S01;rm'; do
  case_dir "parse-id-${id%%:*}"; s01_text | sed "s|^Problem S01:|Problem ${id#*:}:|" >p.txt; expect 3 '.' parse p.txt
done
case_dir parse-stdin-binary; head -c 2000 "$BIN/helios-derive" >p.bin; expect 3 '<stdin>' parse - <p.bin
case_dir parse-usage-no-input; expect 2 'expected 1 input' parse
case_dir parse-usage-unknown-option; cp "$BASE/problem.txt" p.txt; expect 2 'unknown|option' parse p.txt --frobnicate
case_dir parse-usage-bad-backend; cp "$BASE/problem.txt" p.txt; expect 2 'backend' parse p.txt --backend magic

# ---- helios-derive: specs ---------------------------------------------------------------------

case_dir derive-not-json; echo 'not json' >s.json; expect 3 'malformed JSON' derive s.json
case_dir derive-empty; : >s.json; expect 3 'empty input, expected JSON' derive s.json
case_dir derive-truncated; head -c 300 "$BASE/spec.json" >s.json; expect 3 'malformed JSON' derive s.json
case_dir derive-deep-58000; nested 58000 >s.json; expect 3 'nested deeper than 256' derive s.json
case_dir derive-deep-300; nested 300 >s.json; expect 3 'nested deeper than 256' derive s.json
case_dir derive-deep-objects; { printf '{"a":%.0s' $(seq 20000); printf '1'; printf '}%.0s' $(seq 20000); } >s.json
expect 3 'nested deeper than 256' derive s.json
case_dir derive-over-64MiB; { printf '{"schema": "helios/spec", "pad": "'; head -c 67200000 /dev/zero | tr '\0' 'a'; printf '"}'; } >s.json
expect 3 'MiB|bytes|limit' derive s.json
case_dir derive-array-root; echo '[1, 2, 3]' >s.json; expect 3 'not a JSON object' derive s.json
case_dir derive-number-root; echo '42' >s.json; expect 3 'not a JSON object' derive s.json
case_dir derive-string-root; echo '"helios/spec"' >s.json; expect 3 'not a JSON object' derive s.json
case_dir derive-wrong-kind; cp "$BASE/derivation.json" s.json; expect 3 'wrong artifact' derive s.json
case_dir derive-schema-array; jq_spec '.schema = ["helios/spec"]' >s.json; expect 3 'field /schema' derive s.json
case_dir derive-version-string; jq_spec '.schema_version = "1"' >s.json; expect 3 'schema_version' derive s.json
case_dir derive-version-99; jq_spec '.schema_version = 99' >s.json; expect 3 'schema_version' derive s.json
case_dir derive-version-missing; jq_spec 'del(.schema_version)' >s.json; expect 3 'schema_version is missing' derive s.json
case_dir derive-producer-number; jq_spec '.producer = 5' >s.json; expect 3 'schema violation at /producer' derive s.json
case_dir derive-invalid-utf8-string; jq_spec '.problem.title = "X"' | sed 's/"X"/"\xff\xfe"/' >s.json; expect 3 'UTF-8|malformed' derive s.json
case_dir derive-nul-in-string; jq_spec '.problem.title = "a\u0000b"' >s.json; expect 0 '' derive s.json
case_dir derive-control-in-kind; printf '{"schema": "helios/spec\\u001b[2J"}' >s.json; expect 3 'u001b' derive s.json
case_dir derive-duplicate-keys; jq_spec . | sed '0,/"schema_version": 1,/s//"schema_version": 1, "schema_version": 7,/' >s.json; expect 3 '.' derive s.json
case_dir derive-number-1e400; jq_spec . | sed 's/"thrust_N": 0.5/"thrust_N": 1e400/' >s.json; expect 3 's.json: malformed JSON: the number 1e400 is outside the range of a double' derive s.json
for f in '.spacecraft.thrust_N = "0.5":thrust-string' '.spacecraft.thrust_N = -1:thrust-negative' '.spacecraft.thrust_N = 0:thrust-zero' \
  '.spacecraft.isp_s = null:isp-null' '.spacecraft = []:spacecraft-array' 'del(.constraints):no-constraints' \
  '.constraints = []:empty-constraints' '.constraints[0].target.position_km = [1,2]:short-vector' \
  '.constraints[0].target.position_km = ["a","b","c"]:string-vector' '.time.tof_days = -5:tof-negative' \
  '.objective.kind = "maximum_fun":unknown-objective' '.central_body.mu_km3_s2 = 0:mu-zero' \
  '.extra = 1:unknown-top-field' '.problem.id = "S01\"; system(\"id\")":hostile-id' \
  '.problem.id = "a\nb":newline-id' '.problem.id = "":empty-id' '.constraints[0].id = "x y":constraint-id-space' \
  '.constraints[1].at = "never":unknown-at' '.dynamics.model = "n_body":unknown-model'; do
  case_dir "derive-spec-${f##*:}"; jq_spec "${f%:*}" >s.json; expect 3 's.json: spec schema violation at /' derive s.json
done
for m in '.central_body.mu_km3_s2 = 1e308:mu-overflow' '.time.tof_days = 1e306:tof-overflow' \
  '.spacecraft.isp_s = 1e308:isp-overflow' '.spacecraft.initial_mass_kg = 1e308:mass-overflow'; do
  case_dir "derive-magnitude-${m##*:}"; jq_spec "${m%:*}" >s.json; expect 3 'double precision' derive s.json
done
for a in 'unbalanced:(x+:cannot parse' 'deep:'"$(printf '(%.0s' $(seq 300))"'x'"$(printf ')%.0s' $(seq 300))"':nested deeper' \
  'unknown-symbol:q*x:cannot parse' 'power-bomb:(x+y+z+vx+vy+vz)^40:would expand' 'injection:x\"); system(\"id\"):cannot parse' \
  'long:@long.txt:characters'; do
  name=${a%%:*} rest=${a#*:}
  case_dir "derive-acceleration-$name"
  if [[ ${rest%:*} == @long.txt ]]; then awk 'BEGIN { for (i = 0; i < 600000; i++) printf "x+"; print "x" }' >long.txt; fi
  jq --rawfile c <(if [[ -f long.txt ]]; then tr -d '\n' <long.txt; else printf '%s' "${rest%:*}"; fi) \
    '.dynamics.perturbations[0].components[0] = $c' "$BASE/s12-spec.json" >s.json
  rm -f long.txt
  expect 3 "s.json: field /dynamics/perturbations \\(srp\\)/components/0: .*${rest##*:}" derive s.json
done
# A final-state value a double holds in km^40 but not in the normalized units (AU^40 > 1.8e308):
# it became r^40 = 0, r = 0.
case_dir derive-final-state-beyond-normalized
s01_final "At the final time r^40 = 1e300 km^40." >p.txt; "$BIN/helios-parse" p.txt -o s.json; rm p.txt
expect 3 "s.json: constraint 'arrival': target/conditions/0/equals: 1e\+300 km\^40 in the normalized units .* is beyond the range of a double" derive s.json
case_dir derive-cpu-budget
jq '.dynamics.perturbations[0].components[0] = "3^(10^10)*x"' "$BASE/s12-spec.json" >s.json
expect 1 'CPU-time budget of 2 s' derive s.json --time-limit 2
case_dir derive-memory-budget
jq '.dynamics.perturbations[0].components[0] = "3^(10^10)*x"' "$BASE/s12-spec.json" >s.json
# (Under AddressSanitizer the memory budget is not applied: the CPU-time budget stops it.)
expect 1 'memory budget of 200 MB|CPU-time budget of 20 s' derive s.json --memory-limit 200 --time-limit 20
case_dir derive-usage-bad-time-limit; cp "$BASE/spec.json" s.json; expect 2 'time-limit' derive s.json --time-limit -1
case_dir derive-usage-llm-option; cp "$BASE/spec.json" s.json; expect 2 'needs --backend llm' derive s.json --previous x

# ---- helios-verify and helios-gen: derivations ------------------------------------------------

for tool in verify gen; do
  case_dir "$tool-not-json"; echo '{' >d.json; expect 3 'malformed JSON' "$tool" d.json
  case_dir "$tool-deep"; nested 60000 >d.json; expect 3 'nested deeper than 256' "$tool" d.json
  case_dir "$tool-wrong-kind"; cp "$BASE/spec.json" d.json; expect 3 'wrong artifact' "$tool" d.json
  case_dir "$tool-version-bool"; jq_derivation '.schema_version = true' >d.json; expect 3 'schema_version' "$tool" d.json
done
# Expressions of a derivation: gen refuses them as input; verify reports a failed check (exit 4).
for e in 'unbalanced:1/(rx+' 'deep:'"$(printf '(%.0s' $(seq 400))"'rx'"$(printf ')%.0s' $(seq 400))" \
  'unknown-symbol:rx*nosuch' 'power-bomb:(rx+ry+rz+vx+vy+vz)^40' 'injection:rx); system(\"id\"'; do
  case_dir "gen-hamiltonian-${e%%:*}"; jq_derivation --arg h "${e#*:}" '.hamiltonian = $h' >d.json
  expect 3 'd.json: field /hamiltonian' gen d.json
  case_dir "verify-hamiltonian-${e%%:*}"; jq_derivation --arg h "${e#*:}" '.hamiltonian = $h' >d.json
  expect 4 'verdict fail' verify d.json
done
for tool in verify gen; do
  case_dir "$tool-hamiltonian-empty"; jq_derivation '.hamiltonian = ""' >d.json
  expect 3 'd.json: derivation schema violation at /hamiltonian' "$tool" d.json
  case_dir "$tool-number-1e400"; jq_derivation . | sed '0,/"value": [0-9.e+-]*/s//"value": 1e400/' >d.json
  expect 3 'd.json: malformed JSON: the number 1e400 is outside the range of a double' "$tool" d.json
  case_dir "$tool-stdin-deep"; nested 100000 >d.json; expect 3 '<stdin>: JSON nested deeper' "$tool" - <d.json
done
# With the generated dynamics module, helios-gen reads the state and costate equations.
for e in 'rhs-bomb:.costate_odes[0].rhs = "(rx+ry+rz+vx+vy+vz)^40"' 'rhs-unbalanced:.costate_odes[0].rhs = "(("' \
  'ode-missing:.costate_odes = .costate_odes[1:]'; do
  case_dir "gen-${e%%:*}"; jq_derivation "${e#*:}" >d.json; expect 3 'd.json: field /(state|costate)_odes' gen d.json --modules generated
done
# A hostile meaning reaches only a comment, escaped: that is not an error.
case_dir gen-meaning-newline; jq_derivation '.parameters[0].meaning = "mu */ system(\"id\"); /*\n"' >d.json; expect 0 '' gen d.json
for e in 'state-renamed:.states[0].name = "r x"' \
  'state-injection:.states[0].name = "rx;system"' 'id-injection:.problem.id = "S01\"; int pwn = system(\"touch /tmp/pwn\"); //"' \
  'id-newline:.problem.id = "S01\n#include </etc/passwd>"' 'variable-injection:.shooting.variables[1].name = "l_rx=0;system(\"id\")"' 'equations-dropped:.shooting.equations = []' \
  'units-negative:.units.length_km = -1' 'parameter-nan:.parameters[0].value = "nan"' 'times-swapped:.times.tf = -1'; do
  case_dir "gen-${e%%:*}"; jq_derivation "${e#*:}" >d.json
  expect 3 'd.json: (derivation schema violation at /|field /times: the final time)' gen d.json
done
case_dir gen-usage-bad-modules; cp "$BASE/derivation.json" d.json; expect 2 'modules' gen d.json --modules all
case_dir verify-usage-points; cp "$BASE/derivation.json" d.json; expect 2 'points' verify d.json --points 0
case_dir verify-clean; cp "$BASE/derivation.json" d.json; expect 0 '' verify d.json
case_dir verify-cpu-budget; jq_derivation '.hamiltonian = "3^(10^10)*rx"' >d.json
expect 1 'CPU-time budget of 2 s' verify d.json --time-limit 2
# helios-gen has the same budgets (it had none): GiNaC computes 3^(10^10) while reading the equation.
case_dir gen-cpu-budget; jq_derivation '.costate_odes[0].rhs = "3^(10^10)*rx"' >d.json
expect 1 'CPU-time budget of 2 s' gen d.json --time-limit 2
case_dir gen-memory-budget; jq_derivation '.costate_odes[0].rhs = "3^(10^10)*rx"' >d.json
# (Under AddressSanitizer the memory budget is not applied: the CPU-time budget stops it.)
expect 1 'memory budget of 200 MB|CPU-time budget of 20 s' gen d.json --memory-limit 200 --time-limit 20
# psi that asks for another state than its target (issue 46): the row moved, its initial value
# moved, the target taken away or of an unknown kind; each a failed check, not a pass.
for e in 'departure-shifted:(.constraints[0].psi[0] = "-departure_rx-4.3e-6+rx") | (.initial_values[0].value = "departure_rx+4.3e-6")' \
  'initial-value-shifted:.initial_values[0].value = "departure_rx+4.3e-6"' 'target-removed:del(.constraints[1].target)' \
  'target-unknown-kind:.constraints[1].target.kind = "wish"' 'target-moved:.constraints[1].target.position_km[0] += 638'; do
  case_dir "verify-${e%%:*}"; jq_derivation "${e#*:}" >d.json
  expect 4 'verdict fail: 1 of [0-9]+ checks failed \((target:(departure|arrival)|initial_values)\)' verify d.json
done

# ---- helios-solve: the compile cache (issue 46) ----------------------------------------------
# cache_entry: an empty program compiled into ./cache; prints its entry's folder.
cache_entry() {
  printf '#include "helios_runtime.hpp"\nint main() {}\n' >p.cpp
  "$BIN/helios-solve" p.cpp --compile-only --cache-dir cache -o setup.json
  echo "cache/$(jq -r .structure_sha256 setup.json)"
}
# An entry folder that is a link (to a copy of itself) is not this user's alone: refused.
case_dir solve-cache-entry-link; entry=$(cache_entry); mv "$entry" elsewhere; ln -s "$PWD/elsewhere" "$entry"
expect 1 'the compile cache entry is not a private folder of this user' solve p.cpp --compile-only --cache-dir cache
# A program planted in an entry does not match its stored hash: compiled anew, never run.
case_dir solve-cache-planted-program; entry=$(cache_entry); printf '#!/bin/sh\necho planted\n' >"$entry/shoot"
expect 0 '' solve p.cpp --compile-only --cache-dir cache
[[ $(jq -r .cached out) == false ]] || { failures=$((failures + 1)); echo "FAIL $CASE: the planted program was taken"; }

# ---- helios-solve: settings and programs (each refused before any compile) -------------------

for s in 'seed-huge:.seed = 1e30' 'seed-string:.seed = "1"' 'attempts-huge:.max_attempts = 1e12' 'attempts-zero:.max_attempts = 0' \
  'ratio-zero:.eps_first_ratio = 0' 'rtol-negative:.integrator_rtol = -1' 'time-nan:.time_limit_s = "nan"' \
  'unknown-key:.frobnicate = 1' 'array:[1]' 'eps-inverted:.eps_min = 2'; do
  case_dir "solve-settings-${s%%:*}"; jq_settings "${s#*:}" >settings.json; echo 'int main() {}' >shoot.cpp
  expect 3 'settings.json' solve shoot.cpp --settings settings.json --cache-dir cache --trajectory t.csv --plots ''
done
case_dir solve-settings-deep; nested 70000 >settings.json; echo 'int main() {}' >shoot.cpp
expect 3 'nested deeper' solve shoot.cpp --settings settings.json --cache-dir cache --trajectory t.csv --plots ''
case_dir solve-missing-program; cp "$BASE/settings.json" .; expect 3 'no-such.cpp' solve no-such.cpp --settings settings.json --cache-dir cache
case_dir solve-program-is-directory; cp "$BASE/settings.json" .; mkdir shoot.cpp
expect 3 'shoot.cpp' solve shoot.cpp --settings settings.json --cache-dir cache
case_dir solve-settings-missing; echo 'int main() {}' >shoot.cpp; expect 3 'nowhere.json' solve shoot.cpp --settings nowhere.json --cache-dir cache
case_dir solve-usage-memory-limit; cp "$BASE/settings.json" .; echo 'int main() {}' >shoot.cpp
expect 2 'memory-limit' solve shoot.cpp --settings settings.json --memory-limit abc
case_dir solve-usage-time-limit; cp "$BASE/settings.json" .; echo 'int main() {}' >shoot.cpp
expect 2 'time-limit' solve shoot.cpp --settings settings.json --time-limit 0
case_dir solve-settings-node-spacing-tiny; jq_settings '.node_spacing_days = 0.001' >settings.json; echo 'int main() {}' >shoot.cpp
expect 3 'settings.json: field /node_spacing_days: 0.001 is below 1 day' solve shoot.cpp --settings settings.json --cache-dir cache --trajectory t.csv
# A cache folder that is a file (or under one): one line naming the option (was a raw library message).
case_dir solve-cache-dir-file; cp "$BASE/settings.json" .; echo 'int main() {}' >shoot.cpp; echo x >cache
expect 2 '^helios-solve: error: --cache-dir cache: is not a folder' solve shoot.cpp --settings settings.json --cache-dir cache
case_dir solve-cache-dir-under-file; cp "$BASE/settings.json" .; echo 'int main() {}' >shoot.cpp; echo x >cache
expect 2 '^helios-solve: error: --cache-dir cache/sub: cache is not a folder' solve shoot.cpp --settings settings.json --cache-dir cache/sub
# Readers stop at their limit: a device that never ends is refused, not read until memory runs out.
case_dir solve-settings-dev-zero; echo 'int main() {}' >shoot.cpp
expect 3 '/dev/zero: .*larger than the limit' solve shoot.cpp --settings /dev/zero --cache-dir cache --trajectory t.csv
case_dir solve-warm-start-dev-zero; cp "$BASE/settings.json" .; echo 'int main() {}' >shoot.cpp
expect 3 '/dev/zero: .*larger than the limit' solve shoot.cpp --settings settings.json --warm-start /dev/zero --cache-dir cache --trajectory t.csv

# ---- helios-score: the scored artifacts ------------------------------------------------------

case_dir score-reference-not-json; echo 'x' >r.json; expect 3 'r.json' score --reference r.json
case_dir score-reference-deep; nested 60000 >r.json; expect 3 'nested deeper' score --reference r.json
case_dir score-reference-wrong-kind; cp "$BASE/spec.json" r.json; expect 3 'r.json: reference schema violation at /schema' score --reference r.json
case_dir score-spec-deep; cp "$ROOT/scenarios/S01/reference.json" r.json; nested 300 >s.json
expect 3 's.json' score --reference r.json --spec s.json
case_dir score-solution-not-json; cp "$ROOT/scenarios/S01/reference.json" r.json; printf '\377\376' >sol.json
expect 3 'sol.json' score --reference r.json --solution sol.json
case_dir score-derivation-wrong-kind; cp "$ROOT/scenarios/S01/reference.json" r.json; cp "$BASE/spec.json" d.json
expect 3 'd.json' score --reference r.json --derivation d.json
case_dir score-verify-number-1e400; cp "$ROOT/scenarios/S01/reference.json" r.json; echo '{"schema": "helios/verify", "x": 1e400}' >v.json
expect 3 'v.json: malformed JSON: the number 1e400 is outside the range of a double' score --reference r.json --verify v.json
case_dir score-usage-nothing; expect 2 '.' score
# A model's name is text in its cell of scoreboard.md: no new row, heading or HTML.
case_dir score-scoreboard-model-markup; mkdir -p runs/S01
"$BIN/helios-score" --reference "$ROOT/scenarios/S01/reference.json" --spec "$BASE/spec.json" |
  jq '.producer.backend = "llm" | .producer.model = "m | S99 | 100 |\n# Pwned <img src=x onerror=alert(1)>"' >runs/S01/score.json
expect 0 '' score --scoreboard runs
holds "scoreboard.md has one row for the one run, no heading or HTML from the model" \
  eval "[[ \$(grep -c '^|' out) -eq 4 && \$(grep -c '^#' out) -eq 1 ]] && ! grep -q ' <img' out"
case_dir score-crosscheck-cache-dir-file; echo '{}' >sweep.json; echo '{}' >settings.json; echo x >cache
expect 2 '^helios-score: error: --cache-dir cache: is not a folder' score --sweep-crosscheck sweep.json --cells cells \
  --settings settings.json --cache-dir cache --solver "$BIN/helios-solve"
case_dir score-scoreboard-missing; expect 3 'nowhere' score --scoreboard nowhere

# ---- helios-score --report: the problem text it quotes ---------------------------------------
# report_case EXIT PATTERN: helios-score --report on ./p.txt and the base derivation.
report_case() { expect "$1" "$2" score --report --problem p.txt --spec "$BASE/spec.json" --derivation "$BASE/derivation.json"; }
case_dir score-report-problem-binary; printf 'The thrust is 0.5 N.\n\001\002\n' >p.txt; report_case 3 'p.txt:2: control byte'
case_dir score-report-problem-not-utf8; printf 'The thrust is 0.5 N \377.\n' >p.txt; report_case 3 'p.txt:1: the problem text is not valid UTF-8'
case_dir score-report-problem-missing; report_case 3 'p.txt'
case_dir score-report-usage-no-derivation; echo x >p.txt; expect 2 'needs --derivation' score --report --problem p.txt --spec "$BASE/spec.json"
case_dir score-report-problem-dev-zero; expect 3 '/dev/zero: .*larger than the limit' score --report --problem /dev/zero --spec "$BASE/spec.json" --derivation "$BASE/derivation.json"

# ---- helios-score --sweep-cells: the grid of a sweep.json -------------------------------------
# sweep_case ID JSON EXIT PATTERN: helios-score --sweep-cells on ./sweep.json holding JSON.
sweep_case() {
  case_dir "score-sweep-$1"; printf '%s\n' "$2" >sweep.json; cp "$BASE/problem.txt" .
  expect "$3" "$4" score --sweep-cells sweep.json --cells cells
}
sweep_case million-cells '{"departure_mjd2000": {"start": 0, "stop": 999, "step": 1}, "tof_days": {"start": 1, "stop": 1000, "step": 1}}' \
  3 'sweep.json: field /tof_days: the grid has 1000000 cells; the limit is 10000'
sweep_case value-1e300 '{"departure_mjd2000": {"values": [1e300]}, "tof_days": {"values": [300]}}' \
  3 'sweep.json: field /departure_mjd2000: 1e\+300 is above 73050'
sweep_case tof-zero '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [0]}}' 3 'sweep.json: field /tof_days: 0 is below'
sweep_case tof-millennium '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [365250]}}' 3 'sweep.json: field /tof_days: 365250 is above'
sweep_case step-tiny '{"departure_mjd2000": {"start": 0, "stop": 1, "step": 1e-300}, "tof_days": {"values": [300]}}' \
  3 'sweep.json: field /departure_mjd2000/step: more than 1000 values'
sweep_case boundary-short '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [300]}, "boundary": {"tof_max_days": 100}}' \
  3 'sweep.json: field /boundary/tof_max_days: 100 must be at least the longest time of flight 300'
sweep_case boundary-nan '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [300]}, "boundary": {"tof_min_days": "x"}}' \
  3 'sweep.json: field /boundary/tof_min_days: missing or not a number'
# A template whose objective the boundary cannot replace: refused, naming the template.
case_dir score-sweep-boundary-no-objective
echo '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [300]}}' >sweep.json
grep -v '^Minimize' "$ROOT/scenarios/P01/problem.txt" >problem.txt; echo '{}' >settings.json
expect 3 "problem.txt: the sweep's boundary .its minimum-time form.: the template must state its objective in exactly one sentence" \
  score --sweep-boundary sweep.json --cells cells --settings settings.json
# Cells that would fly another problem than their labels (issue 46): refused before any is written.
for e in "weeks:s/@TOF_DAYS@ days/@TOF_DAYS@ weeks/:a time of flight of 2100 d" \
  "glued:s/@TOF_DAYS@ days/1@TOF_DAYS@ days/:a time of flight of 1300 d" \
  "comment:s/is @TOF_DAYS@ days./is 350 days.\n# @TOF_DAYS@/:a time of flight of 350 d" \
  "bound:s/is @TOF_DAYS@ days./is free, between @TOF_DAYS@ days and 500 days./:a free time of flight" \
  "epoch-glued:s/MJD2000 @DEPARTURE_MJD2000@/MJD2000 1@DEPARTURE_MJD2000@/:departure MJD2000 19700"; do
  IFS=: read -r id edit stated <<<"$e"
  case_dir "score-sweep-cell-$id"; sed "$edit" "$ROOT/scenarios/P01/problem.txt" >problem.txt
  echo '{"departure_mjd2000": {"values": [9700]}, "tof_days": {"values": [300]}, "boundary": false}' >sweep.json
  expect 3 "problem.txt: the sweep's cell d9700_t300 states .*$stated.*, not its grid values" score --sweep-cells sweep.json --cells cells
done

# ---- helios-score --oem: trajectory.csv and the run it belongs to ---------------------------

OEM_FIX="$ROOT/tests/fixtures/oem"
# oem_case EXIT PATTERN: helios-score --oem on the fixture's spec and solution and ./t.csv.
oem_case() { expect "$1" "$2" score --oem --spec "$OEM_FIX/spec.json" --solution "$OEM_FIX/solution.json" --trajectory t.csv; }
case_dir score-oem-csv-empty; : >t.csv; oem_case 3 't.csv:1: no header'
case_dir score-oem-csv-random-bytes
awk 'BEGIN { srand(7); for (i = 0; i < 3000; i++) printf "%c", int(rand() * 256) }' >t.csv; oem_case 3 't.csv:1: no column'
case_dir score-oem-csv-nul; sed '3s/,/,\x00/' "$OEM_FIX/trajectory.csv" >t.csv; oem_case 3 't.csv:3: field rx_km'
case_dir score-oem-csv-1e400; sed '3s/,[^,]*,/,1e400,/' "$OEM_FIX/trajectory.csv" >t.csv; oem_case 3 't.csv:3: field rx_km: .1e400. is not a finite number'
case_dir score-oem-csv-ragged; sed '3s/,[^,]*$//' "$OEM_FIX/trajectory.csv" >t.csv; oem_case 3 't.csv:3: 10 fields, the header has 11'
case_dir score-oem-csv-time-back; sed '3s/^[^,]*,/-5,/' "$OEM_FIX/trajectory.csv" >t.csv; oem_case 3 't.csv:3: field t_days: -5 is before'
case_dir score-oem-other-problem; cp "$OEM_FIX/trajectory.csv" t.csv; jq '.problem.id = "S01"' "$OEM_FIX/solution.json" >sol.json
expect 3 'sol.json: field /problem/id' score --oem --spec "$OEM_FIX/spec.json" --solution sol.json --trajectory t.csv
case_dir score-oem-usage-no-trajectory; expect 2 'needs --trajectory' score --oem --spec "$OEM_FIX/spec.json" --solution "$OEM_FIX/solution.json"

# ---- every tool: -o naming a stream -----------------------------------------------------------
# A FIFO, or a device like /dev/null, is written into, never renamed over (as root that replaced
# the system's /dev/null with a regular file).
for kind in fifo device; do
  case_dir "parse-output-$kind"; cp "$BASE/problem.txt" p.txt; stream_case "$kind" 0 '' parse p.txt
  case_dir "derive-output-$kind"; stream_case "$kind" 0 '' derive "$BASE/spec.json"
  case_dir "verify-output-$kind"; stream_case "$kind" 0 '' verify "$BASE/derivation.json"
  case_dir "gen-output-$kind"; stream_case "$kind" 0 '' gen "$BASE/derivation.json"
  # (a program that does not compile: its compile report, quickly)
  case_dir "solve-output-$kind"; echo 'int main() {' >shoot.cpp
  stream_case "$kind" 0 '' solve shoot.cpp --compile-only --cache-dir "$WORK/stream-cache"
  case_dir "score-output-$kind"; cp "$BASE/problem.txt" p.txt
  stream_case "$kind" 0 '' score --report --problem p.txt --spec "$BASE/spec.json" --derivation "$BASE/derivation.json"
done
# Other kinds are refused, naming them.
case_dir parse-output-directory; cp "$BASE/problem.txt" p.txt; mkdir out
expect 1 'out: is a directory, not a file to write' parse p.txt

# ---- the llm backend: what the endpoint and the environment give -------------------------------
# Numeric variables out of their range are refused in one line before any request (1e10 retries
# overflowed an int).
for v in 'HELIOS_LLM_MAX_RETRIES=1e10' 'HELIOS_LLM_MAX_TURNS=0' 'HELIOS_LLM_TIMEOUT_S=1e300' 'HELIOS_LLM_TEMPERATURE=nan'; do
  case_dir "parse-llm-env-${v%%=*}"; cp "$BASE/problem.txt" p.txt
  export "$v" HELIOS_LLM_BASE_URL=http://127.0.0.1:9/v1 HELIOS_LLM_MODEL=m
  expect 2 "^helios-parse: error: $v is not a (whole )?number in" parse --backend llm p.txt
  unset "${v%%=*}" HELIOS_LLM_BASE_URL HELIOS_LLM_MODEL
done
# A reply of 300 MB (streamed, no Content-Length) is refused at the limit while it is read: exit 3,
# the memory of the read bounded (the budget below), its transcript without it.
case_dir parse-llm-reply-300MB; cp "$BASE/problem.txt" p.txt; mkdir -p "$WORK/llm"
echo '{"replies": [{"flood_bytes": 300000000}]}' >"$WORK/llm/flood.json"
"$BIN/fake-llm" --script "$WORK/llm/flood.json" --port-file "$WORK/llm/port" --lifetime 120 >/dev/null &
fake=$!
for _ in $(seq 100); do [[ -s $WORK/llm/port ]] && break; sleep 0.05; done
export HELIOS_LLM_BASE_URL="http://127.0.0.1:$(cat "$WORK/llm/port")/v1" HELIOS_LLM_MODEL=m
expect 3 'the reply is larger than the limit of an llm reply \(67108864 bytes' parse --backend llm p.txt \
  --memory-limit 1000 --transcript "$WORK/llm/flood.transcript.json"
unset HELIOS_LLM_BASE_URL HELIOS_LLM_MODEL
kill "$fake"; wait "$fake"
holds "the transcript is kept and small" eval "[[ \$(wc -c <'$WORK/llm/flood.transcript.json') -lt 100000 ]]"

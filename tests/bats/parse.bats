#!/usr/bin/env bats
# helios-parse: problem text -> spec.json

load test_helper

setup() {
  common_setup
  require_tool parse
}

# write_problem FILE: S01's problem text with sed expressions applied (e.g. 's/0.5 N/500 mN/').
write_problem() {
  local file="$1"
  shift
  local args=()
  local e
  for e in "$@"; do args+=(-e "$e"); done
  if ((${#args[@]})); then sed "${args[@]}" "$S01/problem.txt" >"$file"; else cp "$S01/problem.txt" "$file"; fi
}

# ---- shared contract -------------------------------------------------------------------------

@test "parse: no arguments -> exit 2, one error line" {
  contract_no_args parse
}

@test "parse: unknown option -> exit 2" {
  contract_bad_option parse "$S01/problem.txt"
}

@test "parse: two inputs -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-parse" "$S01/problem.txt" "$S01/problem.txt"
  assert_one_error_line parse
}

@test "parse: --backend other than builtin -> exit 2" {
  run -2 --separate-stderr "$BIN/helios-parse" --backend nope "$S01/problem.txt"
  assert_one_error_line parse
}

@test "parse: missing input file -> exit 3 naming the file, nothing written" {
  mkdir out
  run -3 --separate-stderr "$BIN/helios-parse" no-such-problem.txt -o out/spec.json
  assert_one_error_line parse
  assert_stderr_contains "no-such-problem.txt"
  assert_dir_empty out
}

@test "parse: a directory as the input -> exit 3 naming it" {
  mkdir problem-dir
  run -3 --separate-stderr "$BIN/helios-parse" problem-dir
  assert_one_error_line parse
  assert_stderr_contains "problem-dir"
}

@test "parse: an unwritable -o target -> exit 1, one error line, no temp files" {
  run -1 --separate-stderr "$BIN/helios-parse" "$S01/problem.txt" -o no-such-dir/spec.json
  assert_one_error_line parse
  assert_stderr_contains "no-such-dir/spec.json"
  assert_no_temp_files .
}

@test "parse: --help ends with an e.g. line" {
  contract_help parse
}

@test "parse: --version" {
  contract_version parse
}

# ---- S01 ---------------------------------------------------------------------------------------

@test "parse: S01 parses into a spec with the paper's values" {
  run -0 --separate-stderr "$BIN/helios-parse" "$S01/problem.txt" -o spec.json
  [[ -z $output ]]
  assert_jq spec.json '.schema == "helios/spec" and .schema_version == 1'
  assert_jq spec.json '.problem.id == "S01"'
  assert_jq spec.json '.central_body.name == "Sun" and .central_body.mu_km3_s2 == 1.32712440018e11'
  assert_jq spec.json '.spacecraft == {"thrust_N": 0.5, "isp_s": 2000, "initial_mass_kg": 1000}'
  assert_jq spec.json '.objective.kind == "minimum_fuel"'
  assert_jq spec.json '.time.final_time == "fixed" and .time.tof_days == 348.795 and .time.t0_days == 0'
  assert_jq spec.json '[.constraints[].kind] == ["initial_state", "rendezvous"]'
  assert_jq spec.json '.constraints[0].target.position_km == [-140699693, -51614428, 980]'
  assert_jq spec.json '.constraints[1].target.velocity_km_s == [-16.427384, -14.860506, 9.21486e-2]'
  assert_no_temp_files .
}

@test "parse: output goes to stdout by default and with -o -" {
  run -0 --separate-stderr "$BIN/helios-parse" "$S01/problem.txt"
  jq -e '.problem.id == "S01"' <<<"$output"
  run -0 --separate-stderr "$BIN/helios-parse" "$S01/problem.txt" -o -
  jq -e '.problem.id == "S01"' <<<"$output"
}

@test "parse: reads the problem from stdin with -" {
  "$BIN/helios-parse" "$S01/problem.txt" -o from-file.json
  "$BIN/helios-parse" - -o from-stdin.json <"$S01/problem.txt"
  assert_jq from-stdin.json '.problem.source_file == "<stdin>"'
  # Same spec apart from where it came from.
  diff <(jq -S 'del(.problem.source_file)' from-file.json) <(jq -S 'del(.problem.source_file)' from-stdin.json)
}

@test "parse: an unusable sentence -> exit 3 quoting the sentence and its line" {
  write_problem problem.txt 's/^Minimize the fuel consumption\.$/The spacecraft sings a song./'
  grep -n 'sings a song' problem.txt | grep -q '^8:'
  mkdir out
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt -o out/spec.json
  assert_one_error_line parse
  assert_stderr_contains "problem.txt:8" '"The spacecraft sings a song'
  assert_dir_empty out
}

@test "parse: an unknown unit -> exit 3 naming the unit" {
  write_problem problem.txt 's/0\.5 N/0.5 furlongs/'
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt
  assert_one_error_line parse
  assert_stderr_contains "furlongs" "problem.txt:4"
}

@test "parse: a non-positive thrust -> exit 3" {
  write_problem problem.txt 's/0\.5 N/-0.5 N/'
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt
  assert_one_error_line parse
  assert_stderr_contains "thrust"
}

@test "parse: a missing objective -> exit 3 naming the objective" {
  write_problem problem.txt '/^Minimize/d'
  mkdir out
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt -o out/spec.json
  assert_one_error_line parse
  assert_stderr_contains "objective"
  assert_dir_empty out
}

@test "parse: a missing time of flight -> exit 3" {
  write_problem problem.txt '/^The time of flight/d'
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt
  assert_one_error_line parse
  assert_stderr_contains "time of flight"
}

@test "parse: a sentence given twice -> exit 3" {
  write_problem problem.txt '$a The time of flight is 100 days.'
  run -3 --separate-stderr "$BIN/helios-parse" problem.txt
  assert_one_error_line parse
  assert_stderr_contains "twice"
}

@test "parse: JSON is not a problem text -> exit 3" {
  run -3 --separate-stderr "$BIN/helios-parse" "$S01/reference.json"
  assert_one_error_line parse
}

# ---- units -----------------------------------------------------------------------------------

@test "parse: 0.5 N and 500 mN give the same thrust_N" {
  write_problem newton.txt
  write_problem millinewton.txt 's/0\.5 N/500 mN/'
  grep -q '500 mN' millinewton.txt
  "$BIN/helios-parse" newton.txt -o a.json
  "$BIN/helios-parse" millinewton.txt -o b.json
  assert_jq a.json '.spacecraft.thrust_N == 0.5'
  assert_jq b.json '(.spacecraft.thrust_N - 0.5) | fabs < 1e-12'
}

@test "parse: positions in AU are converted to km" {
  write_problem au.txt 's/position \[-140699693, -51614428, 980\] km/position [1, -0.5, 0.25] AU/'
  grep -q '\[1, -0.5, 0.25\] AU' au.txt
  "$BIN/helios-parse" au.txt -o au.json
  # 1 AU = 149597870.7 km (IAU 2012; the tool may use pykep's 149597870.691): relative 1e-6.
  assert_jq au.json '.constraints[0].target.position_km as [$x, $y, $z]
    | (($x / 149597870.7 - 1) | fabs < 1e-6) and (($y / -74798935.35 - 1) | fabs < 1e-6)
      and (($z / 37399467.675 - 1) | fabs < 1e-6)'
}

@test "parse: positions in m and velocities in m/s are converted to km and km/s" {
  write_problem si.txt 's/position \[-140699693, -51614428, 980\] km with velocity \[9.774596, -28.07828, 4.337725e-4\] km\/s/position [-140699693000, -51614428000, 980000] m with velocity [9774.596, -28078.28, 0.4337725] m\/s/'
  grep -q '980000\] m with' si.txt
  "$BIN/helios-parse" si.txt -o si.json
  "$BIN/helios-parse" "$S01/problem.txt" -o ref.json
  jq -n --slurpfile a si.json --slurpfile b ref.json -e '
    [$a[0].constraints[0].target, $b[0].constraints[0].target] as [$x, $y]
    | [range(3)] | all(
        (($x.position_km[.] - $y.position_km[.]) | fabs) <= 1e-9 * (($y.position_km[.] | fabs) + 1)
        and (($x.velocity_km_s[.] - $y.velocity_km_s[.]) | fabs) <= 1e-12 * (($y.velocity_km_s[.] | fabs) + 1))'
}

@test "parse: a time of flight in s equals the same one in days" {
  # 348.795 days = 30135888 s
  write_problem seconds.txt 's/348\.795 days/30135888 s/'
  grep -q '30135888 s' seconds.txt
  "$BIN/helios-parse" seconds.txt -o s.json
  assert_jq s.json '(.time.tof_days - 348.795) | fabs < 1e-9'
}

@test "parse: a specific impulse stays in seconds" {
  write_problem isp.txt 's/2000 s/3000 s/'
  "$BIN/helios-parse" isp.txt -o isp.json
  assert_jq isp.json '.spacecraft.isp_s == 3000'
}

# ---- a thruster given by fits ------------------------------------------------------------------

# s15_fits FILE THRUSTER-SENTENCE: S15 (a solar-electric engine) with its efficiency, Isp and cap
# replaced by the thruster's fits.
s15_fits() {
  sed "s|^The spacecraft is solar-electric: .*\$|The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, the bus uses 0.5 kW.\n$2|" \
    "$ROOT/scenarios/S15/problem.txt" >"$1"
  grep -q "thrust is" "$1"
}

@test "parse: S15's engine given by fits writes the polynomials in mN and mg/s, the same from N, kg/s and P in W" {
  # 2 eta / (g0 Isp) per kW at S15's eta 0.6 and Isp 2000 s: 61.18 mN/kW and 3.119 mg/s per kW
  s15_fits kw.txt "The thruster's thrust is 61.1829727786757 P mN and its mass flow is 3.1194634650301425 P mg/s, with P its input power in kW up to 10 kW."
  s15_fits w.txt "The thruster's thrust is 6.11829727786757e-5 P N and its mass flow is 3.1194634650301425e-9 P kg/s, where P is its input power in W, up to 10000 W."
  "$BIN/helios-parse" kw.txt -o kw.json
  "$BIN/helios-parse" w.txt -o w.json
  assert_jq kw.json '.spacecraft == {"array_power_1AU_W": 20000, "bus_power_W": 500, "max_engine_power_W": 10000,
    "thrust_polynomial_mN": [0, 61.1829727786757], "mass_flow_polynomial_mg_s": [0, 3.1194634650301425],
    "initial_mass_kg": 1000}'
  jq -n --slurpfile a kw.json --slurpfile b w.json -e '
    [$a[0].spacecraft, $b[0].spacecraft] as [$x, $y]
    | ($x | keys) == ($y | keys) and $x.max_engine_power_W == $y.max_engine_power_W
      and ([range(2)] | all((($x.thrust_polynomial_mN[.] - $y.thrust_polynomial_mN[.]) | fabs) <= 1e-12 * 62
        and (($x.mass_flow_polynomial_mg_s[.] - $y.mass_flow_polynomial_mg_s[.]) | fabs) <= 1e-12 * 4))'
}

@test "parse: fits beside an efficiency -> exit 3 in one line naming the efficiency" {
  s15_fits both.txt "The thruster's thrust is -1.9137 + 36.242 P mN and its mass flow is 0.47556 + 0.90209 P mg/s for an input power P between 0.5 and 2.6 kW."
  sed -i 's/the bus uses 0.5 kW\./the bus uses 0.5 kW and an efficiency of 0.6./' both.txt
  grep -q 'efficiency of 0.6' both.txt
  run -3 --separate-stderr "$BIN/helios-parse" both.txt -o both.json
  assert_one_error_line parse
  assert_stderr_contains "engine_efficiency (0.6)" "the thruster's fits give its performance"
  [[ ! -e both.json ]]
}

# ---- a thruster given by a table ---------------------------------------------------------------

# s15_table FILE LINE...: S15 with its efficiency, Isp and cap replaced by the thruster's table, whose
# lines (the sentence announcing it, the header, the rows) follow the solar-electric sentence.
s15_table() {
  local file="$1" line
  shift
  while IFS= read -r line; do
    if [[ $line == "The spacecraft is solar-electric: "* ]]; then
      echo "The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, the bus uses 0.5 kW."
      printf '%s\n' "$@"
    else
      printf '%s\n' "$line"
    fi
  done <"$ROOT/scenarios/S15/problem.txt" >"$file"
  grep -q "table" "$file"
}

@test "parse: S15's engine given by a thruster's table writes its rows in SI, the same from W, N, kg/s in another order" {
  s15_table kw.txt "The thruster's table gives its thrust and mass flow at these input powers:" \
    "| input power [kW] | thrust [mN] | mass flow [mg/s] |" "|---|---|---|" \
    "| 0.525 | 19.0 | 0.91 |" "| 1.0 | 35.0 | 1.32 |" "| 1.5 | 52.0 | 1.73 |" "| 2.0 | 68.0 | 2.13 |" "| 2.567 | 92.7 | 2.89 |"
  s15_table w.txt "The thruster is given by this table of its input power, thrust and mass flow:" \
    "| mdot (kg/s) | P (W) | T (N) |" \
    "| 9.1e-7 | 525 | 0.019 |" "| 1.32e-6 | 1000 | 0.035 |" "| 1.73e-6 | 1500 | 0.052 |" "| 2.13e-6 | 2000 | 0.068 |" \
    "| 2.89e-6 | 2567 | 0.0927 |"
  "$BIN/helios-parse" kw.txt -o kw.json
  "$BIN/helios-parse" w.txt -o w.json
  assert_jq kw.json '.spacecraft | keys == ["array_power_1AU_W", "bus_power_W", "initial_mass_kg", "thruster_table"]
    and .array_power_1AU_W == 20000 and .bus_power_W == 500 and .initial_mass_kg == 1000'
  local want='[[525, 0.019, 9.1e-7], [1000, 0.035, 1.32e-6], [1500, 0.052, 1.73e-6], [2000, 0.068, 2.13e-6],
    [2567, 0.0927, 2.89e-6]]'
  local f
  for f in kw.json w.json; do
    jq -e --argjson w "$want" '.spacecraft.thruster_table as $t | ($t | length) == 5
      and all($t[]; keys == ["input_power_W", "mass_flow_kg_s", "thrust_N"])
      and ([range(5)] | all(. as $k | [$t[$k].input_power_W, $t[$k].thrust_N, $t[$k].mass_flow_kg_s] as $r
        | [range(3)] | all((($r[.] - $w[$k][.]) | fabs) <= 1e-12 * $w[$k][.])))' "$f"
  done
}

@test "parse: a thruster's table whose input powers go down -> exit 3 in one line naming the row" {
  s15_table down.txt "The thruster's throttle table:" "| P [kW] | T [mN] | mdot [mg/s] |" \
    "| 0.5 | 20 | 1 |" "| 2.0 | 68 | 2.13 |" "| 1.5 | 52 | 1.73 |"
  run -3 --separate-stderr "$BIN/helios-parse" down.txt -o down.json
  assert_one_error_line parse
  assert_stderr_contains 'down.txt:11: cannot use table row "| 1.5 | 52 | 1.73 |"' \
    "the input power 1.5 kW is not above the row before's (2 kW)"
  [[ ! -e down.json ]]
}

@test "parse: a thruster's table beside the engine's efficiency -> exit 3 in one line naming the efficiency" {
  s15_table both.txt "The thruster's throttle table:" "| P [kW] | T [mN] | mdot [mg/s] |" \
    "| 0.5 | 20 | 1 |" "| 1.5 | 52 | 1.73 |" "| 2.5 | 90 | 2.9 |"
  sed -i 's/the bus uses 0.5 kW\./the bus uses 0.5 kW and an efficiency of 0.6./' both.txt
  grep -q 'efficiency of 0.6' both.txt
  run -3 --separate-stderr "$BIN/helios-parse" both.txt -o both.json
  assert_one_error_line parse
  assert_stderr_contains "engine_efficiency (0.6)" "the thruster's table gives its performance"
  [[ ! -e both.json ]]
}

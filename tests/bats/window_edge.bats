#!/usr/bin/env bats
# A free departure whose cheapest date lies past its window (Earth to Mars, 0.5 N, 350 days, the
# cheapest departure about 2026-10-01T13:15): the answer departs at the window's end, never
# outside it, and costs what the same problem with the departure fixed at that date costs (an
# independent solve of another program). A window that holds the cheapest date returns it.

load test_helper

setup_file() {
  require_tool parse derive verify gen solve
}

setup() {
  common_setup
  echo '{}' >defaults.json
}

# mars_problem ID DEPARTURE_SENTENCE > problem.txt
mars_problem() {
  cat <<EOF
Problem $1: Earth to Mars.
The central body is the Sun with gravitational parameter 1.32712440018e11 km^3/s^2.
The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg.
The spacecraft departs from Earth.
$2
The time of flight is 350 days.
At the final time the spacecraft rendezvouses with Mars.
Minimize the fuel consumption.
EOF
}

@test "window edge: a departure window ending before the cheapest date returns its end, at the fixed-date cost" {
  mars_problem W1 "The departure date is free between 2026-08-01 and 2026-10-01." >w1.txt
  mars_problem W1F "The departure date is 2026-10-01." >w1f.txt
  run_chain w1.txt defaults.json w1
  run_chain w1f.txt defaults.json w1f
  local sol=w1/solution.json
  assert_jq "$sol" '.status == "converged" and .max_residual < 1e-10'
  # departs at the window's end (MJD2000 9770 is 2026-10-01), held there
  assert_jq "$sol" '.departure_date_tdb == "2026-10-01T00:00:00" and (.departure_mjd2000 - 9770 | fabs) < 1e-9'
  assert_jq "$sol" '.window_edges | length == 1 and .[0].variable == "t0_frac" and .[0].held_at == 1'
  assert_jq "$sol" '.window_edges[0].released_row == "transversality_t0" and (.window_edges[0].released_row_value | fabs) > 1e-4'
  # the extremal the search reached past the window is recorded, cheaper, and not returned
  assert_jq "$sol" '[.search.extremals[] | select(.outside_window)] | length >= 1'
  assert_jq "$sol" '([.search.extremals[] | select(.outside_window) | .objective] | min) < .search.extremals[.search.returned].objective'
  assert_jq "$sol" '.search.extremals[.search.returned].at_window_edge'
  # the same transfer as the problem with the departure fixed at the window's end
  assert_jq w1f/solution.json '.status == "converged"'
  local edge fixed
  edge=$(jq .propellant_kg "$sol")
  fixed=$(jq .propellant_kg w1f/solution.json)
  awk -v a="$edge" -v b="$fixed" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-8 * b) }' ||
    { echo "edge $edge kg, fixed departure $fixed kg" >&2; false; }
}

@test "window edge: a departure window holding the cheapest date returns it, inside the window" {
  mars_problem W2 "The departure date is free between 2026-09-01 and 2026-12-01." >w2.txt
  run_chain w2.txt defaults.json w2
  local sol=w2/solution.json
  assert_jq "$sol" '.status == "converged" and .max_residual < 1e-10 and .window_edges == null'
  assert_jq "$sol" '(.x[] | select(.name == "t0_frac") | .value) as $f | $f > 0.3 and $f < 0.4'
  assert_jq "$sol" '.departure_date_tdb | startswith("2026-10-01T")'
}

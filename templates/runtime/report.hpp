// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, report (templates/runtime/report.hpp): what the program's entry point
// (main.hpp) runs.
// usage: shoot [--parameters PARAMETERS.json] --settings SETTINGS.json --outcome OUTCOME.json
//              --trajectory TRAJECTORY.csv
// PARAMETERS.json replaces the problem's numbers (load_parameters) before anything reads them.
// Writes OUTCOME.json (solution.json's keys but helios-solve's own: normalized and physical
// numbers) and the trajectory of the final solution.
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

// A neighbour's shooting variables (helios-solve's "warm_start": {"variables": [names], "x":
// [values]}) in this problem's order. They are a guess only where they mean the same: the same
// variables under the same names (the same derivation shape), else the run is refused.
inline std::vector<double> warm_start_of(const nlohmann::json& w) {
  const auto& names = w.at("variables");
  const auto& values = w.at("x");
  if (!names.is_array() || !values.is_array() || names.size() != values.size())
    throw std::runtime_error("warm start: variables and x must be arrays of one length");
  if (static_cast<int>(names.size()) != kProblem.num_vars)
    throw std::runtime_error("warm start: the neighbour has " + std::to_string(names.size()) +
                             " shooting variables, this problem " + std::to_string(kProblem.num_vars));
  std::vector<double> x;
  for (int i = 0; i < kProblem.num_vars; ++i) {
    if (names[i].get<std::string>() != kProblem.variable_names[i])
      throw std::runtime_error("warm start: the neighbour's variable " + std::to_string(i) + " is " +
                               names[i].get<std::string>() + ", this problem's " + kProblem.variable_names[i]);
    x.push_back(values[i].get<double>());
    if (!std::isfinite(x.back())) throw std::runtime_error("warm start: a variable is not finite");
  }
  return x;
}

inline Settings read_settings(const std::string& path) {
  Settings s;
  if (path.empty()) return s;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read settings " + path);
  const nlohmann::json j = nlohmann::json::parse(in);
  s.seed = j.value("seed", s.seed);
  s.max_attempts = j.value("max_attempts", s.max_attempts);
  s.time_limit_s = j.value("time_limit_s", s.time_limit_s);
  s.rtol = j.value("integrator_rtol", s.rtol);
  s.atol = j.value("integrator_atol", s.atol);
  s.hybrd_tol = j.value("hybrd_tol", s.hybrd_tol);
  s.accept_residual = j.value("accept_residual", s.accept_residual);
  s.final_residual = j.value("final_residual", s.final_residual);
  s.eps_start = j.value("eps_start", s.eps_start);
  s.eps_min = j.value("eps_min", s.eps_min);
  s.eps_first_ratio = j.value("eps_first_ratio", s.eps_first_ratio);
  s.leg_attempts = j.value("leg_attempts", s.leg_attempts);
  s.search_starts = j.value("search_starts", s.search_starts);
  s.search_saturation = j.value("search_saturation", s.search_saturation);
  s.search_continued = j.value("search_continued", s.search_continued);
  s.search_attempts = j.value("search_attempts", s.search_attempts);
  s.search_time_s = j.value("search_time_s", s.search_time_s);
  s.search_continue_all = j.value("search_continue_all", s.search_continue_all);
  s.search_families = j.value("search_families", s.search_families);
  s.search_fuel_companion = j.value("search_fuel_companion", s.search_fuel_companion);
  s.search_thrust_continuation = j.value("search_thrust_continuation", s.search_thrust_continuation);
  s.search_fuel_from_time = j.value("search_fuel_from_time", s.search_fuel_from_time);
  s.threads = j.value("threads", s.threads);
  s.search_tol = j.value("search_integrator_tol", s.search_tol);
  s.node_spacing_days = j.value("node_spacing_days", s.node_spacing_days);
  s.jacobian = j.value("jacobian", s.jacobian);
  if (j.contains("warm_start")) {
    s.warm_start = warm_start_of(j.at("warm_start"));
    s.warm_only = j.at("warm_start").value("only", false);
  }
  return s;
}

// A residual as recorded: -1 where the evaluation failed (not finite).
inline double recorded(double residual) {
  return std::isfinite(residual) ? residual : -1.0;
}

inline void write_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".part";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp);
}

// What the re-propagated solution says: its switches, the largest drift of H over an arc, the
// states and times at its ends, and (with a mass state) the propellant and delta-v summed over the
// arcs; with a constant mass the L1 cost (normalized: the propellant it would burn or the delta-v,
// cost_is_delta_v) and the delta-v.
struct TrajectorySummary {
  std::vector<Switch> switches;
  double hamiltonian_drift = 0;
  std::vector<double> initial_state, final_state;
  double t0 = 0, tf = 0;
  double delta_v_m_s = 0, propellant = 0;
};

// Re-propagates the solution, recording samples and switches, and writes the trajectory CSV.
inline TrajectorySummary trajectory(const Settings& s, const Result& r, const std::string& csv_path) {
  const RecordedPath path = recorded_path(s, r.x, r.eps, (kProblem.tf - kProblem.t0) / 500, r.nodes, r.node_segments);
  const std::vector<Sample>& samples = path.samples;
  std::ostringstream csv;
  csv.precision(15);
  csv << "t_days";
  for (int i = 0; i < kProblem.num_states; ++i) csv << ',' << kProblem.state_columns[i];
  for (int i = 0; i < kProblem.num_states; ++i) csv << ",l_" << kProblem.state_names[i];
  for (int i = 0; i < kProblem.num_controls; ++i) csv << ',' << kProblem.control_names[i];
  csv << ",H,S\n";
  // H is constant on each arc (the dynamics are autonomous); it may jump at interior events.
  std::map<int, std::pair<double, double>> h_range;
  std::map<int, std::pair<double, double>> arc_mass;  // first and last mass of each arc
  // A constant mass: the integral of the throttle over the arcs (u = 1 without a throttle). A
  // sample holds the mode of the step that follows it: the left sums are exact at eps = 0.
  double throttle_integral = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Sample &a = samples[i - 1], &b = samples[i];
    if (a.arc != b.arc) continue;
    const int u = kProblem.throttle_index;
    const double ua = u >= 0 ? a.control[u] : 1.0, ub = u >= 0 ? b.control[u] : 1.0;
    throttle_integral += (b.t - a.t) * (r.eps == 0 ? ua : 0.5 * (ua + ub));
  }
  for (const auto& p : samples) {
    if (kProblem.mass_index >= 0) {
      auto& [first, last] = arc_mass.try_emplace(p.arc, p.y[kProblem.mass_index], 0.0).first->second;
      last = p.y[kProblem.mass_index];
      (void)first;
    }
    csv << p.t * kProblem.time_unit_days;
    for (int i = 0; i < kProblem.num_states; ++i) csv << ',' << p.y[i] * kProblem.state_to_physical[i];
    for (int i = 0; i < kProblem.num_states; ++i) csv << ',' << p.y[kProblem.num_states + i];
    for (int i = 0; i < kProblem.num_controls; ++i) csv << ',' << p.control[i];
    csv << ',' << p.H << ',' << p.S << '\n';
    auto& [lo, hi] = h_range.try_emplace(p.arc, INFINITY, -INFINITY).first->second;
    lo = std::min(lo, p.H);
    hi = std::max(hi, p.H);
  }
  write_atomic(csv_path, csv.str());
  TrajectorySummary out;
  out.switches = path.switches;
  for (const auto& [arc, range] : h_range)
    out.hamiltonian_drift = std::max(out.hamiltonian_drift, range.second - range.first);
  const auto& first = samples.front();
  const auto& last = samples.back();
  out.initial_state.assign(first.y.begin(), first.y.begin() + kProblem.num_states);
  out.final_state.assign(last.y.begin(), last.y.begin() + kProblem.num_states);
  // Delta-v by the rocket equation on each arc (a mass drop between arcs is not propellant).
  for (const auto& [arc, mass] : arc_mass) {
    out.delta_v_m_s += kProblem.exhaust_velocity_m_s * std::log(mass.first / mass.second);
    out.propellant += mass.first - mass.second;
  }
  if (constant_mass()) {
    // The L1 cost; the delta-v is the integral of Tmax u / m: the cost times c/m where the cost is
    // the propellant (m is the mass unit), else the cost itself.
    out.propellant = kProblem.throttle_cost_rate() * throttle_integral;
    out.delta_v_m_s = cost_is_delta_v() ? out.propellant * kProblem.speed_unit_km_s * 1e3
                                        : out.propellant * kProblem.exhaust_velocity_m_s;
  }
  out.t0 = first.t;
  out.tf = last.t;
  return out;
}

// A continuation step as solution.json records it (max_residual only where the evaluation was
// finite, revolutions where the continuation follows them).
inline nlohmann::ordered_json continuation_step_record(const ContinuationStep& c) {
  nlohmann::ordered_json step = {
      {"stage", c.stage}, {"value", c.value}, {"converged", c.converged}, {"evaluations", c.evaluations}};
  if (std::isfinite(c.max_residual)) step["max_residual"] = c.max_residual;
  if (std::isfinite(c.revolutions)) step["revolutions"] = c.revolutions;
  if (std::isfinite(c.tf_days)) step["tf_days"] = c.tf_days;
  return step;
}

// A finite objective in named units, under its key (propellant_kg, tof_days, final_radius_km...).
inline void objective_in_units(nlohmann::ordered_json& to, double objective) {
  if (std::isfinite(objective)) to[objective_key()] = objective_in_named_unit(objective);
}

// The distinct extremals at eps_start as solution.json records them ("search", "extremals_at_eps_start"),
// and a minimum-time problem's companion solutions, whose cost is propellant (`propellant`).
inline nlohmann::ordered_json start_extremals_record(const std::vector<StartExtremal>& list,
                                                     bool propellant = objective_is_propellant()) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const StartExtremal& e = list[i];
    nlohmann::ordered_json entry = {{"id", i},
                                    {"cost", recorded(e.shape.cost)},
                                    {"revolutions", e.shape.revolutions},
                                    {"mode_changes", e.shape.switches},
                                    {"reached", e.reached},
                                    {"first_start", e.first_start},
                                    {"max_residual", recorded(e.max_residual)},
                                    {"continued", e.continued},
                                    {"pruned", e.pruned}};
    if (std::isfinite(e.shape.cost)) {  // the smoothed problem's cost
      if (propellant)
        entry[cost_is_delta_v() ? "cost_m_s" : "cost_kg"] = e.shape.cost * fuel_cost_unit(true);
      else if (objective_is_final_state())
        objective_in_units(entry, e.shape.cost);
      else
        entry["cost_days"] = e.shape.cost * kProblem.time_unit_days;
    }
    if (e.arrived >= 0) entry["arrived_at"] = e.arrived;
    if (!e.origin.empty()) entry["origin"] = e.origin;
    out.push_back(entry);
  }
  return out;
}

// The distinct extremals at eps = 0 as solution.json records them ("search", "extremals").
inline nlohmann::ordered_json extremals_record(const std::vector<Extremal>& list) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Extremal& e = list[i];
    nlohmann::ordered_json entry = {{"id", i},
                                    {"objective", recorded(e.shape.cost)},
                                    {"revolutions", e.shape.revolutions},
                                    {"switches", e.shape.switches},
                                    {"reached", e.reached},
                                    {"first_start", e.first_start},
                                    {"from", e.from},
                                    {"max_residual", recorded(e.max_residual)},
                                    {"polished", e.polished},
                                    {"method", e.method}};
    if (e.outside_window) entry["outside_window"] = true;
    if (!e.window_edges.empty()) entry["at_window_edge"] = true;
    if (std::isfinite(e.tf_days)) entry["tf_days"] = e.tf_days;
    if (!e.route.empty()) entry["route"] = e.route;
    if (!e.shape.off_side.empty()) entry["off_side"] = e.shape.off_side;
    objective_in_units(entry, e.shape.cost);
    if (e.bounded_tried) {  // where the passes over the bounds led from this extremal
      nlohmann::ordered_json bounded = {{"converged", std::isfinite(e.bounded_objective)}};
      if (std::isfinite(e.bounded_objective)) {
        bounded["objective"] = e.bounded_objective;
        bounded["passes"] = e.bounded_passes;
        objective_in_units(bounded, e.bounded_objective);
      }
      entry["with_bounds"] = bounded;
    }
    out.push_back(entry);
  }
  return out;
}

// The global search as solution.json records it (schemas/solution.schema.json, "search").
inline nlohmann::ordered_json search_record(const SearchRecord& rec) {
  nlohmann::ordered_json out = {{"method", rec.method},
                                {"threads", rec.threads},
                                {"starts", rec.starts},
                                {"converged_at_eps_start", rec.converged_start},
                                {"events_off_draws", rec.eventless_draws},
                                {"continued", rec.continued},
                                {"converged_at_eps_0", rec.converged_final},
                                {"seconds", rec.seconds},
                                {"cut_by_time", rec.cut_by_time},
                                {"saturated", rec.saturated},
                                {"new_extremal_chance", rec.unseen},
                                {"stopped", rec.stopped},
                                {"extremals_at_eps_start", start_extremals_record(rec.start_extremals)},
                                {"extremals", extremals_record(rec.extremals)}};
  if (!rec.family.empty()) {
    nlohmann::ordered_json family = nlohmann::ordered_json::array();
    for (const FamilyProbe& p : rec.family) {
      nlohmann::ordered_json probe = {
          {"from", p.from}, {"direction", p.direction}, {"revolutions", p.revolutions}, {"how", p.how}};
      if (p.found >= 0) probe["found"] = p.found;
      family.push_back(probe);
    }
    out["family"] = family;
  }
  if (rec.companion_draws > 0)
    out["minimum_fuel_companion"] = {{"held_tf_days", rec.companion_tf_days},
                                     {"starts", rec.companion_draws},
                                     {"converged", rec.companion_converged},
                                     {"solutions", start_extremals_record(rec.companion_solutions, true)}};
  if (!rec.time_route.empty()) {
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (const auto& c : rec.time_route) steps.push_back(continuation_step_record(c));
    nlohmann::ordered_json paths = nlohmann::ordered_json::array();
    for (const auto& p : rec.time_route_paths)
      paths.push_back(
          {{"from", p.from},
           {"minimum_tf_days", std::isfinite(p.tf_min_days) ? nlohmann::ordered_json(p.tf_min_days) : nullptr},
           {"revolutions", std::isfinite(p.revolutions) ? nlohmann::ordered_json(p.revolutions) : nullptr},
           {"reached_before", p.reached_before},
           {"extremal", p.extremal}});
    out["minimum_time_route"] = {{"paths", paths}, {"steps", steps}};
  }
  if (!rec.thrust_continuation.empty()) {
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (const auto& c : rec.thrust_continuation) steps.push_back(continuation_step_record(c));
    out["thrust_continuation"] = {{"arrived", rec.thrust_continuation_arrived}, {"steps", steps}};
  }
  if (!rec.routes.empty()) {
    nlohmann::ordered_json routes = nlohmann::ordered_json::array();
    for (const auto& run : rec.routes)
      routes.push_back({{"name", run.name},
                        {"ran", run.ran},
                        {"outcome", run.outcome},
                        {"extremals_added", run.added},
                        {"evaluations", run.evaluations}});
    out["routes"] = routes;
  }
  if (std::isfinite(rec.minimum_time_days))
    out["minimum_time"] = {
        {"tf_days", rec.minimum_time_days},
        {"bound_days", std::isfinite(rec.bound_days) ? nlohmann::ordered_json(rec.bound_days) : nullptr},
        {"settled", rec.minimum_time_settled},
        {"how", rec.minimum_time_how}};
  if (!std::isnan(rec.coast_bound))
    out["minimum_time_and_coast"] = {{objective_key(), objective_in_named_unit(rec.coast_bound)}};
  if (rec.time_scale.factor > 0)
    out["time_scale"] = {
        {"factor", rec.time_scale.factor},
        {"raised_tf_days", std::isfinite(rec.time_scale.raised_tf_days)
                               ? nlohmann::ordered_json(rec.time_scale.raised_tf_days)
                               : nullptr},
        {"estimate_days",
         std::isfinite(rec.time_scale.estimate_days) ? nlohmann::ordered_json(rec.time_scale.estimate_days) : nullptr},
        {"revolutions",
         std::isfinite(rec.time_scale.revolutions) ? nlohmann::ordered_json(rec.time_scale.revolutions) : nullptr}};
  out["time_limit_hit"] = rec.time_limit_hit;
  if (rec.returned >= 0) {
    out["returned"] = rec.returned;
    out["reason"] = rec.reason;
  }
  return out;
}

// The solves that led to the result, as solution.json records them: the homotopy and
// continuation steps (max_residual only where the evaluation was finite), the legs, the bounds.
inline void steps_record(const Result& r, nlohmann::ordered_json& out) {
  out["homotopy"] = nlohmann::ordered_json::array();
  for (const auto& h : r.homotopy) {
    nlohmann::ordered_json step = {{"eps", h.eps}, {"converged", h.converged}, {"evaluations", h.evaluations}};
    if (std::isfinite(h.max_residual)) step["max_residual"] = h.max_residual;
    out["homotopy"].push_back(step);
  }
  out["method"] = r.method;
  if (!r.legs.empty()) {
    out["legs"] = nlohmann::ordered_json::array();
    for (const auto& l : r.legs)
      out["legs"].push_back({{"leg", l.leg},
                             {"converged", l.converged},
                             {"max_residual", recorded(l.max_residual)},
                             {"evaluations", l.evaluations}});
  }
  out["passes"] = r.passes;
  if (!r.bounds.empty()) {
    out["bounds"] = nlohmann::ordered_json::array();
    for (const auto& b : r.bounds)
      out["bounds"].push_back({{"name", b.name},
                               {"meaning", b.meaning},
                               {"first_pass_value", b.first_pass_value},
                               {"active", b.active},
                               {"value", b.value},
                               {"multiplier", b.multiplier}});
  }
  out["search"] = search_record(r.search);
  if (!r.continuation.empty()) {
    out["continuation"] = nlohmann::ordered_json::array();
    for (const auto& c : r.continuation) out["continuation"].push_back(continuation_step_record(c));
  }
}

// What the shooting function resolves at the solution: the largest |F_i(x') - F_i(x)| over the
// x' whose every component is k = 1..4 representable doubles away from x's (alternating in
// direction); with multiple shooting (nodes.hpp), of its variables and rows, the nodes too. A
// max_residual below it is luck, not accuracy: on S10 (2201 days to Jupiter past a swing-by)
// moving x by round-off moves single shooting's arrival rows by ~1e-10, at any integrator
// tolerance. -1 where F cannot be evaluated there.
inline double residual_noise(const Settings& s, const Result& r) {
  std::vector<double> solution = r.x;
  solution.insert(solution.end(), r.nodes.begin(), r.nodes.end());
  const int n = static_cast<int>(solution.size());
  const auto evaluate = [&](const std::vector<double>& z, Propagator& prop, double* F) {
    solution_function(z.data(), r.nodes.size(), r.eps, r.node_segments, prop, F);
  };
  Propagator prop(s);
  std::vector<double> at(static_cast<std::size_t>(n)), moved(at), x(at);
  double noise = 0;
  try {
    evaluate(solution, prop, at.data());
    for (int k = 1; k <= 4; ++k) {
      for (int i = 0; i < n; ++i) {
        x[i] = solution[i];
        for (int ulp = 0; ulp < k; ++ulp) x[i] = std::nextafter(x[i], (i + k) % 2 ? INFINITY : -INFINITY);
      }
      evaluate(x, prop, moved.data());
      for (int i = 0; i < n; ++i) noise = std::max(noise, std::fabs(moved[i] - at[i]));
    }
  } catch (const numerical_error&) {
    return -1;
  }
  return recorded(noise);
}

// A converged solution as solution.json records it: the physical results (from its re-propagation,
// which also writes the trajectory CSV), then the normalized ones.
inline void solution_record(const Settings& s, const Result& r, const std::string& trajectory_path,
                            nlohmann::ordered_json& out) {
  const TrajectorySummary path = trajectory(s, r, trajectory_path);
  out["tof_days"] = (path.tf - path.t0) * kProblem.time_unit_days;
  if (kProblem.epoch_mjd2000 != 0)
    out["departure_mjd2000"] = kProblem.epoch_mjd2000 + path.t0 * kProblem.time_unit_days;
  if (kProblem.mass_index >= 0) {  // a sail has no mass state
    out["initial_mass_kg"] = path.initial_state[kProblem.mass_index] * kProblem.mass_unit_kg;
    out["final_mass_kg"] = path.final_state[kProblem.mass_index] * kProblem.mass_unit_kg;
    out["propellant_kg"] = path.propellant * kProblem.mass_unit_kg;  // a mass drop is not propellant
    out["delta_v_m_s"] = path.delta_v_m_s;
  } else if (constant_mass()) {  // the mass throughout; the propellant where an exhaust velocity prices it
    out["initial_mass_kg"] = kProblem.mass_unit_kg;
    out["final_mass_kg"] = kProblem.mass_unit_kg;
    if (!cost_is_delta_v()) out["propellant_kg"] = path.propellant * kProblem.mass_unit_kg;
    out["delta_v_m_s"] = path.delta_v_m_s;
  }
  if (objective_is_final_state()) objective_in_units(out, final_state_cost(path.final_state.data()));
  out["epsilon"] = r.eps;
  out["max_residual"] = r.max_residual;
  out["residual_noise"] = residual_noise(s, r);
  nlohmann::ordered_json x = nlohmann::ordered_json::array(), F = nlohmann::ordered_json::array();
  for (int i = 0; i < kProblem.num_vars; ++i) F.push_back({{"name", kProblem.equation_names[i]}, {"value", r.F[i]}});
  for (int i = 0; i < kProblem.num_vars; ++i) x.push_back({{"name", kProblem.variable_names[i]}, {"value", r.x[i]}});
  out["residuals"] = F;
  out["x"] = x;
  if (!r.window_edges.empty()) {  // the edge route's (search/edge.hpp): its row replaced by frac - held
    nlohmann::ordered_json edges = nlohmann::ordered_json::array();
    for (const TimeWindow& w : time_windows())
      if (!std::isnan(r.window_edges[w.variable]))
        edges.push_back(
            {{"variable", kProblem.variable_names[w.variable]},
             {"held_at", r.window_edges[w.variable]},
             {"released_row", kProblem.equation_names[w.row]},
             {"released_row_value", std::isfinite(r.edge_transversality) ? nlohmann::ordered_json(r.edge_transversality)
                                                                         : nlohmann::ordered_json()}});
    out["window_edges"] = edges;
  }
  if (!r.nodes.empty()) {  // multiple shooting (nodes.hpp)
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array(), continuity = nlohmann::ordered_json::array(),
                           times = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < r.nodes.size(); ++i) {
      nodes.push_back({{"name", node_name(static_cast<int>(i))}, {"value", r.nodes[i]}});
      continuity.push_back({{"name", node_name(static_cast<int>(i))}, {"value", r.continuity[i]}});
    }
    for (const double t : r.node_times) times.push_back(t * kProblem.time_unit_days);
    out["multiple_shooting"] = {{"node_t_days", times},
                                {"segments_per_arc", r.node_segments},
                                {"nodes", nodes},
                                {"continuity", continuity},
                                {"single_shooting_max_residual", recorded(r.single_shooting_residual)}};
  }
  out["switches"] = nlohmann::ordered_json::array();
  for (const auto& w : path.switches)
    out["switches"].push_back({{"t_days", w.t * kProblem.time_unit_days}, {"throttle_after", w.throttle_after}});
  out["hamiltonian_drift"] = path.hamiltonian_drift;
}

// What the solve's integrations cost (counters.hpp), as solution.json records it ("integration"):
// taken before the final solution's re-propagation for the trajectory, so it counts the solve alone.
// "jacobian" says which every solve used: the shooting function's and its homotopies' (a leg
// alone, multiple shooting, the continuation onto the events, the bounds' shift).
inline nlohmann::ordered_json integration_record(const Settings& s) {
  const Counters& c = counters();
  const double seconds = static_cast<double>(c.integration_ns.load()) * 1e-9;
  return {{"integrations", c.integrations.load()},
          {"integration_s", seconds},
          {"solve_s", wall_seconds()},
          {"residual_evaluations", c.residual_evaluations.load()},
          {"jacobian", exact_jacobian(s) ? "exact" : "finite-difference"},
          {"jacobian_evaluations", c.jacobian_evaluations.load()},
          {"jacobian_residual_evaluations", c.jacobian_residual_calls.load()},
          {"exact_jacobian_evaluations", c.exact_jacobian_evaluations.load()}};
}

// The outcome of the solve under schemas/solution.schema.json's keys: every key but those
// helios-solve alone knows (the artifact's header, the compile, the settings, the timings, the
// files), which it adds.
inline nlohmann::ordered_json outcome_record(const Settings& s, const Result& r, const std::string& trajectory_path) {
  nlohmann::ordered_json out;
  out["problem"] = {{"id", kProblem.id}};
  out["status"] = status_text(r.status);
  if (!r.detail.empty()) out["status_detail"] = r.detail;
  out["solver_info"] = {{"code", r.info}, {"meaning", hybrd_meaning(r.info)}};
  out["seed"] = s.seed;
  out["restarts"] = std::max(0, r.attempts - 1);
  out["iterations"] = r.iterations;
  out["function_evaluations"] = r.evaluations;
  out["start"] = r.start;
  if (!r.start_detail.empty()) out["start_detail"] = r.start_detail;
  out["integration"] = integration_record(s);
  steps_record(r, out);
  if (r.status == Status::kConverged) solution_record(s, r, trajectory_path, out);
  return out;
}

// The problem's sizes within what the library's arrays hold.
inline void check_problem_shape() {
  if (kProblem.num_states < 1 || kProblem.num_states > kMaxStates || kProblem.num_controls < 0 ||
      kProblem.num_controls > kMaxControls || kProblem.throttle_index >= kProblem.num_controls || kProblem.num_vars < 1)
    throw std::runtime_error("the problem has " + std::to_string(kProblem.num_states) + " states and " +
                             std::to_string(kProblem.num_controls) + " controls; this runtime holds at most " +
                             std::to_string(kMaxStates) + " states and " + std::to_string(kMaxControls) +
                             " controls (helios_runtime.hpp's kMaxStates, kMaxControls)");
  if (kProblem.throttle_index >= 0 && !kModules.throttle_slopes)
    throw std::runtime_error(
        "the problem has a throttle but the program's module table (kModules) names no throttle_slopes");
}

}  // namespace

const char* status_text(Status status) {
  switch (status) {
    case Status::kConverged:
      return "converged";
    case Status::kInfeasible:
      return "infeasible";
    case Status::kNotConverged:
      return "not_converged";
    case Status::kTimeout:
      return "timeout";
    case Status::kNotSolved:
      break;
  }
  return "not_solved";
}

int run(int argc, char** argv) {
  std::string settings_path, parameters_path, outcome_path = "outcome.json", trajectory_path = "trajectory.csv";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--settings")
      settings_path = argv[i + 1];
    else if (a == "--parameters")
      parameters_path = argv[i + 1];
    else if (a == "--outcome")
      outcome_path = argv[i + 1];
    else if (a == "--trajectory")
      trajectory_path = argv[i + 1];
    else
      throw std::runtime_error("unknown option " + a);
  }
  // The problem's numbers first: everything below reads them (the settings' eps_start too).
  if (!parameters_path.empty()) load_parameters(parameters_path);
  check_problem_shape();
  const Settings s = read_settings(settings_path);
  wall_seconds();
  const Result solved = solve_problem(s);
  // What follows evaluates the shooting function at the solution: with the active set it ended on.
  Settings at_solution = s;
  for (const BoundReport& b : solved.bounds) at_solution.active_bounds.push_back(b.active ? 1 : 0);
  at_solution.window_edges = solved.window_edges;
  Result r = solved;
  polish_by_nodes(at_solution, r);
  write_atomic(outcome_path, outcome_record(at_solution, r, trajectory_path).dump(2) + "\n");
  return 0;
}

}  // namespace helios_rt

// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, entry point (templates/runtime/main.hpp).
// usage: shoot --settings SETTINGS.json --result RESULT.json --trajectory TRAJECTORY.csv
// Writes RESULT.json (normalized and physical numbers) and the trajectory of the final solution.
// ---------------------------------------------------------------------------------------------
namespace helios_rt {

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
  s.threads = j.value("threads", s.threads);
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

// Re-propagates the solution, recording samples and switches, and writes the trajectory CSV.
inline nlohmann::json trajectory(const Settings& s, const Result& r, const std::string& csv_path) {
  const RecordedPath path = recorded_path(s, r.x, r.eps, (problem::kTf - problem::kT0) / 500);
  const std::vector<Sample>& samples = path.samples;
  const std::vector<Switch>& switches = path.switches;
  std::ostringstream csv;
  csv.precision(15);
  csv << "t_days";
  for (int i = 0; i < problem::kNumStates; ++i) csv << ',' << problem::kStateColumns[i];
  for (int i = 0; i < problem::kNumStates; ++i) csv << ",l_" << problem::kStateNames[i];
  for (int i = 0; i < problem::kNumControls; ++i) csv << ',' << problem::kControlNames[i];
  csv << ",H,S\n";
  // H is constant on each arc (the dynamics are autonomous); it may jump at interior events.
  std::map<int, std::pair<double, double>> h_range;
  std::map<int, std::pair<double, double>> arc_mass;  // first and last mass of each arc
  for (const auto& p : samples) {
    if constexpr (problem::kMassIndex >= 0) {
      auto& [first, last] = arc_mass.try_emplace(p.arc, p.y[problem::kMassIndex], 0.0).first->second;
      last = p.y[problem::kMassIndex];
      (void)first;
    }
    csv << p.t * problem::kTimeUnitDays;
    for (int i = 0; i < problem::kNumStates; ++i) csv << ',' << p.y[i] * problem::kStateToPhysical[i];
    for (int i = 0; i < problem::kNumStates; ++i) csv << ',' << p.y[problem::kNumStates + i];
    for (int i = 0; i < problem::kNumControls; ++i) csv << ',' << p.control[i];
    csv << ',' << p.H << ',' << p.S << '\n';
    auto& [lo, hi] = h_range.try_emplace(p.arc, INFINITY, -INFINITY).first->second;
    lo = std::min(lo, p.H);
    hi = std::max(hi, p.H);
  }
  write_atomic(csv_path, csv.str());
  nlohmann::json out;
  nlohmann::json sw = nlohmann::json::array();
  for (const auto& w : switches)
    sw.push_back({{"t_days", w.t * problem::kTimeUnitDays}, {"throttle_after", w.throttle_after}});
  out["switches"] = sw;
  double drift = 0;
  for (const auto& [arc, range] : h_range) drift = std::max(drift, range.second - range.first);
  out["hamiltonian_drift"] = drift;  // the largest over the arcs
  out["samples"] = samples.size();
  const auto& last = samples.back();
  out["initial_state"] =
      std::vector<double>(samples.front().y.begin(), samples.front().y.begin() + problem::kNumStates);
  out["final_state"] = std::vector<double>(last.y.begin(), last.y.begin() + problem::kNumStates);
  if constexpr (problem::kMassIndex >= 0) {
    // Delta-v by the rocket equation on each arc (a mass drop between arcs is not propellant).
    double dv = 0, propellant = 0;
    for (const auto& [arc, mass] : arc_mass) {
      dv += problem::kExhaustVelocityMS * std::log(mass.first / mass.second);
      propellant += mass.first - mass.second;
    }
    out["delta_v_m_s"] = dv;
    out["propellant"] = propellant;
  }
  out["t0"] = samples.front().t;
  out["tf"] = last.t;
  return out;
}

// A finite objective in named units: the propellant under `mass_key`, or the flight time under
// `time_key`.
inline void objective_in_units(nlohmann::json& to, double objective, const char* mass_key = "propellant_kg",
                               const char* time_key = "tof_days") {
  if (std::isfinite(objective)) to[kObjectiveIsPropellant ? mass_key : time_key] = objective_in_named_unit(objective);
}

// The global search as solution.json records it (schemas/solution.schema.json, "search").
inline nlohmann::json search_record(const SearchRecord& rec) {
  nlohmann::json at_start = nlohmann::json::array(), extremals = nlohmann::json::array();
  for (std::size_t i = 0; i < rec.start_extremals.size(); ++i) {
    const StartExtremal& e = rec.start_extremals[i];
    nlohmann::json entry = {{"id", i},
                            {"cost", recorded(e.shape.cost)},
                            {"revolutions", e.shape.revolutions},
                            {"mode_changes", e.shape.switches},
                            {"reached", e.reached},
                            {"first_start", e.first_start},
                            {"max_residual", recorded(e.max_residual)},
                            {"continued", e.continued}};
    objective_in_units(entry, e.shape.cost, "cost_kg", "cost_days");  // the smoothed problem's cost
    if (e.arrived >= 0) entry["arrived_at"] = e.arrived;
    at_start.push_back(entry);
  }
  for (std::size_t i = 0; i < rec.extremals.size(); ++i) {
    const Extremal& e = rec.extremals[i];
    nlohmann::json entry = {{"id", i},
                            {"objective", recorded(e.shape.cost)},
                            {"revolutions", e.shape.revolutions},
                            {"switches", e.shape.switches},
                            {"reached", e.reached},
                            {"first_start", e.first_start},
                            {"from", e.from},
                            {"max_residual", recorded(e.max_residual)},
                            {"method", e.method}};
    objective_in_units(entry, e.shape.cost);
    if (e.bounded_tried) {  // where the passes over the bounds led from this extremal
      nlohmann::json bounded = {{"converged", std::isfinite(e.bounded_objective)}};
      if (std::isfinite(e.bounded_objective)) {
        bounded["objective"] = e.bounded_objective;
        bounded["passes"] = e.bounded_passes;
        objective_in_units(bounded, e.bounded_objective);
      }
      entry["with_bounds"] = bounded;
    }
    extremals.push_back(entry);
  }
  nlohmann::json out = {{"method", rec.method},
                        {"threads", rec.threads},
                        {"starts", rec.starts},
                        {"converged_at_eps_start", rec.converged_start},
                        {"continued", rec.continued},
                        {"converged_at_eps_0", rec.converged_final},
                        {"seconds", rec.seconds},
                        {"cut_by_time", rec.cut_by_time},
                        {"extremals_at_eps_start", at_start},
                        {"extremals", extremals}};
  if (rec.returned >= 0) {
    out["returned"] = rec.returned;
    out["reason"] = rec.reason;
  }
  return out;
}

inline int run(int argc, char** argv) {
  std::string settings_path, result_path = "result.json", trajectory_path = "trajectory.csv";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--settings")
      settings_path = argv[i + 1];
    else if (a == "--result")
      result_path = argv[i + 1];
    else if (a == "--trajectory")
      trajectory_path = argv[i + 1];
    else
      throw std::runtime_error("unknown option " + a);
  }
  const Settings s = read_settings(settings_path);
  wall_seconds();
  Result r = solve_problem(s);
  nlohmann::json j;
  j["problem"] = problem::kProblemId;
  j["status"] = r.status;
  j["detail"] = r.detail;
  j["info"] = r.info;
  j["info_meaning"] = hybrd_meaning(r.info);
  j["attempts"] = r.attempts;
  j["iterations"] = r.iterations;
  j["function_evaluations"] = r.evaluations;
  j["seed"] = s.seed;
  nlohmann::json hom = nlohmann::json::array();
  for (const auto& h : r.homotopy)
    hom.push_back({{"eps", h.eps},
                   {"converged", h.converged},
                   {"max_residual", recorded(h.max_residual)},
                   {"evaluations", h.evaluations}});
  j["homotopy"] = hom;
  j["method"] = r.method;
  j["passes"] = r.passes;
  if (!r.bounds.empty()) {
    nlohmann::json bounds = nlohmann::json::array();
    for (const auto& b : r.bounds)
      bounds.push_back({{"name", b.name},
                        {"meaning", b.meaning},
                        {"first_pass_value", b.first_pass_value},
                        {"active", b.active},
                        {"value", b.value},
                        {"multiplier", b.multiplier}});
    j["bounds"] = bounds;
  }
  j["search"] = search_record(r.search);
  if (!r.continuation.empty()) {
    nlohmann::json steps = nlohmann::json::array();
    for (const auto& c : r.continuation)
      steps.push_back({{"stage", c.stage},
                       {"value", c.value},
                       {"converged", c.converged},
                       {"max_residual", recorded(c.max_residual)},
                       {"evaluations", c.evaluations}});
    j["continuation"] = steps;
  }
  if (!r.legs.empty()) {
    nlohmann::json legs = nlohmann::json::array();
    for (const auto& l : r.legs)
      legs.push_back({{"leg", l.leg},
                      {"converged", l.converged},
                      {"max_residual", recorded(l.max_residual)},
                      {"evaluations", l.evaluations}});
    j["legs"] = legs;
  }
  if (r.status == "converged") {
    nlohmann::json x = nlohmann::json::array(), F = nlohmann::json::array();
    for (int i = 0; i < problem::kNumVars; ++i) x.push_back({{"name", problem::kVariableNames[i]}, {"value", r.x[i]}});
    for (int i = 0; i < problem::kNumVars; ++i) F.push_back({{"name", problem::kEquationNames[i]}, {"value", r.F[i]}});
    j["x"] = x;
    j["residuals"] = F;
    j["max_residual"] = r.max_residual;
    j["epsilon"] = r.eps;
    j["trajectory"] = trajectory(s, r, trajectory_path);
    const auto& path = j["trajectory"];
    j["tof_days"] = (path["tf"].get<double>() - path["t0"].get<double>()) * problem::kTimeUnitDays;
    if (problem::kEpochMjd2000 != 0)
      j["departure_mjd2000"] = problem::kEpochMjd2000 + path["t0"].get<double>() * problem::kTimeUnitDays;
    if constexpr (problem::kMassIndex >= 0) {
      const double m0 = path["initial_state"][problem::kMassIndex].get<double>();
      const double mf = path["final_state"][problem::kMassIndex].get<double>();
      j["final_mass_kg"] = mf * problem::kMassUnitKg;
      j["initial_mass_kg"] = m0 * problem::kMassUnitKg;
      j["delta_v_m_s"] = path["delta_v_m_s"];
      j["propellant_kg"] = path["propellant"].get<double>() * problem::kMassUnitKg;
    }
  }
  write_atomic(result_path, j.dump(2) + "\n");
  return 0;
}

}  // namespace helios_rt

int main(int argc, char** argv) {
  try {
    return helios_rt::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shoot: error: %s\n", e.what());
    return 1;
  }
}

// The PROBLEM block: the problem's constants, names and units in namespace problem.
#include "context.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

#include "helios/pmp/catalogue.hpp"

namespace helios::codegen::detail {
namespace {

// The column name and factor of a state in the trajectory's physical units (km, km/s, kg), by its
// unit; a state of any other unit keeps its normalized value.
std::pair<std::string, double> physical(const derivation::Units& units, const derivation::Quantity& state) {
  const double to_km_s_kg = derivation::Units::factor(state.unit, units.length_km, units.time_s, units.mass_kg);
  if (state.unit == derivation::Unit{1, 0, 0}) return {state.name + "_km", to_km_s_kg};
  if (state.unit == derivation::Unit{1, -1, 0}) return {state.name + "_km_s", to_km_s_kg};
  if (state.unit == derivation::Unit{0, 0, 1}) return {state.name + "_kg", to_km_s_kg};
  return {state.name, 1.0};
}

// The runtime's Objective of the derivation's problem.objective.
std::string runtime_objective(const std::string& objective) {
  if (objective == "minimum_time") return "time";
  if (objective == "minimum_fuel" || objective == "minimum_initial_mass") return "propellant";
  if (objective == "maximum_final_radius") return "final_radius";
  if (objective == "maximum_final_energy") return "final_energy";
  throw std::invalid_argument("field /problem/objective: '" + objective + "' is no objective the runtime knows");
}

// Whether a coast keeps the final constraint: the constraint at tf is an orbit insertion (an orbit
// with the position on it free: the spec's orbit targets never fix an anomaly) and the listed
// forces are the central body's and the thrust alone (a perturbation drifts the orbit's elements
// during the coast). A derivation without a terms listing: false.
bool final_coast_keeps_target(const Context& c) {
  if (!c.terms) return false;
  for (const auto& t : *c.terms)
    if (t.kind == "force" && t.name != "two_body" && t.name != "thrust" && t.name != "constant_mass_thrust" &&
        t.name != "solar_electric_thrust")
      return false;
  bool orbit = false;
  for (const auto& k : c.constraints) {
    if (k.at != "tf") continue;
    if (k.kind != "orbit_insertion") return false;
    orbit = true;
  }
  return orbit && c.interior_events.empty();
}

// An engine of constant mass (a constant_mass_thrust or constant_mass_full_thrust term, listing
// Tmax, the mass and, where a specific impulse prices the propellant, the exhaust velocity): the rate
// of its L1 cost at full throttle, Tmax/c or Tmax/mass, as C++ over the parameters; "" for any other.
std::string throttle_cost_rate(const Context& c) {
  if (!c.terms) return "";
  for (const auto& t : *c.terms) {
    if (t.kind != "force" || t.name.rfind("constant_mass_", 0) != 0) continue;
    if (t.parameters.size() != 2 && t.parameters.size() != 3)
      throw std::invalid_argument("field /terms: the term " + t.name +
                                  " lists Tmax, the mass and (optional) the exhaust velocity, got " +
                                  std::to_string(t.parameters.size()) + " parameters");
    return "problem::" + t.parameters[0] + " / problem::" + t.parameters.back();
  }
  return "";
}

// The bodies on their Keplerian orbits: a parameter array each and the list the runtime reads
// ("" without bodies).
std::string orbit_bodies(const std::vector<derivation::Body>& bodies) {
  if (bodies.empty()) return "";
  std::ostringstream o;
  o << "// Bodies on their Keplerian orbits: a (normalized), e, i, raan, argp, mean anomaly (rad) and the\n"
    << "// normalized time of the elements.\n";
  std::string list;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const derivation::Body& b = bodies[k];
    const std::string name = "kOrbitBody" + std::to_string(k);
    o << "HELIOS_PARAMETER_ARRAY(" << name << ", " << number(b.a) << ", " << number(b.e) << ", " << number(b.i_rad)
      << ", " << number(b.raan_rad) << ", " << number(b.argp_rad) << ", " << number(b.mean_anomaly_rad) << ", "
      << number(b.epoch) << ");  // " << comment_text(b.name) << "\n";
    list += (list.empty() ? "" : ", ") + std::string("{") + cpp_string(b.name) + ", " + name + "}";
  }
  o << "const helios_rt::OrbitBody kOrbitBodies[] = {" << list << "};\n";
  return o.str();
}

// What the runtime reads of the engine: an engine of constant mass's full-throttle cost rate
// (`rate`, "" for none), the parameters of role thrust_scale (the thrust continuation multiplies
// them) and whether the full-throttle mass flow follows the position (a solar-electric engine: T(r)).
std::string engine_contract(const Context& c, const std::string& rate, const std::vector<std::string>& scale) {
  std::ostringstream o;
  if (!rate.empty())
    o << "// An engine of constant mass: the rate of its L1 cost at full throttle (the propellant it would\n"
      << "// burn, or the delta-v without an exhaust velocity), read when called: it follows the thrust.\n"
      << "inline double ThrottleCostRate() { return " << rate << "; }\n";
  bool flow_varies = false;
  if (c.terms)
    for (const auto& t : *c.terms) flow_varies = flow_varies || pmp::find_term(t.name)->varying_flow;
  o << "// The parameters the thrust is proportional to (role thrust_scale), and whether the mass flow\n"
    << "// follows the position (a solar-electric engine).\n"
    << "const char* const kThrustScale[] = {" << (scale.empty() ? "" : quoted_list(scale) + ", ") << "nullptr};\n"
    << "constexpr bool kMassFlowVaries = " << (flow_varies ? "true" : "false") << ";\n";
  return o.str();
}

}  // namespace

std::string problem_block(Context& c) {
  const derivation::Times& times = c.times;
  if (!times.tf && times.tf_window.size() != 2)
    throw std::invalid_argument("field /times: a free final time needs tf_window [lo, hi]");
  const double tf = times.tf ? *times.tf : times.tf_window[1];
  const double tf_min = times.tf ? *times.tf : times.tf_window[0];
  if (!(tf > times.t0))
    throw std::invalid_argument("field /times: the final time " + json(tf).dump() + " is not after t0 " +
                                json(times.t0).dump());
  std::ostringstream o;
  o << "// ----- PROBLEM (generated) -----------------------------------------------------------------\n"
    << "namespace problem {\n"
    << "const char* const kProblemId = " << cpp_string(c.problem_id) << ";\n"
    << "constexpr int kNumStates = " << c.states.size() << ";\n"
    << "constexpr int kNumControls = " << c.controls.size() << ";\n"
    << "constexpr int kThrottleIndex = " << c.throttle_index << ";\n"
    << "constexpr int kNumVars = " << c.shooting.variables.size() << ";\n"
    << "constexpr int kMassIndex = " << index_of(c.states, "m") << ";\n"
    << "constexpr bool kHasEvents = " << (c.interior_events.empty() ? "false" : "true")
    << ";  // the module table names shooting_legs\n"
    << "constexpr bool kCoastingTarget = " << (c.coast_dynamics ? "true" : "false")
    << ";  // the module table names coast_dynamics\n"
    << "// The objective the search minimizes.\n"
    << "constexpr helios_rt::Objective kObjective = helios_rt::Objective::" << runtime_objective(c.objective) << ";\n"
    << "// The problem's numbers: globals set from these literals, which a parameters file may replace\n"
    << "// at run time (shoot --parameters; helios_runtime.hpp's HELIOS_PARAMETER).\n"
    << "HELIOS_PARAMETER(kT0, " << number(times.t0) << ");\n"
    << "// The final time, or the upper end of its window when it is free.\n"
    << "HELIOS_PARAMETER(kTf, " << number(tf) << ");\n"
    << "// The lower end of the final time's window (kTf when the final time is fixed).\n"
    << "HELIOS_PARAMETER(kTfMin, " << number(tf_min) << ");\n"
    << "HELIOS_PARAMETER(kHomotopyStart, " << number(c.homotopy_start) << ");\n"
    << "HELIOS_PARAMETER(kTimeUnitDays, " << number(c.units.time_s / 86400.0) << ");\n"
    << "HELIOS_PARAMETER(kLengthUnitKm, " << number(c.units.length_km) << ");\n"
    << "HELIOS_PARAMETER(kSpeedUnitKmS, " << number(c.units.length_km / c.units.time_s) << ");\n"
    << "HELIOS_PARAMETER(kEpochMjd2000, " << number(times.epoch_mjd2000.value_or(0.0)) << ");\n"
    << "HELIOS_PARAMETER(kMassUnitKg, " << number(c.units.mass_kg) << ");\n";
  const derivation::Quantity* exhaust = c.exhaust_velocity();
  o << "HELIOS_PARAMETER(kExhaustVelocityMS, " << number(exhaust ? c.units.to_si(exhaust->value, exhaust->unit) : 0.0)
    << ");\n";
  std::vector<std::string> columns;
  std::string factors;
  for (const auto& s : c.state_quantities) {
    const auto [col, f] = physical(c.units, s);
    columns.push_back(col);
    factors += ", " + number(f);
  }
  std::vector<std::string> vars, eqs;
  for (const auto& v : c.shooting.variables) vars.push_back(v.name);
  for (const auto& e : c.shooting.equations) eqs.push_back(e.name);
  o << "HELIOS_PARAMETER_ARRAY(kStateToPhysical" << factors << ");\n"
    << "const char* const kStateNames[] = {" << quoted_list(c.states) << "};\n"
    << "const char* const kStateColumns[] = {" << quoted_list(columns) << "};\n"
    << "const char* const kControlNames[] = {" << quoted_list(c.controls) << "};\n"
    << "const char* const kVariableNames[] = {" << quoted_list(vars) << "};\n"
    << "const char* const kEquationNames[] = {" << quoted_list(eqs) << "};\n";
  const std::vector<derivation::Body>& bodies = c.bodies;
  o << orbit_bodies(bodies);
  for (const auto& p : c.parameter_quantities)
    if (!p.runtime_evaluated())
      o << "HELIOS_PARAMETER(" << p.name << ", " << number(p.value) << ");  // "
        << comment_text(p.meaning + " [" + p.unit_text + "]") << "\n";
  const std::string rate = throttle_cost_rate(c);
  std::vector<std::string> scale;
  for (const auto& p : c.parameter_quantities)
    if (p.role == derivation::Role::ThrustScale) scale.push_back(p.name);
  o << engine_contract(c, rate, scale);
  o << "constexpr bool kFinalCoastKeepsTarget = " << (final_coast_keeps_target(c) ? "true" : "false")
    << ";  // a coast keeps the final constraint (an orbit, two-body forces)\n";
  o << "}  // namespace problem\n\n"
    << "// The problem's shape as the runtime library reads it (helios_runtime.hpp's ProblemShape).\n"
    << "namespace helios_rt {\n"
    << "constexpr int kNY = 2 * problem::kNumStates;  // states then costates\n"
    << "const ProblemShape kProblem = {problem::kProblemId, problem::kNumStates, problem::kNumControls,\n"
    << "                               problem::kThrottleIndex, problem::kNumVars, problem::kMassIndex,\n"
    << "                               problem::kObjective, problem::kT0, problem::kTf, problem::kTfMin,\n"
    << "                               problem::kHomotopyStart,\n"
    << "                               problem::kTimeUnitDays, problem::kLengthUnitKm, problem::kSpeedUnitKmS,\n"
    << "                               problem::kEpochMjd2000, problem::kMassUnitKg, problem::kExhaustVelocityMS,\n"
    << "                               problem::mu, problem::kStateNames, problem::kStateColumns,\n"
    << "                               problem::kStateToPhysical, problem::kControlNames, problem::kVariableNames,\n"
    << "                               problem::kEquationNames, "
    << (bodies.empty() ? "nullptr, 0" : "problem::kOrbitBodies, " + std::to_string(bodies.size()))
    << ", problem::kFinalCoastKeepsTarget, " << (rate.empty() ? "nullptr" : "problem::ThrottleCostRate")
    << ",\n                               " << (scale.empty() ? "nullptr" : "problem::kThrustScale")
    << ", problem::kMassFlowVaries};\n"
    << "}  // namespace helios_rt\n";
  return o.str();
}

}  // namespace helios::codegen::detail

// The RESIDUAL module: the shooting function (by legs for events), the leg and event plans.
#include "context.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios::codegen::detail {
namespace {

// Runtime-evaluated parameters grouped by source "<kind>:<what>:<event>", names in order.
std::map<std::string, std::vector<std::string>> runtime_parameters(const json& d, const std::string& kind) {
  std::map<std::string, std::vector<std::string>> groups;
  for (const auto& p : d.at("parameters")) {
    const std::string source = p.value("source", "");
    if (source.rfind(kind + ":", 0) == 0) groups[source.substr(kind.size() + 1)].push_back(p.at("name"));
  }
  for (const auto& [key, names] : groups)
    if (names.size() != 6)
      throw std::invalid_argument("field /parameters: " + kind + " target " + key + " needs 6 components, got " +
                                  std::to_string(names.size()));
  return groups;
}

// The C++ local holding the time of `event`: t0, tf, an interior event's epoch t_<id> or the end
// of its stay t_<id>_dep.
std::string event_time(const Context& c, const std::string& event) {
  if (event == "t0" || event == "tf") return event;
  for (const auto& id : c.events)
    if (event == id || event == id + "_dep") return "t_" + event;
  throw std::invalid_argument("field /parameters: unknown event '" + event + "' (t0, tf or an interior event)");
}

// The events' variables and rows for the continuation onto the events (runtime EventPlan): each
// event's constraint rows psi_<id>_j with their multipliers, its free-epoch row time_<id> with the
// epoch fraction, its parameters' stationarity rows. An event is passable when it is instantaneous
// and its state map is the identity with its parameters at 0 (checked at random points); anything
// not found makes the plan not passable (the runtime then solves by legs only).
std::string event_plan_block(Context& c) {
  const json& d = c.d;
  const auto& vars = d.at("shooting").at("variables");
  const auto& eqs = d.at("shooting").at("equations");
  const std::vector<std::string>& var_names = c.variables;
  std::vector<std::string> eq_names;
  for (const auto& e : eqs) eq_names.push_back(e.at("name"));
  const std::vector<std::string> sphere = c.sphere_variables();
  bool passable = true;
  std::ostringstream events;
  for (const auto& e : d.at("events")) {
    const std::string id = e.at("id");
    const auto& psi = e.at("psi");
    const auto& multipliers = e.at("multipliers");
    const std::size_t nc = psi.size() >= c.states.size() ? psi.size() - c.states.size() : 0;
    std::string constraints, parameters, costates;
    // The costates after the event that are shooting variables, with their jump rows.
    for (std::size_t i = 0; i < c.states.size() && i < e.at("costate_map").size(); ++i) {
      const json& m = e.at("costate_map")[i];
      if (!m.contains("variable")) continue;
      const int v = index_of(var_names, m.at("variable").get<std::string>());
      const int row = index_of(eq_names, "jump_" + id + "_" + c.states[i]);
      if (v < 0 || row < 0) passable = false;
      costates += (costates.empty() ? "{" : ", {") + std::to_string(v) + ", " + std::to_string(row) + "}";
    }
    for (std::size_t j = 0; j < nc && j < multipliers.size(); ++j) {
      const int v = index_of(var_names, multipliers[j].get<std::string>());
      const int row = index_of(eq_names, "psi_" + id + "_" + std::to_string(j + 1));
      if (v < 0 || row < 0) passable = false;
      constraints += (constraints.empty() ? "{" : ", {") + std::to_string(v) + ", " + std::to_string(row) + "}";
    }
    if (nc == 0 || multipliers.size() < nc) passable = false;
    // The epoch fraction: the time_fraction variable of the event's time expression.
    int epoch_var = -1;
    for (const auto& name :
         symbolic::free_symbols(c.symbols.parse(e.at("time").at("expression"), "field /events/time/expression"))) {
      const int v = index_of(var_names, name);
      if (v >= 0 && vars[v].value("role", "") == "time_fraction") epoch_var = v;
    }
    const int epoch_row = index_of(eq_names, "time_" + id);
    if ((epoch_var < 0) != (epoch_row < 0)) passable = false;
    // The event's parameters: role "parameter" variables its psi or state map depends on.
    std::vector<std::string> used;
    for (const auto& text : psi) {
      const auto names = symbolic::free_symbols(c.symbols.parse(text, "field /events/psi"));
      used.insert(used.end(), names.begin(), names.end());
    }
    std::vector<std::string> own_parameters;
    for (std::size_t i = 0; i < vars.size(); ++i)
      if (vars[i].value("role", "") == "parameter" && index_of(used, var_names[i]) >= 0) {
        const int row = index_of(eq_names, "stationarity_" + id + "_" + var_names[i]);
        if (row < 0) passable = false;
        own_parameters.push_back(var_names[i]);
        parameters += (parameters.empty() ? "{" : ", {") + std::to_string(i) + ", " + std::to_string(row) + "}";
      }
    // Instantaneous, and x+ = x- with the parameters at 0.
    if (e.at("time").value("duration", 0.0) != 0.0) passable = false;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> dist(0.3, 1.7);
    for (int trial = 0; trial < 3 && passable; ++trial) {
      symbolic::Values values;
      for (const auto& [name, sym] : c.symbols.symtab()) values[name] = dist(rng) * (rng() % 2 ? 1 : -1);
      for (const auto& q : own_parameters) values[q] = 0;
      for (std::size_t i = 0; i < c.states.size() && passable; ++i) {
        try {
          const double after = symbolic::evaluate(
              c.symbols.parse(e.at("state_map")[i].at("expression"), "field /events/state_map"), c.symbols, values);
          const double before = values.at(c.states[i] + "_" + id + "_m");
          if (std::fabs(after - before) > 1e-10 * (1 + std::fabs(after) + std::fabs(before))) passable = false;
        } catch (const std::exception&) {
          passable = false;
        }
      }
    }
    events << "{{" << constraints << "}, {" << epoch_var << ", " << epoch_row << "}, {" << parameters << "}, {"
           << costates << "}}, ";
  }
  std::string sphere_list;
  for (const auto& name : sphere) {
    const int v = index_of(var_names, name);
    if (v < 0) passable = false;
    sphere_list += (sphere_list.empty() ? "" : ", ") + std::to_string(v);
  }
  const int multiplier = index_of(var_names, d.at("multiplier").get<std::string>());
  if (multiplier < 0 || index_of(sphere, d.at("multiplier").get<std::string>()) < 0) passable = false;
  std::string list = events.str();
  if (list.size() >= 2) list.resize(list.size() - 2);
  std::ostringstream o;
  o << "// The events' variables and rows for the continuation onto the events: {passable, lambda0,\n"
    << "// sphere, per event {{nu_j, row of c_j}...}, {epoch fraction, its row}, {{parameter, its row}...},\n"
    << "// {{costate after the event, its jump row}...}}.\n"
    << "const EventPlan kEventPlan = {" << (passable ? "true" : "false") << ", " << multiplier << ", {" << sphere_list
    << "}, {" << list << "}};\n\n";
  return o.str();
}

// The legs between events: which shooting variables each leg solves for alone (leg 0: lambda0,
// lambda(t0) and the first event's multipliers; leg k: the next event's (or the final
// constraint's) multipliers, besides its start costates), and the single-shooting function as the plain case of
// shooting_legs.
std::string legs_block(Context& c, const std::vector<int>& leg_sizes) {
  const json& d = c.d;
  const auto& vars = d.at("shooting").at("variables");
  const json& events = d.at("events");
  const std::vector<std::string> sphere = c.sphere_variables();
  std::string final_id;
  for (const auto& k : d.at("constraints"))
    if (k.at("at") == "tf") final_id = k.at("id");
  // nu_<id>_<row>, exactly (an id may itself end in _<n>, as a second visit's does).
  const auto multiplier_of = [](const std::string& name, const std::string& id) {
    const std::string prefix = "nu_" + id + "_";
    return name.size() > prefix.size() && name.rfind(prefix, 0) == 0 &&
           name.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
  };
  std::vector<std::vector<int>> own(events.size() + 1);
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const std::string name = vars[i].at("name");
    if (index_of(sphere, name) >= 0) own[0].push_back(static_cast<int>(i));
    for (std::size_t k = 0; k < events.size(); ++k)
      if (multiplier_of(name, events[k].at("id"))) own[k].push_back(static_cast<int>(i));
    // The final constraint's multipliers left as variables (a bound's) belong to the last leg.
    if (multiplier_of(name, final_id)) own[events.size()].push_back(static_cast<int>(i));
  }
  // Alone, a leg holds the time fractions at their guesses and the event's other variables (the
  // costates after a state map, Category-C parameters) at 0.
  std::vector<int> fractions, zero;
  for (std::size_t i = 0; i < vars.size(); ++i) {
    bool owned = false;
    for (const auto& leg : own) owned = owned || std::find(leg.begin(), leg.end(), static_cast<int>(i)) != leg.end();
    const std::string role = vars[i].value("role", "");
    if (role == "time_fraction")
      fractions.push_back(static_cast<int>(i));
    else if (!owned && role != "initial_state")  // an initial state stays at its guess
      zero.push_back(static_cast<int>(i));
  }
  const auto list = [](const std::vector<int>& v) {
    std::string out;
    for (std::size_t j = 0; j < v.size(); ++j) out += (j ? ", " : "") + std::to_string(v[j]);
    return "{" + out + "}";
  };
  std::ostringstream o;
  o << "const LegPlan kLegPlan = {{";
  for (std::size_t k = 0; k < own.size(); ++k) {
    const int unknowns = static_cast<int>(own[k].size()) + (k > 0 ? static_cast<int>(c.states.size()) : 0);
    if (unknowns != leg_sizes.at(k))
      throw std::invalid_argument("field /events: leg " + std::to_string(k) + " has " + std::to_string(unknowns) +
                                  " unknowns but " + std::to_string(leg_sizes[k]) + " equations");
    o << (k ? ", " : "") << list(own[k]);
  }
  // Window bounds: bound index (the order of the bound rows), fraction variable, edge.
  std::string edges;
  int bound = 0;
  for (const auto& eq : d.at("shooting").at("equations")) {
    if (!eq.contains("inequality")) continue;
    if (eq.at("inequality").contains("held_when_active")) {
      const json& held = eq.at("inequality").at("held_when_active");
      const int k = index_of(c.variables, held.at("variable"));
      if (k < 0) throw std::invalid_argument("field /shooting/equations: no variable " + held.at("variable").dump());
      edges += std::string(edges.empty() ? "" : ", ") + "{" + std::to_string(bound) + ", " + std::to_string(k) + ", " +
               number(held.at("value")) + "}";
    }
    ++bound;
  }
  o << "}, " << list(fractions) << ", " << list(zero) << ", {" << edges << "}};\n\n"
    << event_plan_block(c) << "void shooting_function(const double* x, double eps, Propagator& prop, double* F) {\n"
    << "  shooting_legs(x, eps, prop, F, nullptr);\n}\n\n";
  return o.str();
}

}  // namespace

std::string residual_module(Context& c) {
  const json& d = c.d;
  std::ostringstream o;
  const auto& vars = d.at("shooting").at("variables");
  const auto& eqs = d.at("shooting").at("equations");
  if (vars.size() != eqs.size())
    throw std::invalid_argument("field /shooting: " + std::to_string(vars.size()) + " variables but " +
                                std::to_string(eqs.size()) + " equations");
  o << "// ----- module RESIDUAL (generated) -------------------------------------------------------\n"
    << "namespace helios_rt {\n\n";
  std::vector<int> leg_sizes;  // equations of each leg alone
  if (d.contains("coast_dynamics")) {
    const auto& coast = d.at("coast_dynamics");
    const auto names = coast.at("states").get<std::vector<std::string>>();
    if (names.size() != 6 || coast.at("rhs").size() != 6)
      throw std::invalid_argument("field /coast_dynamics: a coasting target has 6 states and 6 right-hand sides");
    o << "void coast_dynamics(const double* y, double* dy) {\n";
    for (std::size_t i = 0; i < names.size(); ++i)
      o << "  [[maybe_unused]] const double " << names[i] << " = y[" << i << "];\n";
    for (std::size_t i = 0; i < names.size(); ++i)
      o << "  dy[" << i << "] = " << c.cpp(coast.at("rhs")[i], "/coast_dynamics/rhs/" + std::to_string(i)) << ";\n";
    o << "}\n\n";
  }
  const json events = d.value("events", json::array());
  if (!events.empty())
    o << "// With `legs`: multiple shooting (the costates after each event are legs->starts, their mismatch\n"
      << "// with the jump conditions goes to legs->continuity), or one leg alone (legs->stop_at).\n"
      << "void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs) {\n";
  else
    o << "void shooting_function(const double* x, double eps, Propagator& prop, double* F) {\n";
  // Equation i's code; a bound's row goes through bound_row (its multiplier while inactive).
  const auto equation_code = [&](std::size_t i, const std::string& field) {
    const std::string where = "/shooting/equations/" + std::to_string(i);
    const std::string code = c.cpp(eqs[i].at(field), where + "/" + field);
    if (!eqs[i].contains("inequality")) return code;
    int bound = 0;
    for (std::size_t j = 0; j < i; ++j) bound += eqs[j].contains("inequality") ? 1 : 0;
    return "bound_row(" + std::to_string(bound) + ", " + code + ", " +
           c.cpp(eqs[i].at("inequality").at("inactive_expression"), where + "/inequality/inactive_expression") + ")";
  };
  // The equation of each name, for the legs' own residuals.
  const auto equation = [&](const std::string& name, const std::string& field = "expression") {
    for (std::size_t i = 0; i < eqs.size(); ++i)
      if (eqs[i].at("name") == name) return equation_code(i, eqs[i].contains(field) ? field : "expression");
    throw std::invalid_argument("field /shooting/equations: no equation " + name);
  };
  for (std::size_t i = 0; i < vars.size(); ++i)
    o << "  [[maybe_unused]] const double " << vars[i].at("name").get<std::string>() << " = x[" << i << "];  // "
      << vars[i].at("meaning").get<std::string>() << "\n";
  const json& times = d.at("times");
  o << "  const double t0 = "
    << (times.contains("t0_expression") ? c.cpp(times.at("t0_expression"), "/times/t0_expression")
                                        : std::string("problem::kT0"))
    << ";\n";
  if (times.contains("tf_expression"))
    o << "  const double tf = " << c.cpp(times.at("tf_expression"), "/times/tf_expression") << ";\n";
  else
    o << "  const double tf = problem::kTf;\n";
  // Epochs of the interior events (a stay ends at t_<id>_dep), checked to be in order.
  std::string order = "t0";
  for (std::size_t k = 0; k < events.size(); ++k) {
    const json& e = events[k];
    const std::string id = e.at("id"), where = "/events/" + std::to_string(k);
    o << "  const double t_" << id << " = " << c.cpp(e.at("time").at("expression"), where + "/time/expression") << ";\n"
      << "  [[maybe_unused]] const double t_" << id << "_dep = t_" << id << " + " << number(e.at("time").at("duration"))
      << ";\n";
    order += ", t_" + id + ", t_" + id + "_dep";
  }
  order += ", tf";
  o << "  {\n    const double epochs[] = {" << order << "};\n"
    << "    for (std::size_t k = 1; k < sizeof epochs / sizeof epochs[0]; ++k)\n"
    << "      if (!(epochs[k] >= epochs[k - 1]) || (k % 2 == 1 && !(epochs[k] > epochs[k - 1])))\n"
    << "        throw numerical_error(\"the event epochs are out of order\");\n  }\n"
    << "  double y[kNY];\n";
  // Targets evaluated at the actual event time, in normalized units.
  int block = 0;
  for (const char* kind : {"ephemeris", "ephemeris_rate", "coast"})
    for (const auto& [key, names] : runtime_parameters(d, kind)) {
      const std::string what = key.substr(0, key.find(':')), event = key.substr(key.find(':') + 1);
      const std::string var = std::string(kind) + "_" + std::to_string(block++);
      if (std::string(kind) == "coast") {
        std::string start;
        for (const auto& n : names) {
          if (index_of(c.parameters, n + "_0") < 0)
            throw std::invalid_argument("field /parameters: coasting target " + what + " has no initial value " + n +
                                        "_0");
          start += (start.empty() ? "" : ", ") + std::string("problem::") + n + "_0";
        }
        o << "  const auto " << var << " = coast_state({" << start << "}, problem::kT0, " << event_time(c, event)
          << ");\n";
      } else {
        const std::string function = std::string(kind) == "ephemeris" ? "ephemeris_state" : "ephemeris_rate";
        o << "  const auto " << var << " = " << function << "(\"" << what << "\", " << event_time(c, event) << ");\n";
      }
      for (std::size_t i = 0; i < 6; ++i)
        o << "  [[maybe_unused]] const double " << names[i] << " = " << var << "[" << i << "];\n";
    }
  // Initial states from psi(t0) = 0, initial costates from the shooting variables.
  for (const auto& iv : d.at("initial_values")) {
    const int k = index_of(c.states, iv.at("state"));
    if (k < 0) throw std::invalid_argument("field /initial_values: unknown state " + iv.at("state").dump());
    o << "  y[" << k << "] = " << c.cpp(iv.at("value"), "/initial_values/" + iv.at("state").get<std::string>())
      << ";\n";
  }
  for (std::size_t i = 0; i < c.costates.size(); ++i) {
    const std::string v = c.costates[i] + "_t0";
    bool found = false;
    for (const auto& var : vars) found = found || var.at("name") == v;
    if (!found) throw std::invalid_argument("field /shooting/variables: no variable " + v + " for the initial costate");
    o << "  y[" << c.states.size() + i << "] = " << v << ";\n";
  }
  o << "  const Multipliers mult{" << d.at("multiplier").get<std::string>() << ", eps};\n"
    << "  [[maybe_unused]] std::array<double, problem::kNumControls> control{};\n";
  // Event values: H just before / after an event, under the optimal control.
  std::map<std::string, std::string> hamiltonian_at;
  for (const auto& e : d.value("event_values", json::array())) {
    if (e.value("kind", "") != "hamiltonian")
      throw std::invalid_argument("field /event_values: the runtime evaluates H only, not " + e.dump());
    hamiltonian_at[e.value("at", "tf")] = e.at("name");
  }
  const auto evaluate_h = [&](const std::string& at, const std::string& time) {
    const auto it = hamiltonian_at.find(at);
    if (it == hamiltonian_at.end()) return;
    o << "  control_in_mode(y, mode_at(y, mult), mult, control.data());\n"
      << "  const double " << it->second << " = hamiltonian(" << time << ", y, control.data(), mult);\n";
    hamiltonian_at.erase(it);
  };
  const auto unpack_y = [&](const std::string& suffix) {
    for (std::size_t i = 0; i < c.states.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.states[i] << suffix << " = y[" << i << "];\n";
    for (std::size_t i = 0; i < c.costates.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.costates[i] << suffix << " = y[" << c.states.size() + i << "];\n";
  };
  evaluate_h("t0", "t0");
  std::string from = "t0";
  for (std::size_t k = 0; k < events.size(); ++k) {
    const json& e = events[k];
    const std::string id = e.at("id"), where = "/events/" + std::to_string(k);
    o << "  prop.propagate(" << from << ", t_" << id << ", y, mult);\n";
    unpack_y("_" + id + "_m");
    evaluate_h(id + "_m", "t_" + id);
    // Leg k alone ends here as if the trajectory ended: its conditions c = 0 and lambda(t+) = 0
    // (the shooting variables of lambda(t+) are 0 in leg mode); leg 0 carries the normalization.
    o << "  if (legs && legs->stop_at == " << k << ") {\n";
    int row = 0;
    if (k == 0) o << "    F[" << row++ << "] = " << equation("normalization") << ";\n";
    for (std::size_t j = 0; j < e.at("psi").size() - c.states.size(); ++j)
      o << "    F[" << row++ << "] = " << equation("psi_" + id + "_" + std::to_string(j + 1), "alone_expression")
        << ";\n";
    for (std::size_t i = 0; i < c.costates.size(); ++i) {
      const json& m = e.at("costate_map")[i];
      o << "    F[" << row++ << "] = "
        << (m.contains("variable") ? equation("jump_" + id + "_" + c.states[i])
                                   : c.cpp(m.at("expression"), where + "/costate_map/" + std::to_string(i)))
        << ";\n";
    }
    o << "    return;\n  }\n";
    leg_sizes.push_back(row);
    // x+ = g(x-), lambda+ from the jump rows (or a shooting variable).
    const auto& state_map = e.at("state_map");
    const auto& costate_map = e.at("costate_map");
    if (state_map.size() != c.states.size() || costate_map.size() != c.costates.size())
      throw std::invalid_argument("field " + where + ": state_map and costate_map need one entry per state");
    for (std::size_t i = 0; i < c.states.size(); ++i) {
      if (state_map[i].at("state") != c.states[i] || costate_map[i].at("costate") != c.costates[i])
        throw std::invalid_argument("field " + where + ": the maps must follow the state order");
      o << "  y[" << i << "] = " << c.cpp(state_map[i].at("expression"), where + "/state_map/" + std::to_string(i))
        << ";\n";
    }
    for (std::size_t i = 0; i < c.costates.size(); ++i) {
      const json& m = costate_map[i];
      const std::string value = m.contains("variable")
                                    ? m.at("variable").get<std::string>()
                                    : c.cpp(m.at("expression"), where + "/costate_map/" + std::to_string(i));
      o << "  y[" << c.states.size() + i << "] = " << value << ";\n";
    }
    o << "  if (legs) {\n"
      << "    for (int i = 0; i < problem::kNumStates; ++i) {\n"
      << "      const double start = legs->starts[" << k << " * problem::kNumStates + i];\n"
      << "      if (legs->continuity) legs->continuity[" << k
      << " * problem::kNumStates + i] = y[problem::kNumStates + i] - start;\n"
      << "      y[problem::kNumStates + i] = start;\n    }\n  }\n";
    for (std::size_t i = 0; i < c.states.size(); ++i)
      o << "  [[maybe_unused]] const double " << c.states[i] << "_" << id << "_p = y[" << i << "];\n";
    for (std::size_t i = 0; i < c.costates.size(); ++i)
      if (!costate_map[i].contains("variable") || costate_map[i].at("variable") != c.costates[i] + "_" + id + "_p")
        o << "  [[maybe_unused]] const double " << c.costates[i] << "_" << id << "_p = y[" << c.states.size() + i
          << "];\n";
    evaluate_h(id + "_p", "t_" + id + "_dep");
    from = "t_" + id + "_dep";
  }
  o << "  prop.propagate(" << from << ", tf, y, mult);\n";
  unpack_y("_tf");
  evaluate_h("tf", "tf");
  if (!hamiltonian_at.empty())
    throw std::invalid_argument("field /event_values: no event '" + hamiltonian_at.begin()->first + "'");
  if (!events.empty()) {
    // The last leg alone: the final constraint's own equations (its epoch held at its guess).
    std::string final_id;
    for (const auto& k : d.at("constraints"))
      if (k.at("at") == "tf") final_id = k.at("id");
    o << "  if (legs && legs->stop_at == " << events.size() << ") {\n";
    int row = 0;
    for (std::size_t i = 0; i < eqs.size(); ++i)
      if (eqs[i].value("source", "") == final_id)
        o << "    F[" << row++ << "] = " << equation(eqs[i].at("name"), "alone_expression") << ";\n";
    o << "    return;\n  }\n";
    leg_sizes.push_back(row);
  }
  for (std::size_t i = 0; i < eqs.size(); ++i) {
    const double scale = eqs[i].at("scale");
    o << "  F[" << i << "] = (" << equation_code(i, "expression") << ")";
    if (scale != 1.0) o << " / " << number(scale);
    o << ";  // " << eqs[i].at("meaning").get<std::string>() << "\n";
  }
  o << "}\n\n";
  if (!events.empty()) o << legs_block(c, leg_sizes);
  o << "}  // namespace helios_rt\n";
  return o.str();
}

}  // namespace helios::codegen::detail

// The LegPlan and EventPlan of a program with events.
#include "plans.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios::codegen::detail {
namespace {

// "{a, b}" for a pair of indices, after ", " unless it opens `list`.
void append_pair(std::string& list, int a, int b) {
  list += (list.empty() ? "{" : ", {") + std::to_string(a) + ", " + std::to_string(b) + "}";
}

// True if event `e` is instantaneous and its state map is the identity with its parameters
// `own_parameters` at 0 (checked at random points).
bool is_passable_map(Context& c, const derivation::Event& e, const std::vector<std::string>& own_parameters) {
  if (e.duration != 0.0) return false;
  const std::string& id = e.id;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> dist(0.3, 1.7);
  for (int trial = 0; trial < 3; ++trial) {
    symbolic::Values values;
    for (const auto& [name, sym] : c.symbols.symtab()) values[name] = dist(rng) * (rng() % 2 ? 1 : -1);
    for (const auto& q : own_parameters) values[q] = 0;
    for (std::size_t i = 0; i < c.states.size(); ++i) {
      if (i >= e.state_map.size()) return false;
      try {
        const double after = symbolic::evaluate(
            c.symbols.parse(e.state_map[i].expression.text, "field /events/state_map"), c.symbols, values);
        const double before = values.at(names::before(c.states[i], id));
        if (std::fabs(after - before) > 1e-10 * (1 + std::fabs(after) + std::fabs(before))) return false;
      } catch (const std::exception&) {
        return false;
      }
    }
  }
  return true;
}

// One event's entry of the EventPlan: {{nu_j, row of c_j}...}, {epoch fraction, its row},
// {{parameter, its row}...}, {{costate after the event, its jump row}...}. `passable` is cleared
// when a variable or row is not found, or the event is not passable.
std::string event_plan_entry(Context& c, const derivation::Event& e, const std::vector<std::string>& eq_names,
                             bool& passable) {
  const auto& vars = c.shooting.variables;
  const std::vector<std::string>& var_names = c.variables;
  const std::string& id = e.id;
  const auto& psi = e.psi;
  const auto& multipliers = e.multipliers;
  const std::size_t nc = psi.size() >= c.states.size() ? psi.size() - c.states.size() : 0;
  std::string constraints, parameters, costates;
  // The costates after the event that are shooting variables, with their jump rows.
  for (std::size_t i = 0; i < c.states.size() && i < e.costate_map.size(); ++i) {
    const derivation::CostateMapEntry& m = e.costate_map[i];
    if (!m.variable) continue;
    const int v = index_of(var_names, *m.variable);
    const int row = index_of(eq_names, names::jump_row(id, c.states[i]));
    if (v < 0 || row < 0) passable = false;
    append_pair(costates, v, row);
  }
  for (std::size_t j = 0; j < nc && j < multipliers.size(); ++j) {
    const int v = index_of(var_names, multipliers[j]);
    const int row = index_of(eq_names, names::constraint_row(id, j + 1));
    if (v < 0 || row < 0) passable = false;
    append_pair(constraints, v, row);
  }
  if (nc == 0 || multipliers.size() < nc) passable = false;
  // The epoch fraction: the time_fraction variable of the event's time expression.
  int epoch_var = -1;
  for (const auto& name :
       symbolic::free_symbols(c.symbols.parse(e.time_expression.text, "field /events/time/expression"))) {
    const int v = index_of(var_names, name);
    if (v >= 0 && vars[static_cast<std::size_t>(v)].role == "time_fraction") epoch_var = v;
  }
  const int epoch_row = index_of(eq_names, names::time_row(id));
  if ((epoch_var < 0) != (epoch_row < 0)) passable = false;
  // The event's parameters: role "parameter" variables its psi or state map depends on.
  std::vector<std::string> used;
  for (const auto& text : psi) {
    const auto names = symbolic::free_symbols(c.symbols.parse(text.text, "field /events/psi"));
    used.insert(used.end(), names.begin(), names.end());
  }
  std::vector<std::string> own_parameters;
  for (std::size_t i = 0; i < vars.size(); ++i)
    if (vars[i].role == "parameter" && index_of(used, var_names[i]) >= 0) {
      const int row = index_of(eq_names, names::stationarity_row(id, var_names[i]));
      if (row < 0) passable = false;
      own_parameters.push_back(var_names[i]);
      append_pair(parameters, static_cast<int>(i), row);
    }
  passable = passable && is_passable_map(c, e, own_parameters);
  return "{{" + constraints + "}, {" + std::to_string(epoch_var) + ", " + std::to_string(epoch_row) + "}, {" +
         parameters + "}, {" + costates + "}}";
}

// The events' variables and rows for the continuation onto the events (runtime EventPlan): each
// event's constraint rows psi_<id>_j with their multipliers, its free-epoch row time_<id> with the
// epoch fraction, its parameters' stationarity rows. An event is passable when it is instantaneous
// and its state map is the identity with its parameters at 0; anything not found makes the plan
// not passable (the runtime then solves by legs only).
std::string event_plan_block(Context& c) {
  std::vector<std::string> eq_names;
  for (const auto& e : c.shooting.equations) eq_names.push_back(e.name);
  const std::vector<std::string> sphere = c.sphere_variables();
  bool passable = true;
  std::string entries;
  for (const auto& e : c.interior_events)
    entries += (entries.empty() ? "" : ", ") + event_plan_entry(c, e, eq_names, passable);
  std::string sphere_list;
  for (const auto& name : sphere) {
    const int v = index_of(c.variables, name);
    if (v < 0) passable = false;
    sphere_list += (sphere_list.empty() ? "" : ", ") + std::to_string(v);
  }
  const int multiplier = index_of(c.variables, c.multiplier);
  if (multiplier < 0 || index_of(sphere, c.multiplier) < 0) passable = false;
  std::ostringstream o;
  o << "// The events' variables and rows for the continuation onto the events: {passable, lambda0,\n"
    << "// sphere, per event {{nu_j, row of c_j}...}, {epoch fraction, its row}, {{parameter, its row}...},\n"
    << "// {{costate after the event, its jump row}...}}.\n"
    << "const EventPlan kEventPlan = {" << (passable ? "true" : "false") << ", " << multiplier << ", {" << sphere_list
    << "}, {" << entries << "}};\n\n";
  return o.str();
}

}  // namespace

// The legs between events: which shooting variables each leg solves for alone (leg 0: lambda0,
// lambda(t0) and the first event's multipliers; leg k: the next event's (or the final
// constraint's) multipliers, besides its start costates), and the single-shooting function as the plain case of
// shooting_legs.
std::string legs_block(Context& c, const std::vector<int>& leg_sizes) {
  const auto& vars = c.shooting.variables;
  const auto& events = c.interior_events;
  const std::vector<std::string> sphere = c.sphere_variables();
  std::string final_id;
  for (const auto& k : c.constraints)
    if (k.at == "tf") final_id = k.id;
  std::vector<std::vector<int>> own(events.size() + 1);
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const std::string& name = vars[i].name;
    if (index_of(sphere, name) >= 0) own[0].push_back(static_cast<int>(i));
    for (std::size_t k = 0; k < events.size(); ++k)
      if (names::is_multiplier_of(name, events[k].id)) own[k].push_back(static_cast<int>(i));
    // The final constraint's multipliers left as variables (a bound's) belong to the last leg.
    if (names::is_multiplier_of(name, final_id)) own[events.size()].push_back(static_cast<int>(i));
  }
  // Alone, a leg holds the time fractions at their guesses and the event's other variables (the
  // costates after a state map, Category-C parameters) at 0.
  std::vector<int> fractions, zero;
  for (std::size_t i = 0; i < vars.size(); ++i) {
    bool owned = false;
    for (const auto& leg : own) owned = owned || std::find(leg.begin(), leg.end(), static_cast<int>(i)) != leg.end();
    const std::string& role = vars[i].role;
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
  for (const auto& eq : c.shooting.equations) {
    if (!eq.inequality) continue;
    if (const auto& held = eq.inequality->held_when_active) {
      const int k = index_of(c.variables, held->variable);
      if (k < 0) throw std::invalid_argument("field /shooting/equations: no variable " + json(held->variable).dump());
      edges += std::string(edges.empty() ? "" : ", ") + "{" + std::to_string(bound) + ", " + std::to_string(k) + ", " +
               number(held->value) + "}";
    }
    ++bound;
  }
  o << "}, " << list(fractions) << ", " << list(zero) << ", {" << edges << "}};\n\n"
    << event_plan_block(c) << "void shooting_function(const double* x, double eps, Propagator& prop, double* F) {\n"
    << "  shooting_legs(x, eps, prop, F, nullptr);\n}\n\n";
  return o.str();
}

}  // namespace helios::codegen::detail

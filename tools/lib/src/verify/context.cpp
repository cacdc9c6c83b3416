// Reading the derivation into the Context and drawing the sample points.
#include "context.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "helios/derivation/reader.hpp"
#include "helios/io/error.hpp"
#include "sail.hpp"

namespace helios::verify::detail {
namespace {

std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// The kind of a state: from its meaning, else from its name.
Kind state_kind(const std::string& name, const std::string& meaning) {
  const std::string m = lower(meaning);
  if (m.find("mass") != std::string::npos || name == "m" || name == "mass") return Kind::Mass;
  if (m.find("velocity") != std::string::npos || name[0] == 'v') return Kind::Velocity;
  if (m.find("position") != std::string::npos || name == "x" || name == "y" || name == "z" ||
      (name[0] == 'r' && name.size() <= 2))
    return Kind::Position;
  return Kind::OtherState;
}

// Identifiers of an expression text that are not function names.
std::vector<std::string> identifiers(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < text.size();) {
    const auto ch = static_cast<unsigned char>(text[i]);
    if (!(std::isalpha(ch) || ch == '_') || (i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) ||
                                                       text[i - 1] == '_' || text[i - 1] == '.'))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
    std::size_t k = j;
    while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
    if (k >= text.size() || text[k] != '(') out.push_back(text.substr(i, j - i));
    i = j;
  }
  return out;
}

// A standard normal draw (Box-Muller).
double gaussian(std::mt19937_64& rng) {
  const double u1 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53, u2 = uniform(rng, 0, 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// The value a symbol of `kind` takes at a random point (a parameter its own `value`).
double random_value(Kind kind, double value, std::mt19937_64& rng) {
  switch (kind) {
    case Kind::Position:
      return (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * uniform(rng, 0.5, 2);
    case Kind::Velocity:
      return uniform(rng, -2, 2);
    case Kind::Mass:
      return uniform(rng, 0.3, 1);
    case Kind::OtherState:
      return uniform(rng, 0.5, 1.5);
    case Kind::Costate:
      return uniform(rng, -1, 1);
    case Kind::Multiplier:
      return uniform(rng, 0.1, 1);
    case Kind::Homotopy:
      return uniform(rng, 0.05, 1);
    case Kind::Throttle:
      return uniform(rng, 0, 1);
    case Kind::Direction:
    case Kind::Sail:
    case Kind::EventValue:
      return 0;
    case Kind::Parameter:
      return value;
    case Kind::Sourced:
      return (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * uniform(rng, 0.5, 1.5);
    case Kind::Free:
      return uniform(rng, -1, 1);
  }
  return 0;
}

}  // namespace

double uniform(std::mt19937_64& rng, double a, double b) {
  return a + (b - a) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
}

std::vector<double> random_unit(std::mt19937_64& rng, std::size_t n) {
  std::vector<double> v(n);
  double n2 = 0;
  do {
    n2 = 0;
    for (auto& x : v) {
      x = gaussian(rng);
      n2 += x * x;
    }
  } while (n2 < 1e-12);
  for (auto& x : v) x /= std::sqrt(n2);
  return v;
}

Context::Context(const json& derivation, const VerifyOptions& options) : derivation(derivation), options(options) {
  if (options.points < 1) throw std::invalid_argument("the number of sample points must be at least 1");
  if (!derivation.is_object()) throw input_error("derivation: not a JSON object");
  // The symbols first (their order is the order of a Point's slots, and so of the random draws).
  read_names();
  read_times_and_events();
  declare_constraint_multipliers();
  read_interior_events();
  read_statement();
  read_coast();
  read_sail_definitions();
  recompute_hamiltonian();
  std::mt19937_64 rng(0x9E3779B97F4A7C15ULL ^ options.seed);
  sample_points(rng);
  read_shooting();
}

int Context::declare(const std::string& name, Kind kind, double value) {
  if (!is_identifier(name)) throw input_error("derivation: '" + name + "' is not a valid symbol name");
  if (slots.count(name)) throw input_error("derivation: the name '" + name + "' is used for two different symbols");
  symbols.get(name);
  slots[name] = static_cast<int>(kinds.size());
  kinds.push_back(kind);
  values.push_back(value);
  return slots[name];
}

ex Context::statement(const json& text, const std::string& where) const {
  if (!text.is_string()) throw input_error("derivation: field " + where + " must be an expression string");
  return symbols.parse(text.get<std::string>(), "derivation: " + where);
}

// A symbol the derivation introduces (event states, multipliers, fractions): declared once.
void Context::declare_new(const std::string& name, Kind kind) {
  if (!slots.count(name)) declare(name, kind);
}

// Declares the identifiers of `text` that are not symbols yet (kind Free); returns them.
std::vector<std::string> Context::declare_unknown(const std::string& text) {
  std::vector<std::string> out;
  for (const auto& name : identifiers(text))
    if (!slots.count(name) && name != "Pi" && name != "Euler" && name != "Catalan" && is_identifier(name)) {
      declare(name, Kind::Free);
      out.push_back(name);
    }
  return out;
}

// The names and kinds of the states, costates, controls and parameters, the cost multiplier and
// the homotopy parameter, each declared with its values at t0 and tf where it has them.
// The names through the one reader of a derivation (helios/derivation/reader.hpp), declared here in
// the verifier's own order: states with their t0/tf values, costates, controls, parameters.
void Context::read_names() {
  const derivation::Reader names(derivation, "derivation", /*parse_units=*/false);
  multiplier = names.multiplier;
  eps = names.homotopy;
  states = names.states;
  costates = names.costates;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Kind k = state_kind(states[i], names.state_quantities[i].meaning);
    for (const auto& name : {states[i], names::at_t0(states[i]), names::at_tf(states[i])}) declare(name, k);
  }
  for (const auto& c : costates)
    for (const auto& name : {c, names::at_t0(c), names::at_tf(c)}) declare(name, Kind::Costate);
  for (std::size_t i = 0; i < names.controls.size(); ++i) {
    const std::string& name = names.controls[i];
    const std::string& kind = names.control_kinds[i];
    if (kind == "throttle") throttle = name;
    if (kind == "direction") directions.push_back(name);
    if (kind == "sail_normal") sails.push_back(name);
    declare(name, kind == "throttle" ? Kind::Throttle : kind == "direction" ? Kind::Direction : Kind::Sail);
  }
  for (std::size_t i = 0; i < states.size(); ++i)
    if (kinds[static_cast<std::size_t>(slot(states[i]))] == Kind::Position) positions.push_back(i);
  if (!sails.empty() && (sails.size() != 3 || positions.size() != 3))
    throw input_error(
        "derivation: a sail normal needs three controls of kind sail_normal and three position states, got " +
        std::to_string(sails.size()) + " and " + std::to_string(positions.size()));
  for (const auto& p : names.parameter_quantities) {
    parameters.push_back(p.name);
    declare(p.name, p.runtime_evaluated() ? Kind::Sourced : Kind::Parameter, p.value);
    if (p.runtime_evaluated()) sources[p.name] = p.source;
  }
  declare(multiplier, Kind::Multiplier);
  declare(eps, Kind::Homotopy);
}

// The multipliers the constraints name (kind Free).
void Context::declare_constraint_multipliers() {
  const json& d = derivation;
  if (d.contains("constraints") && d["constraints"].is_array())
    for (const auto& c : d["constraints"])
      if (c.contains("multipliers") && c["multipliers"].is_array())
        for (const auto& m : c["multipliers"])
          if (m.is_string() && !slots.count(m.get<std::string>())) declare(m.get<std::string>(), Kind::Free);
}

// The problem statement: dynamics, costs, endpoint constraints (psi read in the state symbols).
void Context::read_statement() {
  const json& d = derivation;
  const json& dyn = io::require(d, "dynamics", "derivation");
  const json& rhs = io::require(dyn, "state_rhs", "derivation dynamics");
  if (!rhs.is_array() || rhs.size() != states.size())
    throw input_error("derivation: dynamics.state_rhs must have one expression per state (" +
                      std::to_string(states.size()) + ")");
  // Dynamics that depend on the time (a third body's motion, a user's acceleration) name t.
  for (const auto& text : rhs)
    if (text.is_string())
      for (const auto& name : identifiers(text.get<std::string>()))
        if (name == "t") declare_new("t", Kind::Free);
  for (std::size_t i = 0; i < rhs.size(); ++i)
    state_rhs.push_back(statement(rhs[i], "dynamics.state_rhs[" + states[i] + "]"));
  running_cost = statement(io::require(dyn, "running_cost", "derivation dynamics"), "dynamics.running_cost");
  endpoint_cost = statement(io::require(dyn, "endpoint_cost", "derivation dynamics"), "dynamics.endpoint_cost");
  GiNaC::exmap tf_to_state;  // an endpoint cost written in x_tf is read in x
  for (const auto& s : states) tf_to_state[sym(names::at_tf(s))] = sym(s);
  endpoint_cost = endpoint_cost.subs(tf_to_state);
  if (d.contains("constraints")) {
    for (const auto& c : d["constraints"]) {
      Constraint k;
      k.id = io::require_string(c, "id", "derivation constraints");
      k.at = io::require_string(c, "at", "derivation constraint " + k.id);
      if (k.at != "t0" && k.at != "tf")
        throw input_error("derivation: constraint " + k.id + " is at '" + k.at + "', expected t0 or tf");
      GiNaC::exmap to_state;
      for (const auto& s : states) to_state[sym(names::at(s, k.at))] = sym(s);
      const json& psi = io::require(c, "psi", "derivation constraint " + k.id);
      for (std::size_t j = 0; j < psi.size(); ++j)
        k.psi.push_back(statement(psi[j], "constraints[" + k.id + "].psi[" + std::to_string(j) + "]").subs(to_state));
      for (const auto& m : c.value("multipliers", json::array()))
        k.multipliers.push_back(m.is_string() ? m.get<std::string>() : "");
      constraints.push_back(k);
    }
  }
  for (const auto& k : constraints)
    for (const auto& psi : k.psi)
      for (const auto& s : states)
        if (psi.has(sym(s))) (k.at == "tf" ? fixed_at_tf : fixed_at_t0).insert(s);
}

// H = lambda0 L + lambda.f, its gradients in the direction and sail controls, and a* = -g/|g|
// at full thrust (the exact throttle checks use it until the derivation's own law is verified).
void Context::recompute_hamiltonian() {
  hamiltonian = sym(multiplier) * running_cost;
  for (std::size_t i = 0; i < states.size(); ++i) hamiltonian += sym(costates[i]) * state_rhs[i];
  hamiltonian_compiled = compile(hamiltonian);
  for (const auto& a : directions) {
    dH_da.push_back(hamiltonian.diff(GiNaC::ex_to<symbol>(sym(a))));
    dH_da_compiled.push_back(compile(dH_da.back()));
  }
  for (const auto& n : sails) {
    dH_dn.push_back(hamiltonian.diff(GiNaC::ex_to<symbol>(sym(n))));
    dH_dn_compiled.push_back(compile(dH_dn.back()));
  }
  ex norm2 = 0;
  std::vector<ex> g;
  for (const auto& gj : dH_da) {
    g.push_back(throttle.empty() ? gj : gj.subs(sym(throttle) == 1));
    norm2 += GiNaC::pow(g.back(), 2);
  }
  for (const auto& gj : g) direction_law.push_back(-gj / GiNaC::sqrt(norm2));
}

// times (free final time: tf_expression in shooting variables it introduces) and event_values.
void Context::read_times_and_events() {
  const json& times =
      derivation.contains("times") && derivation["times"].is_object() ? derivation["times"] : json::object();
  free_tf = times.value("final_time", "fixed") == "free";
  if (derivation.contains("event_values") && derivation["event_values"].is_array())
    for (const auto& e : derivation["event_values"]) {
      EventValue v;
      v.name = io::require_string(e, "name", "derivation event_values");
      v.meaning = e.value("meaning", "");
      v.hamiltonian = e.value("kind", "") == "hamiltonian";
      if (e.contains("at") && e["at"].is_string())
        v.at = e["at"].get<std::string>();
      else if (v.name.rfind("hamiltonian", 0) == 0 && v.name.size() > 2)
        v.at = v.name.substr(2);
      declare(v.name, Kind::EventValue);
      event_values.push_back(v);
    }
  read_departure(times);
  if (!free_tf) return;
  if (!times.contains("tf_expression") || !times["tf_expression"].is_string()) {
    tf_error = "times.tf_expression is missing: a free final time needs tf as an expression of a shooting variable";
    return;
  }
  tf_text = times["tf_expression"].get<std::string>();
  for (const auto& name : identifiers(tf_text))
    if (!slots.count(name) && name != "Pi" && name != "Euler" && name != "Catalan") {
      tf_vars.push_back(name);
      declare(name, Kind::Free);
    }
  try {
    tf_expr = symbols.parse(tf_text, "times.tf_expression");
  } catch (const std::exception& e) {
    tf_error = e.what();
  }
  // An endpoint cost may name the final time itself (Mayer form of minimum time).
  if (!slots.count("tf")) declare("tf", Kind::Free);
}

// times.departure == "free": t0 = t0_expression(t0_frac), tf = tf_expression = t0 + the fixed total time.
void Context::read_departure(const json& times) {
  free_t0 = times.value("departure", "fixed") == "free";
  if (!free_t0) return;
  try {
    for (const char* key : {"t0_expression", "tf_expression"}) {
      if (!times.contains(key) || !times[key].is_string())
        throw std::invalid_argument(std::string("times.") + key + " is missing: a sliding departure needs t0 and tf " +
                                    "as expressions of a shooting variable (t0_frac)");
      const std::string text = times[key].get<std::string>();
      for (const auto& name : declare_unknown(text)) t0_vars.push_back(name);
      (std::string(key) == "t0_expression" ? t0_expr : t0_tf_expr) = symbols.parse(text, std::string("times.") + key);
    }
  } catch (const std::exception& e) {
    t0_error = e.what();
  }
}

void Context::read_interior_events() {
  if (!derivation.contains("events") || !derivation["events"].is_array()) return;
  std::size_t index = 0;
  for (const auto& je : derivation["events"]) {
    Event e;
    e.id = je.is_object() ? je.value("id", "") : "";
    if (!is_identifier(e.id)) e.id = "#" + std::to_string(index);
    ++index;
    const std::string where = "events[" + e.id + "]";
    try {
      if (!is_identifier(e.id)) throw std::invalid_argument(where + " has no valid id");
      e.kind = je.value("kind", "");
      for (std::size_t i = 0; i < states.size(); ++i) {
        const Kind k = kinds[static_cast<std::size_t>(slot(states[i]))];
        declare_new(names::before(states[i], e.id), k);
        declare_new(names::after(states[i], e.id), k);
        declare_new(names::before(costates[i], e.id), Kind::Costate);
        declare_new(names::after(costates[i], e.id), Kind::Costate);
      }
      declare_new(names::event_time(e.id), Kind::Free);
      for (const auto& v : event_values)
        if (v.hamiltonian && v.at == names::before_label(e.id))
          e.Hm = v.name;
        else if (v.hamiltonian && v.at == names::after_label(e.id))
          e.Hp = v.name;
      const json& time = io::require(je, "time", where);
      e.time_text = io::require_string(time, "expression", where + ".time");
      e.time_vars = declare_unknown(e.time_text);
      e.time_expr = symbols.parse(e.time_text, where + ".time.expression");
      if (time.contains("window") && time["window"].is_array() && time["window"].size() == 2)
        for (const auto& w : time["window"]) e.window.push_back(w.is_number() ? w.get<double>() : std::nan(""));
      const json& mult = io::require(je, "multipliers", where);
      for (const auto& m : mult) {
        e.multiplier_text.push_back(m.is_string() ? m.get<std::string>() : "");
        if (is_identifier(e.multiplier_text.back())) declare_new(e.multiplier_text.back(), Kind::Free);
      }
      const json& psi = io::require(je, "psi", where);
      for (std::size_t j = 0; j < psi.size(); ++j) {
        if (!psi[j].is_string()) throw std::invalid_argument(where + ".psi[" + std::to_string(j) + "] is not a string");
        e.psi_text.push_back(psi[j].get<std::string>());
        for (const auto& q : declare_unknown(e.psi_text.back())) e.free_params.push_back(q);
        e.psi.push_back(symbols.parse(e.psi_text.back(), where + ".psi[" + std::to_string(j) + "]"));
      }
      e.map.assign(states.size(), ex(0));
      e.map_text.assign(states.size(), "");
      for (const auto& m : io::require(je, "state_map", where)) {
        const std::string s = io::require_string(m, "state", where + ".state_map");
        const auto it = std::find(states.begin(), states.end(), s);
        if (it == states.end()) throw std::invalid_argument(where + ".state_map names '" + s + "', not a state");
        const auto i = static_cast<std::size_t>(it - states.begin());
        e.map_text[i] = io::require_string(m, "expression", where + ".state_map[" + s + "]");
        for (const auto& q : declare_unknown(e.map_text[i])) e.free_params.push_back(q);
        e.map[i] = symbols.parse(e.map_text[i], where + ".state_map[" + s + "]");
      }
      for (std::size_t i = 0; i < states.size(); ++i)
        if (e.map_text[i].empty())
          throw std::invalid_argument(where + ".state_map has no entry for state " + states[i]);
      e.costate_map.assign(states.size(), CostateEntry{});
      for (const auto& m : io::require(je, "costate_map", where)) {
        const std::string l = io::require_string(m, "costate", where + ".costate_map");
        const auto it = std::find(costates.begin(), costates.end(), l);
        if (it == costates.end()) throw std::invalid_argument(where + ".costate_map names '" + l + "', not a costate");
        CostateEntry& c = e.costate_map[static_cast<std::size_t>(it - costates.begin())];
        c.given = true;
        if (m.contains("variable")) {
          c.is_variable = true;
          c.variable = io::require_string(m, "variable", where + ".costate_map[" + l + "]");
          if (is_identifier(c.variable)) declare_new(c.variable, Kind::Costate);
        } else {
          c.text = io::require_string(m, "expression", where + ".costate_map[" + l + "]");
          declare_unknown(c.text);
          c.expr = symbols.parse(c.text, where + ".costate_map[" + l + "]");
        }
      }
    } catch (const std::exception& x) {
      e.error = x.what();
    }
    interior_events.push_back(e);
  }
}

// coast_dynamics: the state symbols of the coasting target and their uncontrolled dynamics.
void Context::read_coast() {
  if (!derivation.contains("coast_dynamics")) return;
  has_coast = true;
  const json& c = derivation["coast_dynamics"];
  try {
    if (!c.is_object() || !c.contains("states") || !c["states"].is_array() || !c.contains("rhs") ||
        !c["rhs"].is_array())
      throw std::invalid_argument("coast_dynamics must have arrays states and rhs");
    std::vector<std::size_t> rv;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const Kind k = kinds[static_cast<std::size_t>(slot(states[i]))];
      if (k == Kind::Position || k == Kind::Velocity) rv.push_back(i);
    }
    for (std::size_t i = 0; i < c["states"].size(); ++i) {
      const std::string name = c["states"][i].is_string() ? c["states"][i].get<std::string>() : "";
      const Kind k = i < rv.size() ? kinds[static_cast<std::size_t>(slot(states[rv[i]]))] : Kind::Free;
      // The coast states may reuse the problem's own r, v names (same order), or be new symbols.
      if (!(i < rv.size() && name == states[rv[i]])) {
        if (slots.count(name))
          throw std::invalid_argument("coast_dynamics.states: '" + name + "' is already a symbol of the problem");
        declare(name, k);
      }
      coast_states.push_back(name);
    }
    for (std::size_t i = 0; i < c["rhs"].size(); ++i)
      coast_rhs.push_back(statement(c["rhs"][i], "coast_dynamics.rhs[" + std::to_string(i) + "]"));
  } catch (const std::exception& e) {
    coast_error = e.what();
  }
}

// control_law.sail.definitions: named intermediate expressions (e.g. sail_A, sail_B, sail_alpha),
// each in the problem's symbols and the earlier definitions; the sail law is read with them inlined.
void Context::read_sail_definitions() {
  if (!derivation.contains("control_law") || !derivation["control_law"].is_object() ||
      !derivation["control_law"].contains("sail") || !derivation["control_law"]["sail"].is_object() ||
      !derivation["control_law"]["sail"].contains("definitions"))
    return;
  try {
    const json& defs = derivation["control_law"]["sail"]["definitions"];
    if (!defs.is_array()) throw std::invalid_argument("control_law.sail.definitions must be an array");
    for (const auto& def : defs) {
      const std::string name = def.is_object() ? def.value("name", "") : "";
      const std::string where = "control_law.sail.definitions[" + name + "]";
      if (slots.count(name)) throw std::invalid_argument(where + ": the name is already a symbol of the problem");
      const ex e = statement(def.is_object() && def.contains("expression") ? def["expression"] : json(), where);
      declare(name, Kind::Free);
      sail_definitions[sym(name)] = e.subs(sail_definitions);
    }
  } catch (const std::exception& e) {
    sail_definitions_error = e.what();
  }
}

void Context::sample_points(std::mt19937_64& rng) {
  std::vector<Compiled> statement;
  statement.push_back(compile(running_cost));
  for (const auto& fi : state_rhs) statement.push_back(compile(fi));
  statement.push_back(hamiltonian_compiled);
  for (const auto& c : dH_da_compiled) statement.push_back(c);
  for (const auto& c : dH_dn_compiled) statement.push_back(c);
  const int max_draws = 200 * options.points;
  for (int draw = 0; draw < max_draws && static_cast<int>(points.size()) < options.points; ++draw) {
    Point p(values.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = random_value(kinds[i], values[i], rng);
    if (!directions.empty()) p = set_direction(p, random_unit(rng, directions.size()));
    if (!sails.empty()) p = set_sail(*this, p, random_admissible(*this, p, rng));
    bool finite = true;
    for (const auto& c : statement) finite = finite && std::isfinite(c(p));
    if (!finite) continue;
    // Event values are what the runtime evaluates: H_tf is H at the _tf values, optimal controls;
    // H_t0 at the _t0 values, hamiltonian<id>_m / hamiltonian<id>_p at the states and costates around an event.
    for (const auto& v : event_values)
      if (v.hamiltonian) {
        const double h = hamiltonian_compiled(at_label(p, v.at));
        if (!std::isfinite(h)) finite = false;
        p[static_cast<std::size_t>(slot(v.name))] = h;
      }
    if (finite) points.push_back(std::move(p));
  }
  if (points.empty() || static_cast<int>(points.size()) < options.points)
    throw std::domain_error(
        "derivation: the dynamics and running cost are not finite at random points of the state space");
}

void Context::read_shooting() {
  const json empty = json::array();
  const json& sh =
      derivation.contains("shooting") && derivation["shooting"].is_object() ? derivation["shooting"] : json::object();
  const json& vars = sh.contains("variables") && sh["variables"].is_array() ? sh["variables"] : empty;
  const json& eqs = sh.contains("equations") && sh["equations"].is_array() ? sh["equations"] : empty;
  for (const auto& v : vars) variables.push_back(v.is_object() ? v.value("name", "") : "");
  for (std::size_t k = 0; k < eqs.size(); ++k) {
    Equation e;
    e.name = eqs[k].is_object() ? eqs[k].value("name", "") : "";
    if (e.name.empty()) e.name = "#" + std::to_string(k);
    const std::string where = "shooting.equations[" + e.name + "]";
    try {
      if (!eqs[k].is_object() || !eqs[k].contains("expression") || !eqs[k]["expression"].is_string())
        throw std::invalid_argument(where + ": no expression string");
      e.text = eqs[k]["expression"].get<std::string>();
      e.e = symbols.parse(e.text, where);
      e.c = compile(e.e);
      for (const auto& p : points) e.values.push_back(e.c(p));
      for (auto& name : symbolic::free_symbols(e.e)) e.symbols.insert(std::move(name));
      e.ok = true;
    } catch (const std::exception& x) {
      e.error = x.what();
    }
    equations.push_back(e);
  }
}

Point Context::set_direction(Point p, const std::vector<double>& a) const {
  for (std::size_t j = 0; j < directions.size(); ++j) p[static_cast<std::size_t>(slot(directions[j]))] = a[j];
  return p;
}

std::vector<double> Context::direction_of(const Point& p) const {
  std::vector<double> a;
  for (const auto& name : directions) a.push_back(p[static_cast<std::size_t>(slot(name))]);
  return a;
}

// The verifier's own minimizing direction a* = -g/|g|, g = dH/da with the throttle at `u`
// (NaN: the point's own throttle); returns p with the direction controls set to it.
Point Context::with_direction(const Point& p, double u) const {
  if (directions.empty()) return p;
  Point q = p;
  if (!throttle.empty() && !std::isnan(u)) q[static_cast<std::size_t>(slot(throttle))] = u;
  std::vector<double> g;
  double n2 = 0;
  for (const auto& c : dH_da_compiled) {
    g.push_back(c(q));
    n2 += g.back() * g.back();
  }
  if (!(n2 > 0) || !std::isfinite(n2)) return p;
  for (auto& x : g) x = -x / std::sqrt(n2);
  return set_direction(p, g);
}

// p with the controls at the verifier's own optimum: a* = -g/|g|, n* numerically, and (with
// `throttle`) u* minimizing H over [0, 1] (grid, then golden section).
Point Context::optimal_controls(const Point& p, bool with_throttle) const {
  Point q = p;
  if (!sails.empty()) q = set_sail(*this, q, optimal_sail(*this, q));
  if (with_throttle && !throttle.empty()) {
    const auto us = static_cast<std::size_t>(slot(throttle));
    auto h = [&](double u) {
      Point r = q;
      r[us] = u;
      return hamiltonian_compiled(with_direction(r, u));
    };
    int best = 0;
    for (int k = 1; k <= kThrottleGrid; ++k)
      if (h(static_cast<double>(k) / kThrottleGrid) < h(static_cast<double>(best) / kThrottleGrid)) best = k;
    double a = std::max(0, best - 1) / static_cast<double>(kThrottleGrid);
    double b = std::min(kThrottleGrid, best + 1) / static_cast<double>(kThrottleGrid);
    const double g = 0.6180339887498949;
    for (int it = 0; it < 80 && b - a > 1e-13; ++it) {
      const double x1 = b - g * (b - a), x2 = a + g * (b - a);
      if (h(x1) <= h(x2))
        b = x2;
      else
        a = x1;
    }
    double u = 0.5 * (a + b);
    for (double end : {0.0, 1.0})
      if (h(end) <= h(u)) u = end;
    q[us] = u;
    return with_direction(q, u);
  }
  return with_direction(q, std::nan(""));
}

// The point as seen at tf: states and costates take their _tf values, controls their optimum.
Point Context::at_tf(const Point& p) const {
  Point q = p;
  for (std::size_t i = 0; i < states.size(); ++i) {
    q[static_cast<std::size_t>(slot(states[i]))] = p[static_cast<std::size_t>(slot(names::at_tf(states[i])))];
    q[static_cast<std::size_t>(slot(costates[i]))] = p[static_cast<std::size_t>(slot(names::at_tf(costates[i])))];
  }
  return optimal_controls(q, true);
}

// The point as seen at `label` (t0, tf, <event>_m, <event>_p): states and costates take their
// values there (where the derivation has such symbols), controls their optimum.
Point Context::at_label(const Point& p, const std::string& label) const {
  if (label == "tf") return at_tf(p);
  Point q = p;
  for (std::size_t i = 0; i < states.size(); ++i)
    for (const auto* name : {&states[i], &costates[i]}) {
      const auto it = slots.find(names::at(*name, label));
      if (it != slots.end()) q[static_cast<std::size_t>(slot(*name))] = p[static_cast<std::size_t>(it->second)];
    }
  return optimal_controls(q, true);
}

}  // namespace helios::verify::detail

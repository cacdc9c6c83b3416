// Reading the derivation into the Context and drawing the sample points.
#include "context.hpp"

#include <algorithm>
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

// `derivation` once the options are known to be usable: the document's read comes after that check.
const json& checked(const json& derivation, const VerifyOptions& options) {
  if (options.points < 1) throw std::invalid_argument("the number of sample points must be at least 1");
  return derivation;
}

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

Context::Context(const json& derivation, const VerifyOptions& options)
    : doc(checked(derivation, options), "derivation", /*parse_units=*/false), options(options) {
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

ex Context::statement(const std::string& text, const std::string& where) const {
  return symbols.parse(text, "derivation: " + where);
}

// A symbol the derivation introduces (event states, multipliers, fractions): declared once.
void Context::declare_new(const std::string& name, Kind kind) {
  if (!slots.count(name)) declare(name, kind);
}

// Declares the identifiers of `text` that are not symbols yet (kind Free); returns them.
std::vector<std::string> Context::declare_unknown(const std::string& text) {
  std::vector<std::string> out;
  for (const auto& name : symbolic::identifiers(text))
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
  const derivation::Document& names = doc;
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
  // The intermediates (symbols without a slot): substituted wherever a claim names them, so that
  // every check recomputes from the states, the parameters and its own arithmetic.
  GiNaC::exmap substituted;
  for (const auto& q : doc.intermediate_list) {
    const ex e = symbols.parse(q.expression.text, "derivation: intermediates[" + q.name + "]");
    substituted[symbols.get(q.name)] = e;
    symbols.substitute_on_parse(substituted);
  }
}

// The multipliers the constraints name (kind Free).
void Context::declare_constraint_multipliers() {
  for (const auto& c : doc.constraints)
    for (const auto& m : c.multipliers)
      if (!slots.count(m)) declare(m, Kind::Free);
}

// The problem statement: dynamics, costs, endpoint constraints (psi read in the state symbols).
void Context::read_statement() {
  const auto& rhs = doc.dynamics.state_rhs;
  if (rhs.size() != states.size())
    throw input_error("derivation: dynamics.state_rhs must have one expression per state (" +
                      std::to_string(states.size()) + ")");
  // Dynamics that depend on the time (a third body's motion, a user's acceleration) name t.
  for (const auto& e : rhs)
    for (const auto& name : symbolic::identifiers(e.text))
      if (name == "t") declare_new("t", Kind::Free);
  for (std::size_t i = 0; i < rhs.size(); ++i)
    state_rhs.push_back(statement(rhs[i].text, "dynamics.state_rhs[" + states[i] + "]"));
  running_cost = statement(doc.dynamics.running_cost.text, "dynamics.running_cost");
  endpoint_cost = statement(doc.dynamics.endpoint_cost.text, "dynamics.endpoint_cost");
  GiNaC::exmap tf_to_state;  // an endpoint cost written in x_tf is read in x
  for (const auto& s : states) tf_to_state[sym(names::at_tf(s))] = sym(s);
  endpoint_cost = endpoint_cost.subs(tf_to_state);
  std::set<std::string> unknowns;  // the shooting variables' names
  for (const auto& v : doc.shooting.variables) unknowns.insert(v.name);
  for (const auto& c : doc.constraints) {
    Constraint k;
    k.id = c.id;
    k.at = c.at;
    if (k.at != "t0" && k.at != "tf")
      throw input_error("derivation: constraint " + k.id + " is at '" + k.at + "', expected t0 or tf");
    GiNaC::exmap to_state;
    for (const auto& s : states) to_state[sym(names::at(s, k.at))] = sym(s);
    for (std::size_t j = 0; j < c.psi.size(); ++j) {
      if (k.at == "t0")
        for (const auto& name : symbolic::identifiers(c.psi[j].text))
          if (unknowns.count(name) && !slots.count(name)) {
            declare(name, Kind::Free);
            k.free_params.push_back(name);
          }
      k.psi.push_back(
          statement(c.psi[j].text, "constraints[" + k.id + "].psi[" + std::to_string(j) + "]").subs(to_state));
    }
    k.multipliers = c.multipliers;
    k.multipliers_unknown = k.at == "tf" && !k.multipliers.empty() &&
                            std::all_of(k.multipliers.begin(), k.multipliers.end(),
                                        [&](const std::string& nu) { return unknowns.count(nu) > 0; });
    constraints.push_back(k);
  }
  for (const auto& k : constraints)
    for (const auto& psi : k.psi)
      for (const auto& s : states)
        if (psi.has(sym(s)) && !k.multipliers_unknown) (k.at == "tf" ? fixed_at_tf : fixed_at_t0).insert(s);
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
  const derivation::Times& times = doc.times;
  free_tf = times.final_time == "free";
  for (const auto& e : doc.event_value_list) {
    EventValue v;
    v.name = e.name;
    v.meaning = e.meaning;
    v.hamiltonian = e.kind.value_or("") == "hamiltonian";
    v.at = e.at ? *e.at : names::hamiltonian_label(v.name);
    declare(v.name, Kind::EventValue);
    event_values.push_back(v);
  }
  read_departure(times);
  if (!free_tf) return;
  if (!times.tf_expression) {
    tf_error = "times.tf_expression is missing: a free final time needs tf as an expression of a shooting variable";
    return;
  }
  tf_text = times.tf_expression->text;
  for (const auto& name : symbolic::identifiers(tf_text))
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
void Context::read_departure(const derivation::Times& times) {
  free_t0 = times.departure == "free";
  if (!free_t0) return;
  try {
    for (const char* key : {"t0_expression", "tf_expression"}) {
      const auto& given = std::string(key) == "t0_expression" ? times.t0_expression : times.tf_expression;
      if (!given)
        throw std::invalid_argument(std::string("times.") + key + " is missing: a sliding departure needs t0 and tf " +
                                    "as expressions of a shooting variable (t0_frac)");
      const std::string text = given->text;
      for (const auto& name : declare_unknown(text)) t0_vars.push_back(name);
      (std::string(key) == "t0_expression" ? t0_expr : t0_tf_expr) = symbols.parse(text, std::string("times.") + key);
    }
  } catch (const std::exception& e) {
    t0_error = e.what();
  }
}

void Context::read_interior_events() {
  std::size_t index = 0;
  for (const auto& je : doc.interior_events) {
    Event e;
    e.id = je.id;
    if (!is_identifier(e.id)) e.id = "#" + std::to_string(index);
    ++index;
    const std::string where = "events[" + e.id + "]";
    try {
      if (!is_identifier(e.id)) throw std::invalid_argument(where + " has no valid id");
      e.kind = je.kind;
      declare_event_symbols(e);
      e.time_text = je.time_expression.text;
      e.time_vars = declare_unknown(e.time_text);
      e.time_expr = symbols.parse(e.time_text, where + ".time.expression");
      if (je.window.size() == 2) e.window = je.window;
      for (const auto& m : je.multipliers) {
        e.multiplier_text.push_back(m);
        if (is_identifier(m)) declare_new(m, Kind::Free);
      }
      for (std::size_t j = 0; j < je.psi.size(); ++j) {
        e.psi_text.push_back(je.psi[j].text);
        for (const auto& q : declare_unknown(e.psi_text.back())) e.free_params.push_back(q);
        e.psi.push_back(symbols.parse(e.psi_text.back(), where + ".psi[" + std::to_string(j) + "]"));
      }
      read_event_maps(je, e, where);
    } catch (const std::exception& x) {
      e.error = x.what();
    }
    interior_events.push_back(e);
  }
}

// The symbols of an event: the states and costates just before and after it, its time; and the
// names of the event values that are H just before and after it.
void Context::declare_event_symbols(Event& e) {
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
}

// The event's state_map and costate_map, in state order; every state must have its entry.
void Context::read_event_maps(const derivation::Event& je, Event& e, const std::string& where) {
  e.map.assign(states.size(), ex(0));
  e.map_text.assign(states.size(), "");
  for (const auto& m : je.state_map) {
    const auto it = std::find(states.begin(), states.end(), m.state);
    if (it == states.end()) throw std::invalid_argument(where + ".state_map names '" + m.state + "', not a state");
    const auto i = static_cast<std::size_t>(it - states.begin());
    e.map_text[i] = m.expression.text;
    for (const auto& q : declare_unknown(e.map_text[i])) e.free_params.push_back(q);
    e.map[i] = symbols.parse(e.map_text[i], where + ".state_map[" + m.state + "]");
  }
  for (std::size_t i = 0; i < states.size(); ++i)
    if (e.map_text[i].empty()) throw std::invalid_argument(where + ".state_map has no entry for state " + states[i]);
  e.costate_map.assign(states.size(), CostateEntry{});
  for (const auto& m : je.costate_map) {
    const std::string& l = m.costate;
    const auto it = std::find(costates.begin(), costates.end(), l);
    if (it == costates.end()) throw std::invalid_argument(where + ".costate_map names '" + l + "', not a costate");
    CostateEntry& c = e.costate_map[static_cast<std::size_t>(it - costates.begin())];
    c.given = true;
    if (m.variable) {
      c.is_variable = true;
      c.variable = *m.variable;
      if (is_identifier(c.variable)) declare_new(c.variable, Kind::Costate);
    } else {
      if (!m.expression)
        throw std::invalid_argument("field " + where + ".costate_map[" + l + "]/expression is missing");
      c.text = m.expression->text;
      declare_unknown(c.text);
      c.expr = symbols.parse(c.text, where + ".costate_map[" + l + "]");
    }
  }
}

// coast_dynamics: the state symbols of the coasting target and their uncontrolled dynamics.
void Context::read_coast() {
  if (!doc.coast_dynamics) return;
  has_coast = true;
  const derivation::CoastDynamics& c = *doc.coast_dynamics;
  try {
    std::vector<std::size_t> rv;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const Kind k = kinds[static_cast<std::size_t>(slot(states[i]))];
      if (k == Kind::Position || k == Kind::Velocity) rv.push_back(i);
    }
    for (std::size_t i = 0; i < c.states.size(); ++i) {
      const std::string& name = c.states[i];
      const Kind k = i < rv.size() ? kinds[static_cast<std::size_t>(slot(states[rv[i]]))] : Kind::Free;
      // The coast states may reuse the problem's own r, v names (same order), or be new symbols.
      if (!(i < rv.size() && name == states[rv[i]])) {
        if (slots.count(name))
          throw std::invalid_argument("coast_dynamics.states: '" + name + "' is already a symbol of the problem");
        declare(name, k);
      }
      coast_states.push_back(name);
    }
    for (std::size_t i = 0; i < c.rhs.size(); ++i)
      coast_rhs.push_back(statement(c.rhs[i].text, "coast_dynamics.rhs[" + std::to_string(i) + "]"));
  } catch (const std::exception& e) {
    coast_error = e.what();
  }
}

// control_law.sail.definitions: named intermediate expressions (e.g. sail_A, sail_B, sail_alpha),
// each in the problem's symbols and the earlier definitions; the sail law is read with them inlined.
void Context::read_sail_definitions() {
  if (!doc.control_law.sail) return;
  try {
    for (const auto& def : doc.control_law.sail->definitions) {
      const std::string& name = def.name;
      const std::string where = "control_law.sail.definitions[" + name + "]";
      if (slots.count(name)) throw std::invalid_argument(where + ": the name is already a symbol of the problem");
      const ex e = statement(def.expression.text, where);
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
  for (const auto& v : doc.shooting.variables) variables.push_back(v.name);
  for (std::size_t k = 0; k < doc.shooting.equations.size(); ++k) {
    const derivation::ShootingEquation& written = doc.shooting.equations[k];
    Equation e;
    e.name = written.name;
    if (e.name.empty()) e.name = "#" + std::to_string(k);
    const std::string where = "shooting.equations[" + e.name + "]";
    try {
      e.text = written.expression.text;
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

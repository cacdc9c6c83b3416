// The typed derivation document: each section read strictly from the artifact's JSON, and the
// JSON of the sections helios-derive and the readers share (sections.hpp).
#include "helios/derivation/document.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "helios/io/error.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::derivation {
namespace {

using io::json;

// The helpers below throw std::invalid_argument "field <pointer> ..."; the constructor adds the
// file's name in front.

// `obj`'s member `key` at `where`: an array (an empty one when absent and not required).
const json& array(const json& obj, const std::string& key, const std::string& where, bool required = true) {
  static const json kEmpty = json::array();
  if (!required && (!obj.is_object() || !obj.contains(key))) return kEmpty;
  const json& v = io::require(obj, key, where);
  if (!v.is_array()) throw std::invalid_argument("field " + where + "/" + key + " must be an array, got " + v.dump());
  return v;
}

const json& object(const json& obj, const std::string& key, const std::string& where) {
  const json& v = io::require(obj, key, where);
  if (!v.is_object()) throw std::invalid_argument("field " + where + "/" + key + " must be an object, got " + v.dump());
  return v;
}

std::string at(const std::string& where, std::size_t i) {
  return where + "/" + std::to_string(i);
}

Expression expression(const json& obj, const std::string& key, const std::string& where) {
  return {io::require_string(obj, key, where), where + "/" + key};
}

std::optional<Expression> optional_expression(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) return std::nullopt;
  return expression(obj, key, where);
}

std::optional<std::string> optional_string(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) return std::nullopt;
  return io::require_string(obj, key, where);
}

// The member `key` of `obj`, null when absent.
json optional_json(const json& obj, const std::string& key) {
  return obj.contains(key) ? obj.at(key) : json();
}

std::vector<Expression> expressions(const json& obj, const std::string& key, const std::string& where,
                                    bool required = true) {
  std::vector<Expression> out;
  const json& list = array(obj, key, where, required);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_string())
      throw std::invalid_argument("field " + at(where + "/" + key, i) + " must be a string, got " + list[i].dump());
    out.push_back({list[i].get<std::string>(), at(where + "/" + key, i)});
  }
  return out;
}

std::vector<std::string> strings(const json& obj, const std::string& key, const std::string& where) {
  std::vector<std::string> out;
  for (const auto& e : expressions(obj, key, where)) out.push_back(e.text);
  return out;
}

std::vector<double> numbers(const json& obj, const std::string& key, const std::string& where, bool required) {
  std::vector<double> out;
  const json& list = array(obj, key, where, required);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number())
      throw std::invalid_argument("field " + at(where + "/" + key, i) + " must be a number, got " + list[i].dump());
    out.push_back(list[i].get<double>());
  }
  return out;
}

// An optional string member: "" when absent.
std::string optional_text(const json& obj, const std::string& key, const std::string& where) {
  return optional_string(obj, key, where).value_or("");
}

std::optional<double> optional_number(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) return std::nullopt;
  return io::require_number(obj, key, where);
}

Times read_times(const json& d) {
  const json& t = object(d, "times", "");
  Times out;
  out.t0 = io::require_number(t, "t0", "/times");
  out.tf = optional_number(t, "tf", "/times");
  out.epoch_mjd2000 = optional_number(t, "epoch_mjd2000", "/times");
  out.final_time = io::require_string(t, "final_time", "/times");
  out.departure = optional_string(t, "departure", "/times").value_or("fixed");
  out.tf_expression = optional_expression(t, "tf_expression", "/times");
  out.t0_expression = optional_expression(t, "t0_expression", "/times");
  out.tf_window = numbers(t, "tf_window", "/times", false);
  out.t0_window = numbers(t, "t0_window", "/times", false);
  return out;
}

std::vector<Ode> read_odes(const json& d, const std::string& key, const std::string& name_key) {
  std::vector<Ode> out;
  const json& list = array(d, key, "");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = at("/" + key, i);
    out.push_back({io::require_string(list[i], name_key, where), expression(list[i], "rhs", where)});
  }
  return out;
}

// ---- the shared sections (sections.hpp): read as Expression, written from either form --------

std::vector<Definition> read_definitions(const json& law, const std::string& where) {
  std::vector<Definition> out;
  const json& defs = array(law, "definitions", where, false);
  for (std::size_t i = 0; i < defs.size(); ++i)
    out.push_back({io::require_string(defs[i], "name", at(where + "/definitions", i)),
                   expression(defs[i], "expression", at(where + "/definitions", i))});
  return out;
}

ShootingEquation read_equation(const json& e, const std::string& where) {
  ShootingEquation out;
  out.name = io::require_string(e, "name", where);
  out.expression = expression(e, "expression", where);
  out.meaning = io::require_string(e, "meaning", where);
  out.scale = io::require_number(e, "scale", where);
  out.source = optional_text(e, "source", where);
  out.alone_expression = optional_expression(e, "alone_expression", where);
  if (e.contains("inequality")) {
    const json& q = object(e, "inequality", where);
    const std::string w = where + "/inequality";
    out.inequality = Inequality{io::require_string(q, "sense", w), io::require_string(q, "multiplier", w),
                                expression(q, "inactive_expression", w), optional_json(q, "rule"), std::nullopt};
    if (q.contains("held_when_active")) {
      const json& held = object(q, "held_when_active", w);
      out.inequality->held_when_active = Inequality::Held{io::require_string(held, "variable", w + "/held_when_active"),
                                                          io::require_number(held, "value", w + "/held_when_active")};
    }
  }
  return out;
}

const std::string& text(const Expression& e) {
  return e.text;
}

std::string text(const GiNaC::ex& e) {
  return symbolic::to_text(e);
}

template <class E>
json texts(const std::vector<E>& v) {
  json out = json::array();
  for (const auto& e : v) out.push_back(text(e));
  return out;
}

// A number as helios-derive writes a bound or a window's edge: a whole one as an integer.
json number(double v) {
  return v == std::floor(v) && std::fabs(v) < 1e15 ? json(static_cast<long long>(v)) : json(v);
}

// Sets out[key] = value unless value is empty (an optional member not given).
void put(json& out, const std::string& key, const std::string& value) {
  if (!value.empty()) out[key] = value;
}

// What a direction and a sail law begin with: the controls, and the definitions where there are any.
template <class E>
json unit_vector_law(const std::vector<std::string>& controls,
                     const std::vector<sections::Definition<E>>& definitions) {
  json out = {{"controls", controls}};
  if (definitions.empty()) return out;
  json& list = out["definitions"] = json::array();
  for (const auto& def : definitions) list.push_back({{"name", def.name}, {"expression", text(def.expression)}});
  return out;
}

template <class E>
json direction_json(const sections::DirectionLaw<E>& a) {
  json out = unit_vector_law(a.controls, a.definitions);
  out["law"] = texts(a.law);
  if (!a.dH_da.empty()) out["dH_da"] = texts(a.dH_da);
  put(out, "reason", a.reason);
  return out;
}

template <class E>
json sail_json(const sections::SailLaw<E>& n) {
  json out = unit_vector_law(n.controls, n.definitions);
  out["cone_angle"] = text(n.cone_angle);
  out["law"] = texts(n.law);
  put(out, "stationarity", n.stationarity);
  put(out, "admissible", n.admissible);
  put(out, "reason", n.reason);
  return out;
}

template <class E>
json throttle_json(const sections::ThrottleLaw<E>& u) {
  json bounds = json::array();
  for (double b : u.bounds) bounds.push_back(number(b));
  json out = {{"control", u.control},
              {"bounds", bounds},
              {"switching_function", text(u.switching_function)},
              {"dH_du_at_lower", text(u.dH_du_at_lower)},
              {"dH_du_at_upper", text(u.dH_du_at_upper)}};
  if (u.d2H_du2) out["d2H_du2"] = text(*u.d2H_du2);
  out["interior"] = text(u.interior);
  put(out, "smoothing", u.smoothing);
  put(out, "law", u.law);
  return out;
}

json variable_json(const ShootingVariable& v) {
  json out = {{"name", v.name}, {"meaning", v.meaning}};
  put(out, "role", v.role);
  out["scale"] = v.scale;
  if (!v.range.empty()) out["range"] = v.range;
  put(out, "init", v.init);
  return out;
}

template <class E>
json equation_json(const sections::ShootingEquation<E>& q) {
  json out = {{"name", q.name},
              {"expression", text(q.expression)},
              {"meaning", q.meaning},
              {"scale", q.scale},
              {"source", q.source}};
  if (q.inequality) {
    const auto& b = *q.inequality;
    json& bound = out["inequality"] = {
        {"sense", b.sense}, {"multiplier", b.multiplier}, {"inactive_expression", text(b.inactive_expression)}};
    if (!b.rule.is_null()) bound["rule"] = b.rule;
    if (b.held_when_active)
      bound["held_when_active"] = {{"variable", b.held_when_active->variable},
                                   {"value", number(b.held_when_active->value)}};
  }
  if (q.alone_expression) out["alone_expression"] = text(*q.alone_expression);
  return out;
}

}  // namespace

namespace sections {

std::vector<Intermediate<Expression>> read_intermediates(const json& d) {
  std::vector<Intermediate<Expression>> out;
  const json& list = array(d, "intermediates", "", false);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = at("/intermediates", i);
    out.push_back({io::require_string(list[i], "name", where), io::require_string(list[i], "meaning", where),
                   optional_text(list[i], "unit", where), expression(list[i], "expression", where)});
  }
  return out;
}

std::vector<SideCondition<Expression>> read_side_conditions(const json& obj, const std::string& where) {
  std::vector<SideCondition<Expression>> out;
  if (!obj.contains("must_be_positive")) return out;
  const json& list = array(obj, "must_be_positive", where);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string w = at(where + "/must_be_positive", i);
    out.push_back({expression(list[i], "expression", w), io::require_string(list[i], "meaning", w)});
  }
  return out;
}

// An optional list of strings: absent reads as nullopt.
std::optional<std::vector<std::string>> optional_strings(const json& obj, const std::string& key,
                                                         const std::string& where) {
  if (!obj.contains(key)) return std::nullopt;
  return strings(obj, key, where);
}

std::vector<Constraint<Expression>> read_constraints(const json& d) {
  std::vector<Constraint<Expression>> out;
  const json& list = array(d, "constraints", "");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = at("/constraints", i);
    Constraint<Expression> c;
    c.id = io::require_string(list[i], "id", where);
    c.kind = io::require_string(list[i], "kind", where);
    c.at = io::require_string(list[i], "at", where);
    c.target = optional_json(list[i], "target");
    c.psi = expressions(list[i], "psi", where);
    c.multipliers = strings(list[i], "multipliers", where);
    c.must_be_positive = read_side_conditions(list[i], where);
    c.conditions = optional_strings(list[i], "conditions", where);
    c.eliminated_multipliers = optional_strings(list[i], "eliminated_multipliers", where);
    c.time_condition = optional_text(list[i], "time_condition", where);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<Event<Expression>> read_events(const json& d) {
  std::vector<Event<Expression>> out;
  const json& list = array(d, "events", "", false);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const json& e = list[k];
    const std::string where = at("/events", k);
    Event<Expression> ev;
    ev.id = io::require_string(e, "id", where);
    ev.kind = io::require_string(e, "kind", where);
    ev.target = optional_json(e, "target");
    const json& time = object(e, "time", where);
    ev.time_symbol = io::require_string(time, "symbol", where + "/time");
    ev.window = numbers(time, "window", where + "/time", true);
    ev.time_expression = expression(time, "expression", where + "/time");
    ev.duration = io::require_number(time, "duration", where + "/time");
    ev.psi = expressions(e, "psi", where);
    ev.multipliers = strings(e, "multipliers", where);
    ev.must_be_positive = read_side_conditions(e, where);
    ev.conditions = optional_strings(e, "conditions", where).value_or(std::vector<std::string>{});
    const json& map = array(e, "state_map", where);
    for (std::size_t i = 0; i < map.size(); ++i)
      ev.state_map.push_back({io::require_string(map[i], "state", at(where + "/state_map", i)),
                              expression(map[i], "expression", at(where + "/state_map", i))});
    const json& costates = array(e, "costate_map", where);
    for (std::size_t i = 0; i < costates.size(); ++i) {
      const std::string w = at(where + "/costate_map", i);
      ev.costate_map.push_back({io::require_string(costates[i], "costate", w),
                                optional_string(costates[i], "variable", w),
                                optional_expression(costates[i], "expression", w)});
    }
    out.push_back(std::move(ev));
  }
  return out;
}

ControlLaw<Expression> read_control_law(const json& d) {
  const json& law = object(d, "control_law", "");
  ControlLaw<Expression> out;
  for (const auto& [key, value] : law.items())
    if (key != "direction" && key != "throttle" && key != "sail") out.other.push_back(key);
  if (law.contains("direction")) {
    const json& a = object(law, "direction", "/control_law");
    const std::string w = "/control_law/direction";
    out.direction =
        DirectionLaw<Expression>{strings(a, "controls", w), read_definitions(a, w), expressions(a, "law", w),
                                 expressions(a, "dH_da", w, false), optional_text(a, "reason", w)};
  }
  if (law.contains("throttle")) {
    const json& u = object(law, "throttle", "/control_law");
    const std::string w = "/control_law/throttle";
    ThrottleLaw<Expression> t;
    t.control = io::require_string(u, "control", w);
    t.bounds = numbers(u, "bounds", w, true);
    t.switching_function = expression(u, "switching_function", w);
    t.dH_du_at_lower = expression(u, "dH_du_at_lower", w);
    t.dH_du_at_upper = expression(u, "dH_du_at_upper", w);
    t.interior = expression(u, "interior", w);
    t.d2H_du2 = optional_expression(u, "d2H_du2", w);
    t.smoothing = optional_text(u, "smoothing", w);
    t.law = optional_text(u, "law", w);
    out.throttle = std::move(t);
  }
  if (law.contains("sail")) {
    const json& n = object(law, "sail", "/control_law");
    const std::string w = "/control_law/sail";
    out.sail = SailLaw<Expression>{strings(n, "controls", w),           read_definitions(n, w),
                                   expression(n, "cone_angle", w),      expressions(n, "law", w),
                                   optional_text(n, "stationarity", w), optional_text(n, "admissible", w),
                                   optional_text(n, "reason", w)};
  }
  return out;
}

std::vector<InitialValue<Expression>> read_initial_values(const json& d) {
  std::vector<InitialValue<Expression>> out;
  const json& initial = array(d, "initial_values", "");
  for (std::size_t i = 0; i < initial.size(); ++i)
    out.push_back({io::require_string(initial[i], "state", at("/initial_values", i)),
                   expression(initial[i], "value", at("/initial_values", i))});
  return out;
}

std::vector<EventValue> read_event_values(const json& d) {
  std::vector<EventValue> out;
  const json& values = array(d, "event_values", "", false);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string where = at("/event_values", i);
    out.push_back({io::require_string(values[i], "name", where), io::require_string(values[i], "meaning", where),
                   optional_string(values[i], "kind", where), optional_string(values[i], "at", where)});
  }
  return out;
}

Shooting<Expression> read_shooting(const json& d) {
  Shooting<Expression> out;
  const json& sh = object(d, "shooting", "");
  const json& vars = array(sh, "variables", "/shooting");
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const std::string where = at("/shooting/variables", i);
    ShootingVariable v;
    v.name = io::require_string(vars[i], "name", where);
    v.meaning = io::require_string(vars[i], "meaning", where);
    v.scale = io::require_number(vars[i], "scale", where);
    v.role = optional_text(vars[i], "role", where);
    v.range = numbers(vars[i], "range", where, false);
    v.init = optional_text(vars[i], "init", where);
    out.variables.push_back(std::move(v));
  }
  const json& eqs = array(sh, "equations", "/shooting");
  for (std::size_t i = 0; i < eqs.size(); ++i)
    out.equations.push_back(read_equation(eqs[i], at("/shooting/equations", i)));
  return out;
}

template <class E>
json to_json(const std::vector<Intermediate<E>>& intermediates) {
  json out = json::array();
  for (const auto& q : intermediates) {
    json entry = {{"name", q.name}, {"meaning", q.meaning}};
    put(entry, "unit", q.unit);
    entry["expression"] = text(q.expression);
    out.push_back(entry);
  }
  return out;
}

template <class E>
json to_json(const ControlLaw<E>& law) {
  json out = json::object();
  if (law.direction) out["direction"] = direction_json(*law.direction);
  if (law.sail) out["sail"] = sail_json(*law.sail);
  if (law.throttle) out["throttle"] = throttle_json(*law.throttle);
  return out;
}

template <class E>
json to_json(const std::vector<InitialValue<E>>& values) {
  json out = json::array();
  for (const auto& v : values) out.push_back({{"state", v.state}, {"value", text(v.value)}});
  return out;
}

json to_json(const std::vector<EventValue>& values) {
  json out = json::array();
  for (const auto& v : values) {
    json value = {{"name", v.name}};
    if (v.kind) value["kind"] = *v.kind;
    if (v.at) value["at"] = *v.at;
    value["meaning"] = v.meaning;
    out.push_back(value);
  }
  return out;
}

template <class E>
json to_json(const Shooting<E>& shooting) {
  json variables = json::array(), equations = json::array();
  for (const auto& v : shooting.variables) variables.push_back(variable_json(v));
  for (const auto& q : shooting.equations) equations.push_back(equation_json(q));
  return {{"variables", variables}, {"equations", equations}};
}

template <class E>
json side_conditions_json(const std::vector<SideCondition<E>>& sides) {
  json out = json::array();
  for (const auto& side : sides) out.push_back({{"expression", text(side.expression)}, {"meaning", side.meaning}});
  return out;
}

template <class E>
json to_json(const std::vector<Constraint<E>>& constraints) {
  json list = json::array();
  for (const auto& c : constraints) {
    json out = {{"id", c.id}, {"kind", c.kind}, {"at", c.at}};
    if (!c.target.is_null()) out["target"] = c.target;
    out["psi"] = texts(c.psi);
    out["multipliers"] = c.multipliers;
    if (!c.must_be_positive.empty()) out["must_be_positive"] = side_conditions_json(c.must_be_positive);
    if (c.conditions) out["conditions"] = *c.conditions;
    if (c.eliminated_multipliers) out["eliminated_multipliers"] = *c.eliminated_multipliers;
    put(out, "time_condition", c.time_condition);
    list.push_back(out);
  }
  return list;
}

template <class E>
json to_json(const std::vector<Event<E>>& events) {
  json list = json::array();
  for (const auto& e : events) {
    json out = {{"id", e.id}, {"kind", e.kind}};
    if (!e.target.is_null()) out["target"] = e.target;
    out["time"] = {{"symbol", e.time_symbol},
                   {"window", e.window},
                   {"expression", text(e.time_expression)},
                   {"duration", e.duration}};
    out["psi"] = texts(e.psi);
    out["multipliers"] = e.multipliers;
    if (!e.must_be_positive.empty()) out["must_be_positive"] = side_conditions_json(e.must_be_positive);
    out["conditions"] = e.conditions;
    json state_map = json::array(), costate_map = json::array();
    for (const auto& m : e.state_map) state_map.push_back({{"state", m.state}, {"expression", text(m.expression)}});
    for (const auto& m : e.costate_map) {
      json entry = {{"costate", m.costate}};
      if (m.variable) entry["variable"] = *m.variable;
      if (m.expression) entry["expression"] = text(*m.expression);
      costate_map.push_back(entry);
    }
    out["state_map"] = state_map;
    out["costate_map"] = costate_map;
    list.push_back(out);
  }
  return list;
}

// helios-derive writes the GiNaC form, a reader (and the round-trip tests) the Expression form.
template json to_json(const std::vector<Intermediate<GiNaC::ex>>&);
template json to_json(const std::vector<Intermediate<Expression>>&);
template json to_json(const ControlLaw<GiNaC::ex>&);
template json to_json(const ControlLaw<Expression>&);
template json to_json(const std::vector<InitialValue<GiNaC::ex>>&);
template json to_json(const std::vector<InitialValue<Expression>>&);
template json to_json(const std::vector<Constraint<GiNaC::ex>>&);
template json to_json(const std::vector<Constraint<Expression>>&);
template json to_json(const std::vector<Event<GiNaC::ex>>&);
template json to_json(const std::vector<Event<Expression>>&);
template json to_json(const Shooting<GiNaC::ex>&);
template json to_json(const Shooting<Expression>&);

}  // namespace sections

Document::Document(const json& derivation, const std::string& file, bool parse_units)
    : Reader(derivation, file, parse_units), file(file) {
  try {
    read_sections();
    control_law = sections::read_control_law(d);
    interior_events = sections::read_events(d);
    shooting = sections::read_shooting(d);
    terms = read_terms(d, file);
  } catch (const std::invalid_argument& e) {  // "field <pointer> ..."
    throw input_error(file + ": " + e.what());
  }
  check_intermediates();
}

// An intermediate is a function of t, the states, the parameters and the earlier intermediates:
// the readers evaluate them first and differentiate through them in the states only.
void Document::check_intermediates() const {
  std::set<std::string> allowed(states.begin(), states.end()), taken;
  allowed.insert(parameters.begin(), parameters.end());
  allowed.insert("t");
  for (const auto* of : {&states, &costates, &controls, &parameters, &variables, &definitions, &event_values})
    taken.insert(of->begin(), of->end());
  taken.insert({"t", multiplier, homotopy});
  for (const auto& q : intermediate_list) {
    if (!symbolic::is_identifier(q.name) || taken.count(q.name))
      throw input_error(file + ": field /intermediates: the name '" + q.name +
                        "' is not an identifier or is taken by another symbol of the derivation");
    taken.insert(q.name);
    for (const auto& name : symbolic::free_symbols(parse(q.expression)))
      if (!allowed.count(name))
        throw input_error(
            file + ": field " + q.expression.pointer + ": the intermediate " + q.name + " uses " + name +
            "; an intermediate may use only t, the states, the parameters and the intermediates before it");
    allowed.insert(q.name);
  }
  if (intermediate_list.empty()) return;
  // They are evaluated along the trajectory (the dynamics, H, the costate equations, the control
  // law), not where the shooting rows, the endpoint and event conditions or the initial values are:
  // an expression there that names one is refused, naming both.
  std::set<std::string> names;
  for (const auto& q : intermediate_list) names.insert(q.name);
  const auto refuse_in = [&](const Expression& e) {
    for (const auto& word : symbolic::identifiers(e.text))
      if (names.count(word))
        throw input_error(file + ": field " + e.pointer + ": uses the intermediate " + word +
                          ", which is evaluated only along the trajectory (dynamics, H, costate equations, control "
                          "law); write it out here");
  };
  for (const auto& q : shooting.equations) {
    refuse_in(q.expression);
    if (q.alone_expression) refuse_in(*q.alone_expression);
    if (q.inequality) refuse_in(q.inequality->inactive_expression);
  }
  for (const auto& c : constraints) {
    for (const auto& e : c.psi) refuse_in(e);
    for (const auto& side : c.must_be_positive) refuse_in(side.expression);
  }
  for (const auto& ev : interior_events) {
    refuse_in(ev.time_expression);
    for (const auto& e : ev.psi) refuse_in(e);
    for (const auto& side : ev.must_be_positive) refuse_in(side.expression);
    for (const auto& m : ev.state_map) refuse_in(m.expression);
    for (const auto& m : ev.costate_map)
      if (m.expression) refuse_in(*m.expression);
  }
  for (const auto& v : initial_values) refuse_in(v.value);
}

symbolic::ChainRule Document::chain_rule() const {
  symbolic::ChainRule chain;
  for (const auto& q : intermediate_list)
    chain.add(GiNaC::ex_to<GiNaC::symbol>(symbols.symtab().at(q.name)), parse(q.expression));
  return chain;
}

void Document::read_sections() {
  problem_id = io::require_string(object(d, "problem", ""), "id", "/problem");
  objective = io::require_string(object(d, "problem", ""), "objective", "/problem");
  producer = optional_json(d, "producer");
  homotopy_start = io::require_number(object(d, "homotopy", ""), "start", "/homotopy");
  const json& body_list = array(d, "bodies", "", false);
  for (std::size_t i = 0; i < body_list.size(); ++i) {
    const std::string where = at("/bodies", i);
    const json& el = object(body_list[i], "elements", where);
    const std::string w = where + "/elements";
    bodies.push_back({io::require_string(body_list[i], "name", where), io::require_number(body_list[i], "epoch", where),
                      io::require_number(el, "a", w), io::require_number(el, "e", w),
                      io::require_number(el, "i_rad", w), io::require_number(el, "raan_rad", w),
                      io::require_number(el, "argp_rad", w), io::require_number(el, "mean_anomaly_rad", w)});
  }
  times = read_times(d);
  intermediate_list = sections::read_intermediates(d);
  const json& dyn = object(d, "dynamics", "");
  dynamics = {expressions(dyn, "state_rhs", "/dynamics"), expression(dyn, "running_cost", "/dynamics"),
              expression(dyn, "endpoint_cost", "/dynamics")};
  hamiltonian = expression(d, "hamiltonian", "");
  state_odes = read_odes(d, "state_odes", "state");
  costate_odes = read_odes(d, "costate_odes", "costate");
  constraints = sections::read_constraints(d);
  initial_values = sections::read_initial_values(d);
  event_value_list = sections::read_event_values(d);
  if (d.contains("coast_dynamics")) {
    const json& c = object(d, "coast_dynamics", "");
    coast_dynamics = CoastDynamics{strings(c, "states", "/coast_dynamics"), expressions(c, "rhs", "/coast_dynamics")};
  }
}

GiNaC::ex Document::parse(const Expression& e) const {
  return symbols.parse(e.text, file + ": field " + e.pointer);
}

}  // namespace helios::derivation

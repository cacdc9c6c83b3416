// The typed derivation document: each section read strictly from the artifact's JSON.
#include "helios/derivation/document.hpp"

#include <stdexcept>

#include "helios/io/error.hpp"

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

std::vector<Expression> expressions(const json& obj, const std::string& key, const std::string& where) {
  std::vector<Expression> out;
  const json& list = array(obj, key, where);
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

std::optional<double> optional_number(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.contains(key)) return std::nullopt;
  return io::require_number(obj, key, where);
}

std::vector<Definition> read_definitions(const json& law, const std::string& where) {
  std::vector<Definition> out;
  const json& defs = array(law, "definitions", where, false);
  for (std::size_t i = 0; i < defs.size(); ++i)
    out.push_back({io::require_string(defs[i], "name", at(where + "/definitions", i)),
                   expression(defs[i], "expression", at(where + "/definitions", i))});
  return out;
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

std::vector<SideCondition> read_side_conditions(const json& obj, const std::string& where) {
  std::vector<SideCondition> out;
  if (!obj.contains("must_be_positive")) return out;
  const json& list = array(obj, "must_be_positive", where);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string w = at(where + "/must_be_positive", i);
    out.push_back({expression(list[i], "expression", w), io::require_string(list[i], "meaning", w)});
  }
  return out;
}

std::vector<Constraint> read_constraints(const json& d) {
  std::vector<Constraint> out;
  const json& list = array(d, "constraints", "");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = at("/constraints", i);
    Constraint c;
    c.id = io::require_string(list[i], "id", where);
    c.kind = io::require_string(list[i], "kind", where);
    c.at = io::require_string(list[i], "at", where);
    c.psi = expressions(list[i], "psi", where);
    c.multipliers = strings(list[i], "multipliers", where);
    c.must_be_positive = read_side_conditions(list[i], where);
    c.target = optional_json(list[i], "target");
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<CostateMapEntry> read_costate_map(const json& e, const std::string& where) {
  std::vector<CostateMapEntry> out;
  const json& list = array(e, "costate_map", where);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string w = at(where + "/costate_map", i);
    out.push_back({io::require_string(list[i], "costate", w), optional_string(list[i], "variable", w),
                   optional_expression(list[i], "expression", w)});
  }
  return out;
}

Event read_event(const json& e, const std::string& where) {
  Event out;
  out.id = io::require_string(e, "id", where);
  out.kind = io::require_string(e, "kind", where);
  const json& time = object(e, "time", where);
  out.time_symbol = io::require_string(time, "symbol", where + "/time");
  out.window = numbers(time, "window", where + "/time", true);
  out.time_expression = expression(time, "expression", where + "/time");
  out.duration = io::require_number(time, "duration", where + "/time");
  out.psi = expressions(e, "psi", where);
  out.multipliers = strings(e, "multipliers", where);
  out.must_be_positive = read_side_conditions(e, where);
  const json& map = array(e, "state_map", where);
  for (std::size_t i = 0; i < map.size(); ++i)
    out.state_map.push_back({io::require_string(map[i], "state", at(where + "/state_map", i)),
                             expression(map[i], "expression", at(where + "/state_map", i))});
  out.costate_map = read_costate_map(e, where);
  out.target = optional_json(e, "target");
  return out;
}

ShootingEquation read_equation(const json& e, const std::string& where) {
  ShootingEquation out;
  out.name = io::require_string(e, "name", where);
  out.expression = expression(e, "expression", where);
  out.meaning = io::require_string(e, "meaning", where);
  out.scale = io::require_number(e, "scale", where);
  out.source = optional_string(e, "source", where).value_or("");
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

}  // namespace

const ShootingEquation* Shooting::equation(const std::string& name) const {
  for (const auto& e : equations)
    if (e.name == name) return &e;
  return nullptr;
}

Document::Document(const json& derivation, const std::string& file, bool parse_units)
    : Reader(derivation, file, parse_units), file(file) {
  try {
    read_sections();
    read_laws();
    read_events();
    read_shooting();
    terms = read_terms(d, file);
  } catch (const std::invalid_argument& e) {  // "field <pointer> ..."
    throw input_error(file + ": " + e.what());
  }
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
  const json& dyn = object(d, "dynamics", "");
  dynamics = {expressions(dyn, "state_rhs", "/dynamics"), expression(dyn, "running_cost", "/dynamics"),
              expression(dyn, "endpoint_cost", "/dynamics")};
  hamiltonian = expression(d, "hamiltonian", "");
  state_odes = read_odes(d, "state_odes", "state");
  costate_odes = read_odes(d, "costate_odes", "costate");
  constraints = read_constraints(d);
  const json& initial = array(d, "initial_values", "");
  for (std::size_t i = 0; i < initial.size(); ++i)
    initial_values.push_back({io::require_string(initial[i], "state", at("/initial_values", i)),
                              expression(initial[i], "value", at("/initial_values", i))});
  const json& values = array(d, "event_values", "", false);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string where = at("/event_values", i);
    event_value_list.push_back({io::require_string(values[i], "name", where),
                                io::require_string(values[i], "meaning", where),
                                optional_string(values[i], "kind", where), optional_string(values[i], "at", where)});
  }
  if (d.contains("coast_dynamics")) {
    const json& c = object(d, "coast_dynamics", "");
    coast_dynamics = CoastDynamics{strings(c, "states", "/coast_dynamics"), expressions(c, "rhs", "/coast_dynamics")};
  }
}

void Document::read_laws() {
  const json& law = object(d, "control_law", "");
  for (const auto& [key, value] : law.items())
    if (key != "direction" && key != "throttle" && key != "sail") control_law.other.push_back(key);
  if (law.contains("direction")) {
    const json& a = object(law, "direction", "/control_law");
    const std::string w = "/control_law/direction";
    control_law.direction = DirectionLaw{strings(a, "controls", w), read_definitions(a, w), expressions(a, "law", w)};
  }
  if (law.contains("throttle")) {
    const json& u = object(law, "throttle", "/control_law");
    const std::string w = "/control_law/throttle";
    control_law.throttle = ThrottleLaw{io::require_string(u, "control", w),    numbers(u, "bounds", w, true),
                                       expression(u, "switching_function", w), expression(u, "dH_du_at_lower", w),
                                       expression(u, "dH_du_at_upper", w),     expression(u, "interior", w),
                                       optional_expression(u, "d2H_du2", w)};
  }
  if (law.contains("sail")) {
    const json& n = object(law, "sail", "/control_law");
    const std::string w = "/control_law/sail";
    control_law.sail = SailLaw{strings(n, "controls", w), read_definitions(n, w), expression(n, "cone_angle", w),
                               expressions(n, "law", w)};
  }
}

void Document::read_events() {
  const json& list = array(d, "events", "", false);
  for (std::size_t i = 0; i < list.size(); ++i) interior_events.push_back(read_event(list[i], at("/events", i)));
}

void Document::read_shooting() {
  const json& sh = object(d, "shooting", "");
  const json& vars = array(sh, "variables", "/shooting");
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const std::string where = at("/shooting/variables", i);
    ShootingVariable v;
    v.name = io::require_string(vars[i], "name", where);
    v.meaning = io::require_string(vars[i], "meaning", where);
    v.scale = io::require_number(vars[i], "scale", where);
    v.role = optional_string(vars[i], "role", where).value_or("");
    v.range = numbers(vars[i], "range", where, false);
    shooting.variables.push_back(std::move(v));
  }
  const json& eqs = array(sh, "equations", "/shooting");
  for (std::size_t i = 0; i < eqs.size(); ++i)
    shooting.equations.push_back(read_equation(eqs[i], at("/shooting/equations", i)));
}

GiNaC::ex Document::parse(const Expression& e) const {
  return symbols.parse(e.text, file + ": field " + e.pointer);
}

}  // namespace helios::derivation

// The derivation artifact (schemas/derivation.schema.json) of a typed Derivation: expressions as
// GiNaC text, every condition and shooting row with what it means.
#include <algorithm>

#include "helios/io/schema.hpp"
#include "helios/pmp/derive.hpp"

namespace helios::pmp {
namespace {

using io::json;
using symbolic::to_text;

json texts(const std::vector<GiNaC::ex>& v) {
  json out = json::array();
  for (const auto& e : v) out.push_back(to_text(e));
  return out;
}

json named_list(const std::vector<Named>& v, bool with_value) {
  json out = json::array();
  for (const auto& n : v) {
    json e = {{"name", n.name}, {"meaning", n.meaning}, {"unit", n.unit}};
    if (with_value) e["value"] = n.value;
    if (!n.source.empty()) e["source"] = n.source;
    if (!n.role.empty()) e["role"] = n.role;
    out.push_back(e);
  }
  return out;
}

// The constraint's section (derivation/sections.hpp): its rows, multipliers and side conditions,
// and the conditions it gives in words.
derivation::sections::Constraint<GiNaC::ex> constraint_section(const EndpointConditions& c) {
  const EndpointConstraint& k = c.constraint;
  derivation::sections::Constraint<GiNaC::ex> out{k.id,
                                                  k.kind,
                                                  k.at,
                                                  k.target,
                                                  k.psi,
                                                  c.multipliers,
                                                  k.must_be_positive,
                                                  std::vector<std::string>{},
                                                  std::nullopt,
                                                  c.time_condition};
  if (k.at == "t0") {
    out.conditions->push_back("x(t0) is fixed for " + std::to_string(k.fixed_states.size()) +
                              " states, so their costates at t0 are free (shooting variables)");
    for (const auto& q : k.free_parameters)
      out.conditions->push_back("nu^T dpsi/d" + q.name + " = 0 with lambda(t0) = -nu^T dpsi/dx: " + q.name +
                                " is a free parameter of psi");
  } else {
    out.eliminated_multipliers.emplace();
    for (const auto& row : c.transversality) out.conditions->push_back(to_text(row) + " = 0");
    for (const auto& row : c.eliminated) out.eliminated_multipliers->push_back(to_text(row) + " = 0");
  }
  return out;
}

// The event's section: its epoch, rows, the conditions in words and the maps across it.
derivation::sections::Event<GiNaC::ex> event_section(const Problem& p, const EventConditions& c) {
  const InteriorEvent& e = c.event;
  derivation::sections::Event<GiNaC::ex> out;
  out.id = e.id;
  out.kind = e.kind;
  out.target = e.target;
  out.time_symbol = c.time_symbol;
  out.window = {e.window_lo, e.window_hi};
  out.time_expression = c.time;
  out.duration = e.duration;
  out.psi = c.psi;
  out.multipliers = c.multipliers;
  out.must_be_positive = e.must_be_positive;
  for (std::size_t s = 0; s < p.states.size(); ++s) {
    const std::string& x = p.states[s].name;
    const std::string xm = names::before(x, e.id);
    out.conditions.push_back(names::before(names::costate(x), e.id) + " = nu^T dc/d" + xm + " + lambda(t+)^T dg/d" +
                             xm);
    out.state_map.push_back({x, e.map[s]});
    const CostateAfterEvent& l = c.costate_map[s];
    if (l.shooting_variable)
      out.costate_map.push_back({l.costate, to_text(l.value), std::nullopt});
    else
      out.costate_map.push_back({l.costate, std::nullopt, l.value});
  }
  out.conditions.push_back("lambda(t+) = -nu_g (the multipliers of x+ - g)");
  out.conditions.push_back("H(t-) - H(t+) + nu_c^T dc/dt + lambda(t+)^T dg/dt = 0 (free epoch)");
  for (const auto& q : e.free_parameters)
    out.conditions.push_back("nu_c^T dc/d" + q + " + lambda(t+)^T dg/d" + q + " = 0");
  return out;
}

json homotopy_json(bool smoothed) {
  if (smoothed)
    return {{"symbol", "eps"},
            {"start", 1.0},
            {"end", 0.0},
            {"meaning", "quadratic smoothing of the throttle: eps = 1 energy-like, eps = 0 fuel-optimal bang-bang"}};
  return {{"symbol", "eps"},
          {"start", 0.0},
          {"end", 0.0},
          {"meaning", "none: H does not contain eps (no smoothing is needed or used)"}};
}

json bodies_json(const std::vector<OrbitBody>& orbit_bodies) {
  json bodies = json::array();
  for (const auto& b : orbit_bodies)
    bodies.push_back({{"name", b.name},
                      {"model", "kepler"},
                      {"epoch", b.epoch},
                      {"elements",
                       {{"a", b.elements.a},
                        {"e", b.elements.e},
                        {"i_rad", b.elements.i},
                        {"raan_rad", b.elements.raan},
                        {"argp_rad", b.elements.argp},
                        {"mean_anomaly_rad", b.elements.mean_anomaly}}},
                      {"meaning", "Keplerian orbit about the central body (normalized a and epoch)"}});
  return bodies;
}

// The terms whose sums are f and L: name, kind, the parameters each uses and its details.
json terms_json(const std::vector<TermListing>& terms) {
  json list = json::array();
  for (const auto& t : terms) {
    json entry = {{"name", t.name}, {"kind", t.kind}, {"parameters", t.parameters}};
    for (const auto& [key, value] : t.details.items()) entry[key] = value;
    list.push_back(entry);
  }
  return list;
}

// The problem as the derivation sees it: states with their costates, controls, parameters,
// the dynamics and the bodies the runtime propagates.
void problem_sections(const Derivation& d, json& doc) {
  const Problem& p = d.problem;
  doc["problem"] = {{"id", p.id},
                    {"dynamics_model", p.dynamics_model},
                    {"objective", p.objective},
                    {"perturbations", p.perturbations}};
  doc["units"] = units_of(p);
  doc["times"] = times_of(p);
  json states = named_list(p.states, false);
  for (auto& s : states) s["costate"] = names::costate(s["name"].get<std::string>());
  doc["states"] = states;
  json controls = json::array();
  for (const auto& c : p.controls) controls.push_back({{"name", c.name}, {"meaning", c.meaning}, {"kind", c.kind}});
  doc["controls"] = controls;
  doc["parameters"] = named_list(p.parameters, true);
  doc["terms"] = terms_json(p.terms);
  doc["homotopy"] = homotopy_json(d.smoothed);
  doc["multiplier"] = "lambda0";
  if (!p.intermediates.empty()) doc["intermediates"] = derivation::sections::to_json(p.intermediates);
  doc["dynamics"] = {{"state_rhs", texts(p.f)},
                     {"running_cost", to_text(p.running_cost)},
                     {"endpoint_cost", to_text(p.endpoint_cost)}};
  const bool coasting = std::any_of(p.parameters.begin(), p.parameters.end(),
                                    [](const Named& q) { return q.source.rfind("coast:", 0) == 0; });
  if (coasting) doc["coast_dynamics"] = {{"states", {"rx", "ry", "rz", "vx", "vy", "vz"}}, {"rhs", texts(p.coast_f)}};
  if (!d.hamiltonian_values.empty()) doc["event_values"] = derivation::sections::to_json(d.hamiltonian_values);
  if (!p.orbit_bodies.empty()) doc["bodies"] = bodies_json(p.orbit_bodies);
}

// Refuses an expression text longer than its readers accept (symbolic::kMaxExpressionChars):
// a derivation helios-verify and helios-gen would reject is not written.
void check_expression_sizes(const json& doc) {
  io::for_each_scalar(doc, [](const json& value, const std::string& where) {
    if (value.is_string() && value.get_ref<const std::string&>().size() > symbolic::kMaxExpressionChars)
      throw std::domain_error(
          "the derivation's " + where + " would be " + std::to_string(value.get_ref<const std::string&>().size()) +
          " characters; an expression may have at most " + std::to_string(symbolic::kMaxExpressionChars) +
          " (the problem's expressions are too large)");
  });
}

}  // namespace

json derivation_json(const Derivation& d) {
  const Problem& p = d.problem;
  json doc = io::artifact_header("derivation", "helios-derive", "builtin");
  problem_sections(d, doc);
  if (!d.events.empty()) {
    std::vector<derivation::sections::Event<GiNaC::ex>> events;
    for (const auto& e : d.events) events.push_back(event_section(p, e));
    doc["events"] = derivation::sections::to_json(events);
  }
  doc["hamiltonian"] = to_text(d.hamiltonian);
  json state_odes = json::array(), costate_odes = json::array();
  for (std::size_t i = 0; i < p.states.size(); ++i) {
    state_odes.push_back({{"state", p.states[i].name}, {"rhs", to_text(d.state_odes[i])}});
    costate_odes.push_back({{"costate", names::costate(p.states[i].name)}, {"rhs", to_text(d.costate_odes[i])}});
  }
  doc["state_odes"] = state_odes;
  doc["costate_odes"] = costate_odes;
  doc["control_law"] = derivation::sections::to_json(d.control);
  doc["initial_values"] = derivation::sections::to_json(d.initial_values);
  std::vector<derivation::sections::Constraint<GiNaC::ex>> constraints;
  for (const auto& c : d.constraints) constraints.push_back(constraint_section(c));
  doc["constraints"] = derivation::sections::to_json(constraints);
  doc["shooting"] = derivation::sections::to_json(d.shooting);
  check_expression_sizes(doc);
  return doc;
}

json units_of(const Problem& p) {
  return {{"length", p.units.length_name},
          {"length_km", p.units.length_km},
          {"time", p.units.time_name},
          {"time_s", p.units.time_s},
          {"mass_kg", p.units.mass_kg}};
}

json times_of(const Problem& p) {
  json times;
  if (p.free_final_time) {
    const GiNaC::symbol tf_frac(names::fraction("tf"));
    times = {{"t0", p.t0},
             {"final_time", "free"},
             {"tf_window", {p.tf_min, p.tf}},
             {"tf_expression", to_text(p.tf_min + (p.tf - p.tf_min) * tf_frac)}};
  } else {
    times = {{"t0", p.t0}, {"tf", p.tf}, {"final_time", "fixed"}};
  }
  if (p.free_departure) {
    // The departure slides in its window; the total time of flight stays fixed.
    const GiNaC::symbol t0_frac(names::fraction("t0"));
    const GiNaC::ex t0 = p.t0_min + (p.t0_max - p.t0_min) * t0_frac;
    times["departure"] = "free";
    times["t0_window"] = {p.t0_min, p.t0_max};
    times["t0_expression"] = to_text(t0);
    times["tf_expression"] = to_text(t0 + (p.tf - p.t0));
  }
  if (p.has_epoch) times["epoch_mjd2000"] = p.epoch_mjd2000;
  return times;
}

}  // namespace helios::pmp

// The problem of a spec in the solver's normalized units: the spacecraft's states, controls
// and parameters, the dynamics f(x, u), the running cost and the times; the constraints are
// built in constraints.cpp.
#include "helios/pmp/model.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "constraints.hpp"
#include "helios/astro/constants.hpp"
#include "terms/term.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using io::json;

Units units_for(const json& central_body) {
  using namespace helios::astro;
  const std::string name = central_body.at("name").get<std::string>();
  const double mu = central_body.at("mu_km3_s2").get<double>();
  Units u;
  if (name == "Sun" || name == "sun") {
    u.length_name = "AU";
    u.time_name = "Julian year";
    u.length_km = AU_KM;
    u.time_s = JULIAN_YEAR_DAYS * DAY_S;
  } else {
    // Planetocentric: body radius and the time unit that makes mu = 1.
    const double radius = central_body.contains("radius_km") ? central_body.at("radius_km").get<double>()
                          : name == "Earth"                  ? R_EARTH_KM
                          : name == "Mars"                   ? R_MARS_KM
                                                             : 0.0;
    if (radius == 0.0) throw std::invalid_argument("field /central_body/name: no radius known for '" + name + "'");
    u.length_name = name + " radius";
    u.length_km = radius;
    u.time_s = std::sqrt(radius * radius * radius / mu);
    u.time_name = "time unit (mu = 1)";
  }
  return u;
}

}  // namespace

bool Problem::has_state(const std::string& name) const {
  for (const auto& s : states)
    if (s.name == name) return true;
  return false;
}

symbolic::ChainRule Problem::chain_rule() const {
  symbolic::ChainRule chain;
  const auto symbol = [&](const std::string& name) { return GiNaC::ex_to<GiNaC::symbol>(symbols.symtab().at(name)); };
  std::set<std::string> named;
  for (const auto& q : intermediates) {
    chain.add(symbol(q.name), q.expression);
    named.insert(q.name);
  }
  for (const auto& q : intermediates)
    for (const auto& s : states)
      if (named.count(names::partial(q.name, s.name)))
        chain.name_partial(symbol(q.name), symbol(s.name), symbol(names::partial(q.name, s.name)));
  return chain;
}

bool Problem::has_control(const std::string& name) const {
  for (const auto& c : controls)
    if (c.name == name) return true;
  return false;
}

namespace {

// The problem's name, its dynamics model (with its perturbations) and its objective and units.
void describe(Problem& p, const json& spec) {
  p.id = spec.at("problem").at("id").get<std::string>();
  const json& dyn = spec.at("dynamics");
  p.propulsion = dyn.at("propulsion").get<std::string>();
  bool j2 = false;
  for (const auto& q : dyn.value("perturbations", json::array())) {
    j2 = j2 || q.at("kind") == "j2";
    p.perturbations.push_back(q.value("name", q.at("kind").get<std::string>()));
  }
  p.dynamics_model = dyn.at("model").get<std::string>() + (j2 ? "_j2" : "") + "_" +
                     dyn.at("coordinates").get<std::string>() + "_" + p.propulsion;
  p.objective = spec.at("objective").at("kind").get<std::string>();
  p.units = units_for(spec.at("central_body"));
}

// The force terms of the spec, built by the catalogue's entries in its order (the order their
// parameters are registered): two-body gravity, J2, the engine, the user's accelerations, the third
// bodies, ...; a perturbation's term once for each of the spec's entries of its kind.
terms::ForceList force_terms(const Problem& p, const json& spec) {
  const std::string mass_unit = p.free_initial_mass ? "final mass" : "initial mass";
  const json perturbations = spec.at("dynamics").value("perturbations", json::array());
  for (const auto& q : perturbations)
    if (!find_perturbation(q.at("kind").get<std::string>()))
      throw std::invalid_argument("field /dynamics/perturbations: no term of the catalogue is built from the kind '" +
                                  q.at("kind").get<std::string>() + "'");
  terms::ForceList forces;
  int engines = 0;
  for (const auto& entry : term_catalogue()) {
    if (!entry.build) continue;
    const auto add = [&](const json* perturbation) {
      auto term = entry.build({p, spec, perturbation, mass_unit});
      if (!term) return;
      engines += entry.engine;
      forces.push_back(std::move(term));
    };
    if (entry.spec_kind.empty())
      add(nullptr);
    else
      for (const auto& q : perturbations)
        if (q.at("kind") == entry.spec_kind) add(&q);
  }
  if (engines != 1)
    throw std::invalid_argument("field /spacecraft: " + std::to_string(engines) +
                                " engine terms of the catalogue apply to the spacecraft; its propulsion needs one");
  return forces;
}

// The states, controls and parameters: position and velocity in the central body's field, and
// what each force term adds (a sail's normal, or a thruster's throttle and direction with the
// mass it burns).
terms::ForceList spacecraft(Problem& p, const json& spec) {
  const json& sc = spec.at("spacecraft");
  // Minimum initial mass: m0 is unknown and the final (dry + payload) mass is given, so it sets the
  // mass scale; otherwise m0 does.
  p.free_initial_mass = p.objective == "minimum_initial_mass";
  const std::string mass_field = p.free_initial_mass ? "final_mass_kg" : "initial_mass_kg";
  if (p.propulsion != "solar_sail") {
    if (!sc.contains(mass_field))
      throw std::invalid_argument("field /spacecraft/" + mass_field + " is missing (objective " + p.objective + ")");
    p.units.mass_kg = sc.at(mass_field).get<double>();
  }
  const std::string L = p.units.length_name, T = p.units.time_name;
  p.states = {{"rx", "position x", L},           {"ry", "position y", L},           {"rz", "position z", L},
              {"vx", "velocity x", L + "/" + T}, {"vy", "velocity y", L + "/" + T}, {"vz", "velocity z", L + "/" + T}};
  terms::ForceList forces = force_terms(p, spec);
  for (const auto& term : forces) {
    for (auto& s : term->states()) p.states.push_back(s);
    for (auto& c : term->controls()) p.controls.push_back(c);
    for (auto& q : term->parameters()) p.parameters.push_back(q);
  }
  return forces;
}

// The symbols of the model, in a fixed order: GiNaC orders terms by the symbols' creation, so
// this order fixes the text of every expression derived from them.
void register_symbols(Problem& p) {
  auto& S = p.symbols;
  for (const auto& s : p.states) {
    S.get(s.name);
    S.get(names::costate(s.name));
  }
  for (const auto& c : p.controls) S.get(c.name);
  for (const auto& q : p.parameters) S.get(q.name);
  S.get("lambda0");
  S.get("t");
  S.get("eps");
}

// Each intermediate's own partial derivatives in the states, intermediates of their own
// (names::partial): the costate equations then hold dT/dr as dT/dP dP_in_drx, not the power law's
// gradient multiplied into every term.
void state_partials(Problem& p) {
  const std::size_t given = p.intermediates.size();
  for (std::size_t i = 0; i < given; ++i)
    for (const auto& s : p.states) {
      const derivation::sections::Intermediate<ex> q = p.intermediates[i];
      const ex d = q.expression.diff(p.symbols.get(s.name));
      if (d.is_zero()) continue;
      p.symbols.get(names::partial(q.name, s.name));
      p.intermediates.push_back({names::partial(q.name, s.name),
                                 "the partial derivative of " + q.name + " in " + s.name + " (at fixed intermediates)",
                                 q.unit + "/" + s.unit, d});
    }
}

// f(x, u): the sum of the force terms' accelerations and mass rates, each term listed; the
// natural field's terms alone are the coast dynamics of coasting targets.
void dynamics(Problem& p, const terms::ForceList& forces) {
  auto& S = p.symbols;
  const bool has_mass = p.has_state("m");
  const terms::Frame x = {
      {S.get("rx"), S.get("ry"), S.get("rz")}, {S.get("vx"), S.get("vy"), S.get("vz")}, has_mass ? S.get("m") : ex(1)};
  std::vector<ex> accel = {0, 0, 0}, field = {0, 0, 0};
  ex mass_rate = 0;
  for (const auto& term : forces) {
    const std::vector<ex> a = term->acceleration(p, x);
    for (int i = 0; i < 3; ++i) {
      accel[i] += a[i];
      if (find_term(term->name())->field) field[i] += a[i];
    }
    mass_rate += term->mass_rate(p);
    std::vector<std::string> used;
    for (const auto& q : term->parameters()) used.push_back(q.name);
    p.terms.push_back(terms::listing(term->name(), "force", used, term->details(p)));
  }
  p.coast_f = {x.v[0], x.v[1], x.v[2], field[0], field[1], field[2]};
  p.f = {x.v[0], x.v[1], x.v[2], accel[0], accel[1], accel[2]};
  if (has_mass) p.f.push_back(mass_rate);
  state_partials(p);
}

// The running cost L and the endpoint cost phi of the objective's cost term.
void objective(Problem& p) {
  std::unique_ptr<terms::CostTerm> cost;
  const bool full_throttle = !p.has_control("u") && p.propulsion != "solar_sail";
  if (p.objective == "minimum_fuel" || p.objective == "minimum_initial_mass") {
    if (p.propulsion == "solar_sail")
      throw std::invalid_argument("field /objective/kind: a solar sail uses no fuel; minimize the time instead");
    if (full_throttle)
      throw std::invalid_argument(
          "field /objective/kind: an engine at full throttle throughout burns a fixed "
          "amount of fuel; minimize the time or maximize the final radius instead");
    if (p.objective == "minimum_initial_mass" && !p.thrust_parameters.empty() && p.thrust_parameters[0] != "Tmax")
      throw std::invalid_argument(
          "field /objective/kind: minimum_initial_mass with a solar-electric engine is not supported (its guess "
          "of m0 assumes a constant mass flow); minimize the fuel instead");
    if (!p.has_state("m") && p.objective == "minimum_initial_mass")
      throw std::invalid_argument(
          "field /objective/kind: an engine of constant mass burns no propellant that a larger initial mass would "
          "carry; minimize the fuel or the time instead");
    // An engine of constant mass: the L1 cost Tmax/c u (the propellant it would burn) where it has an
    // exhaust velocity, else Tmax/m u (the delta-v).
    const bool priced = p.has_state("m") || std::any_of(p.parameters.begin(), p.parameters.end(),
                                                        [](const Named& q) { return q.name == "c"; });
    cost = p.objective == "minimum_initial_mass" ? terms::initial_mass_cost()
           : priced                              ? terms::fuel_cost()
                                                 : terms::delta_v_cost();
  } else if (p.objective == "minimum_time") {
    cost = terms::time_cost();
  } else if (p.objective == "maximum_final_radius" || p.objective == "maximum_final_energy") {
    if (p.free_final_time)
      throw std::invalid_argument("field /objective/kind: " + p.objective +
                                  " needs a fixed time of flight (with it free the final radius has no maximum)");
    cost = p.objective == "maximum_final_radius" ? terms::final_radius_cost() : terms::final_energy_cost();
  } else {
    throw std::invalid_argument("field /objective/kind: " + p.objective + " is not supported");
  }
  p.running_cost = cost->running_cost(p);
  p.endpoint_cost = cost->endpoint_cost(p);
  p.terms.push_back(terms::listing(cost->name(), "cost", cost->parameters()));
}

// t0 = 0 and tf (or its window), a sliding departure's window and the calendar epoch.
void times(Problem& p, const json& time) {
  const double time_s = p.units.time_s;
  p.t0 = 0;
  p.free_final_time = time.at("final_time") == "free";
  if (p.free_final_time) {
    p.tf_min = time.at("tof_min_days").get<double>() * helios::astro::DAY_S / time_s;
    p.tf = time.at("tof_max_days").get<double>() * helios::astro::DAY_S / time_s;
  } else {
    p.tf = time.at("tof_days").get<double>() * helios::astro::DAY_S / time_s;
  }
  p.final_mass = 1;
  p.free_departure = time.value("departure", "fixed") == "free";
  if (p.free_departure) {
    if (p.free_final_time)
      throw std::invalid_argument("field /time/departure: a free departure needs a fixed total time of flight");
    if (!time.contains("t0_window_days") || !time.contains("epoch_mjd2000"))
      throw std::invalid_argument("field /time: a free departure needs t0_window_days and epoch_mjd2000");
    p.t0_min = time.at("t0_window_days")[0].get<double>() * helios::astro::DAY_S / time_s;
    p.t0_max = time.at("t0_window_days")[1].get<double>() * helios::astro::DAY_S / time_s;
    if (!(p.t0_max > p.t0_min)) throw std::invalid_argument("field /time/t0_window_days: the window is empty");
  }
  if (time.contains("epoch_mjd2000")) {
    p.epoch_mjd2000 = time.at("epoch_mjd2000").get<double>();
    p.has_epoch = true;
  }
}

}  // namespace

// Every number of the problem in normalized units is finite: a spec magnitude beyond double
// precision (mu of 1e308 km^3/s^2, a flight of 1e306 days) is refused here, by its meaning,
// rather than written as a derivation that fails its schema.
void check_magnitudes(const Problem& p) {
  const auto refuse = [](const std::string& what) {
    throw std::domain_error(what +
                            " is not finite in normalized units: a value of the spec is beyond the range of "
                            "double precision");
  };
  for (const auto& q : p.parameters)
    if (!std::isfinite(q.value)) refuse("the " + q.meaning + " (parameter " + q.name + ")");
  for (const double t : {p.t0, p.tf, p.tf_min, p.t0_min, p.t0_max})
    if (!std::isfinite(t)) refuse("a time of the problem (departure, time of flight or their window)");
  for (const auto& e : p.events)
    if (!std::isfinite(e.duration) || !std::isfinite(e.window_lo) || !std::isfinite(e.window_hi))
      refuse("the time of event " + e.id);
}

Problem build_problem(const json& spec) {
  Problem p;
  describe(p, spec);
  const terms::ForceList forces = spacecraft(p, spec);
  register_symbols(p);
  dynamics(p, forces);
  times(p, spec.at("time"));
  objective(p);
  refuse_free_node_by_symmetry(spec);
  for (const auto& c : spec.at("constraints")) {
    if (c.at("at") == "interior")
      p.events.push_back(interior_event(p, c));
    else
      p.constraints.push_back(endpoint_constraint(p, c));
  }
  for (std::size_t i = 1; i < p.events.size(); ++i)
    if (p.events[i].window_lo < p.events[i - 1].window_lo)
      throw std::invalid_argument("constraint '" + p.events[i].id + "': interior events must be listed in time order");
  check_magnitudes(p);
  return p;
}

}  // namespace helios::pmp

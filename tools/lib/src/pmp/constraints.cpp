// The constraints of a problem from its spec: the targets' states as parameters (ephemerides,
// Keplerian orbits, coasting or fixed states), endpoint constraints psi and interior events.
#include "constraints.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <stdexcept>

#include "helios/astro/constants.hpp"
#include "helios/pmp/catalogue.hpp"
#include "helios/spec/state_conditions.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using io::json;
using symbolic::to_text;

const std::vector<std::string> kPositionVelocity = {"rx", "ry", "rz", "vx", "vy", "vz"};

// Registers a body on a Keplerian orbit (once per name) so the runtime can propagate it.
void add_orbit_body(Problem& p, const std::string& name, const json& el) {
  for (const auto& b : p.orbit_bodies)
    if (b.name == name) return;
  using namespace helios::astro;
  OrbitBody b;
  b.name = name;
  b.elements.a = el.at("a_AU").get<double>() * AU_KM / p.units.length_km;
  b.elements.e = el.at("e").get<double>();
  b.elements.i = el.at("i_deg").get<double>() * DEG_TO_RAD;
  b.elements.raan = el.at("raan_deg").get<double>() * DEG_TO_RAD;
  b.elements.argp = el.at("argp_deg").get<double>() * DEG_TO_RAD;
  if (el.contains("mean_anomaly_deg")) {
    b.elements.mean_anomaly = el.at("mean_anomaly_deg").get<double>() * DEG_TO_RAD;
  } else {
    // True to mean anomaly through the eccentric anomaly.
    const double nu = el.at("true_anomaly_deg").get<double>() * DEG_TO_RAD, e = b.elements.e;
    const double E = 2 * std::atan2(std::sqrt(1 - e) * std::sin(nu / 2), std::sqrt(1 + e) * std::cos(nu / 2));
    b.elements.mean_anomaly = E - e * std::sin(E);
  }
  b.epoch = (el.at("epoch_mjd2000").get<double>() - p.epoch_mjd2000) * DAY_S / p.units.time_s;
  p.orbit_bodies.push_back(b);
}

// The target's position and velocity at `event` (t0, tf, an interior event's id or <id>_dep) as
// parameters <prefix>_rx ... <prefix>_vz; `rates` gets their time derivatives, 0 unless `moving`.
std::vector<ex> target_state(Problem& p, const std::string& prefix, const json& target, const std::string& event,
                             bool moving, std::vector<ex>& rates) {
  auto& S = p.symbols;
  const Units& U = p.units;
  const std::string L = U.length_name, T = U.time_name;
  const std::string kind = target.at("kind");
  if ((kind == "body" || kind == "orbit") && !p.has_epoch)
    throw std::invalid_argument("field /time/epoch_mjd2000 is missing but target '" + prefix +
                                "' follows a body's motion");
  if (kind == "orbit") add_orbit_body(p, target.at("body"), target.at("elements"));
  std::vector<ex> state;
  rates.clear();
  for (std::size_t j = 0; j < kPositionVelocity.size(); ++j) {
    const std::string& n = kPositionVelocity[j];
    const bool is_pos = j < 3;
    const int i = static_cast<int>(j % 3);
    const std::string unit = is_pos ? L : L + "/" + T;
    const std::string name = names::target_component(prefix, n);
    const std::string what = std::string(is_pos ? "position " : "velocity ") + n[1];
    state.push_back(S.get(name));
    ex rate = 0;
    if (kind == "fixed_state") {
      const double value = is_pos ? target.at("position_km")[i].get<double>() / U.length_km
                                  : target.at("velocity_km_s")[i].get<double>() / U.speed_km_s();
      p.parameters.push_back({name, what + " of target " + prefix, unit, value});
    } else if (kind == "body" || kind == "orbit") {
      const std::string body = target.at("body").get<std::string>();
      const std::string model = kind == "body" ? "JPL low-precision ephemeris" : "Keplerian orbit";
      p.parameters.push_back(
          {name, what + " of " + body + " (" + model + ") at " + event, unit, 0.0, "ephemeris:" + body + ":" + event});
      if (moving) {
        const std::string rname = names::rate(name);
        p.parameters.push_back({rname, "time derivative of " + name + " (of the ephemeris model)", unit + "/" + T, 0.0,
                                "ephemeris_rate:" + body + ":" + event});
        rate = S.get(rname);
      }
    } else {
      const std::string start = names::initial_value(name);
      const double value = is_pos ? target.at("position_km")[i].get<double>() / U.length_km
                                  : target.at("velocity_km_s")[i].get<double>() / U.speed_km_s();
      p.parameters.push_back({start, what + " of coasting target " + prefix + " at t0", unit, value});
      S.get(start);
      p.parameters.push_back({name, what + " of coasting target " + prefix + " at " + event + " (propagated unpowered)",
                              unit, 0.0, "coast:" + prefix + ":" + event});
    }
    rates.push_back(rate);
  }
  if (kind == "coasting" && moving) {
    // A coasting target moves by the coast dynamics at its own state.
    GiNaC::exmap at_target;
    for (std::size_t i = 0; i < kPositionVelocity.size(); ++i) at_target[S.get(kPositionVelocity[i])] = state[i];
    for (std::size_t j = 0; j < kPositionVelocity.size(); ++j) rates[j] = p.coast_f[j].subs(at_target);
  }
  for (std::size_t j = 0; j < state.size(); ++j)
    if (!rates[j].is_zero()) p.parameter_rates[GiNaC::ex_to<GiNaC::symbol>(state[j]).get_name()] = rates[j];
  return state;
}

// A bound on the speed relative to a target, |v_rel|^2 - vmax^2 <= 0 (the square keeps it smooth
// where v_rel = 0); vmax becomes the parameter vmax_<id>.
ex speed_bound(Problem& p, const std::string& id, const std::vector<ex>& relative, double max_km_s) {
  const std::string name = "vmax_" + id;
  p.parameters.push_back({name, "highest speed relative to " + id, p.units.length_name + "/" + p.units.time_name,
                          max_km_s / p.units.speed_km_s()});
  const ex vmax = p.symbols.get(name);
  return relative[0] * relative[0] + relative[1] * relative[1] + relative[2] * relative[2] - vmax * vmax;
}

// An interior event's identity and window; throws for what the engine cannot formulate.
InteriorEvent event_window(const Problem& p, const json& c) {
  InteriorEvent e;
  e.id = c.at("id");
  e.kind = c.at("kind");
  e.target = c.at("target");
  const std::string where = "constraint '" + e.id + "'";
  const double day = helios::astro::DAY_S / p.units.time_s;
  e.window_lo = c.at("window_days")[0].get<double>() * day;
  e.window_hi = c.at("window_days")[1].get<double>() * day;
  if (!(e.window_hi > e.window_lo)) throw std::invalid_argument(where + ": field window_days is empty");
  if (e.target.at("kind") == "coasting" || e.target.at("kind") == "fixed_state")
    throw std::invalid_argument(where + ": an interior event needs a moving body (an ephemeris or an orbit)");
  const double tf_max = p.free_departure ? p.t0_max + p.tf : p.tf;
  if (e.window_lo <= (p.free_departure ? p.t0_min : p.t0) || e.window_hi >= tf_max)
    throw std::invalid_argument(where + ": its window must lie inside the time of flight");
  e.duration = c.value("stay_days", 0.0) * day;
  return e;
}

// The window as two bounds on the epoch (two-pass): window_lo - t <= 0 and t - window_hi <= 0.
void window_rows(Problem& p, InteriorEvent& e) {
  const ex t = p.symbols.get(names::event_time(e.id));
  e.c.push_back(e.window_lo - t);
  e.c_names.push_back("window start - " + names::event_time(e.id) + " (<= 0: not before the window)");
  e.c_inequality.push_back(true);
  e.c.push_back(t - e.window_hi);
  e.c_names.push_back(names::event_time(e.id) + " - window end (<= 0: not after the window)");
  e.c_inequality.push_back(true);
}

// The conditions c on the arriving state x-: it meets the target (a flyby or swing-by in
// position only), a flyby's bounded relative speed, and the window.
void arrival_conditions(Problem& p, const json& c, InteriorEvent& e, const std::vector<ex>& xm,
                        const std::vector<ex>& arrival) {
  const std::size_t matched = e.kind == "rendezvous" ? 6 : 3;
  for (std::size_t j = 0; j < matched; ++j) {
    e.c.push_back(xm[j] - arrival[j]);
    e.c_names.push_back(kPositionVelocity[j] + " - " + to_text(arrival[j]));
    e.c_inequality.push_back(false);
  }
  if (c.contains("max_relative_speed_km_s")) {
    if (e.kind != "flyby")
      throw std::invalid_argument("constraint '" + e.id + "': only a flyby has a relative speed to bound");
    std::vector<ex> relative(3);
    for (int i = 0; i < 3; ++i) relative[i] = xm[3 + i] - arrival[3 + i];
    e.c.push_back(speed_bound(p, e.id, relative, c.at("max_relative_speed_km_s").get<double>()));
    e.c_names.push_back("|v - v_" + e.id + "|^2 - vmax_" + e.id + "^2 (<= 0)");
    e.c_inequality.push_back(true);
  }
  window_rows(p, e);
}

// Unpowered patched-conic swing-by: the excess velocity v_inf = v- - v_body keeps its size and
// turns by delta, at azimuth phi about v_inf measured from the ecliptic-parallel normal w:
//   v_inf+ = cos(delta) v_inf + sin(delta) (cos(phi) |v_inf| w/|w| + sin(phi) v_inf x w/|w|),
//   w = z x v_inf. delta and phi are free parameters of psi (Category C).
void gravity_assist(Problem& p, const json& c, InteriorEvent& e, const std::vector<ex>& xm,
                    const std::vector<ex>& arrival) {
  auto& S = p.symbols;
  const Units& U = p.units;
  const std::string where = "constraint '" + e.id + "'";
  if (!c.contains("body_mu_km3_s2")) throw std::invalid_argument(where + ": field body_mu_km3_s2 is missing");
  const std::string mu_name = "mu_" + e.id, delta = "delta_" + e.id, phi = "phi_" + e.id;
  p.parameters.push_back(
      {mu_name, "gravitational parameter of the swing-by body " + e.id, U.length_name + "^3/" + U.time_name + "^2",
       c.at("body_mu_km3_s2").get<double>() * U.time_s * U.time_s / (U.length_km * U.length_km * U.length_km)});
  const ex d = S.get(delta), f = S.get(phi);
  e.free_parameters = {delta, phi};
  std::vector<ex> vinf(3);
  for (int i = 0; i < 3; ++i) vinf[i] = xm[3 + i] - arrival[3 + i];
  const auto cross = [](const std::vector<ex>& a, const std::vector<ex>& b) {
    return std::vector<ex>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const std::vector<ex> w = cross({0, 0, 1}, vinf), vw = cross(vinf, w);
  const ex wn = GiNaC::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const ex vn = GiNaC::sqrt(vinf[0] * vinf[0] + vinf[1] * vinf[1] + vinf[2] * vinf[2]);
  for (int i = 0; i < 3; ++i)
    e.map[3 + i] = arrival[3 + i] + GiNaC::cos(d) * vinf[i] +
                   GiNaC::sin(d) * (GiNaC::cos(f) * vn * w[i] + GiNaC::sin(f) * vw[i]) / wn;
  if (c.contains("min_periapsis_radius_km")) {
    // r_p = mu/v_inf^2 (1/sin(delta/2) - 1) >= r_min, written without the 1/sin singularity at
    // delta = 0 and for either sign of delta: sin^2(delta/2) (1 + r_min v_inf^2/mu)^2 - 1 <= 0.
    const std::string rmin = "rmin_" + e.id;
    p.parameters.push_back({rmin, "lowest periapsis radius of the swing-by at " + e.id, U.length_name,
                            c.at("min_periapsis_radius_km").get<double>() / U.length_km});
    const ex k = 1 + S.get(rmin) * vn * vn / S.get(mu_name);
    e.c.push_back((1 - GiNaC::cos(d)) / 2 * k * k - 1);
    e.c_names.push_back("sin(delta/2)^2 (1 + rmin v_inf^2/mu)^2 - 1 (<= 0: periapsis radius >= rmin)");
    e.c_inequality.push_back(true);
  }
}

// An orbit or conditions on the state fix fewer states than a point: they are formulated with the
// departure epoch and the initial mass known.
void require_known_start(const Problem& p, const std::string& where, const std::string& what) {
  if (p.free_departure) throw std::invalid_argument(where + ": " + what + " needs a fixed departure epoch");
  if (p.free_initial_mass) throw std::invalid_argument(where + ": " + what + " needs a known initial mass");
}

// The state on a target orbit at tf, the position on it free: the orbit's rows (orbit_rows), none
// of which fixes a state, so their multipliers are unknowns of the shooting. The orbit does not
// move: dpsi/dtf = 0.
EndpointConstraint orbit_insertion(Problem& p, EndpointConstraint k) {
  const std::string where = "constraint '" + k.id + "'";
  if (k.at != "tf") throw std::invalid_argument(where + ": an orbit insertion is at tf");
  if (k.target.at("kind") != "orbital_elements")
    throw std::invalid_argument(where + ": an orbit insertion needs a target of kind orbital_elements");
  require_known_start(p, where, "an orbit target");
  const OrbitRows rows = orbit_rows(p, k.id, k.target);
  k.psi = rows.psi;
  k.psi_names = rows.names;
  k.psi_inequality.assign(rows.psi.size(), false);
  k.psi_t.assign(rows.psi.size(), 0);
  k.must_be_positive = rows.must_be_positive;
  k.multipliers_unknown = true;
  return k;
}

// Whether the rows' gradients in the states are independent at a generic state (random states
// and parameters): -1, or the first row that depends on those before it.
int dependent_row(Problem& p, const std::vector<ex>& psi) {
  std::vector<GiNaC::symbol> states;
  for (const auto& s : p.states) states.push_back(GiNaC::ex_to<GiNaC::symbol>(p.symbols.get(s.name)));
  GiNaC::exmap at;
  double v = 0.61;
  for (const auto& [name, s] : p.symbols.symtab()) at[s] = (v = std::fmod(v * 7.31 + 0.37, 1.0)) + 0.5;
  std::vector<std::vector<double>> basis;
  for (std::size_t j = 0; j < psi.size(); ++j) {
    std::vector<double> g;
    for (const auto& s : states) g.push_back(GiNaC::ex_to<GiNaC::numeric>(psi[j].diff(s).subs(at).evalf()).to_double());
    double norm0 = 0;
    for (const double a : g) norm0 += a * a;
    for (const auto& b : basis) {  // Gram-Schmidt against the unit rows before
      double d = 0;
      for (std::size_t i = 0; i < g.size(); ++i) d += g[i] * b[i];
      for (std::size_t i = 0; i < g.size(); ++i) g[i] -= d * b[i];
    }
    double norm = 0;
    for (const double a : g) norm += a * a;
    if (!(norm > 1e-18 * norm0) || norm0 == 0) return static_cast<int>(j);
    for (double& a : g) a /= std::sqrt(norm);
    basis.push_back(g);
  }
  return -1;
}

// Conditions written as equations of the final state (spec target "expressions", one row each,
// in normalized units: (f(x) - value) / its unit). Like an orbit they fix no state, so their
// multipliers are unknowns of the shooting; they do not depend on time.
EndpointConstraint state_conditions(Problem& p, EndpointConstraint k) {
  auto& S = p.symbols;
  const Units& U = p.units;
  const std::string where = "constraint '" + k.id + "'";
  if (k.at != "tf") throw std::invalid_argument(where + ": conditions on the state are at tf");
  if (k.target.at("kind") != "expressions")
    throw std::invalid_argument(where + ": state conditions need a target of kind expressions");
  require_known_start(p, where, "a condition on the state");
  symbolic::SymbolTable vars = spec::state_condition_symbols();
  const std::vector<ex> r = {S.get("rx"), S.get("ry"), S.get("rz")}, v = {S.get("vx"), S.get("vy"), S.get("vz")};
  const std::vector<ex> h = {r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0]};
  const auto norm = [](const std::vector<ex>& a) { return GiNaC::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); };
  // f is a power law in the units (expression_dimension checks it), so f of the normalized state
  // is f of the state in km, s and kg divided by its unit in normalized units.
  GiNaC::exmap to_model = {{vars.get("x"), r[0]},        {vars.get("y"), r[1]},    {vars.get("z"), r[2]},
                           {vars.get("r"), norm(r)},     {vars.get("vx"), v[0]},   {vars.get("vy"), v[1]},
                           {vars.get("vz"), v[2]},       {vars.get("v"), norm(v)}, {vars.get("hx"), h[0]},
                           {vars.get("hy"), h[1]},       {vars.get("hz"), h[2]},   {vars.get("h"), norm(h)},
                           {vars.get("mu"), S.get("mu")}};
  if (p.has_state("m")) to_model[vars.get("m")] = S.get("m");
  const json& conditions = k.target.at("conditions");
  if (!conditions.is_array() || conditions.empty())
    throw std::invalid_argument(where + ": target/conditions must list at least one condition");
  if (conditions.size() > p.states.size())
    throw std::invalid_argument(where + ": " + std::to_string(conditions.size()) + " conditions on " +
                                std::to_string(p.states.size()) + " states: at most one per state");
  for (std::size_t j = 0; j < conditions.size(); ++j) {
    const std::string at = where + ": target/conditions/" + std::to_string(j);
    const json& c = conditions[j];
    const std::string text = c.at("expression").get<std::string>();
    const ex f = vars.parse(text, at + "/expression");
    if (f.has(vars.get("m")) && !p.has_state("m"))
      throw std::invalid_argument(at + "/expression: '" + text + "' uses m, and this spacecraft has no mass state");
    const spec::UnitDimension d = spec::expression_dimension(f, vars, at + "/expression");
    if (c.at("unit").get<std::string>() != spec::unit_text(d))
      throw std::invalid_argument(at + "/unit: '" + c.at("unit").get<std::string>() + "', but '" + text + "' is in " +
                                  spec::unit_text(d));
    const double unit = std::pow(U.length_km, d.length) * std::pow(U.time_s, d.time) * std::pow(U.mass_kg, d.mass);
    const double value = c.at("equals").get<double>();
    spec::require_in_range(value, value / unit,
                           at + "/equals: " + io::short_number(value) + " " + spec::unit_text(d) +
                               " in the normalized units (length " + io::short_number(U.length_km) + " km, time " +
                               io::short_number(U.time_s) + " s, mass " + io::short_number(U.mass_kg) + " kg)");
    k.psi.push_back(f.subs(to_model) - value / unit);
    k.psi_names.push_back(text + " = " + io::short_number(value) + " " + spec::unit_text(d));
  }
  if (const int j = dependent_row(p, k.psi); j >= 0)
    throw std::invalid_argument(where + ": target/conditions/" + std::to_string(j) + " ('" + k.psi_names[j] +
                                "') is not independent of the conditions before it");
  k.psi_inequality.assign(k.psi.size(), false);
  k.psi_t.assign(k.psi.size(), 0);
  k.multipliers_unknown = true;
  return k;
}

// The departure from an orbit given by all its elements, the position on it free: x(t0) =
// X(theta) with the anomaly theta a free parameter of psi, found by stationarity (lambda(t0) is
// orthogonal to the orbit's tangent dX/dtheta); the initial mass is known.
EndpointConstraint orbit_departure(Problem& p, EndpointConstraint k) {
  const std::string where = "constraint '" + k.id + "'";
  require_known_start(p, where, "a departure orbit");
  const std::string theta = "theta_" + k.id, node = "node_" + k.id, argp = "argp_" + k.id;
  const json free = k.target.value("free", json::array());
  const auto angle = [&](const std::string& name, const char* element) {
    return std::find(free.begin(), free.end(), element) != free.end() ? ex(p.symbols.get(name)) : ex(0);
  };
  const std::vector<ex> x =
      orbit_point(p, k.id, k.target, {p.symbols.get(theta), angle(node, "raan"), angle(argp, "argp")});
  for (std::size_t j = 0; j < kPositionVelocity.size(); ++j) {
    const std::string& n = kPositionVelocity[j];
    k.psi.push_back(p.symbols.get(n) - x[j]);
    k.psi_names.push_back(n + " - X_" + n + "(" + theta + ")");
    k.fixed_states.push_back(n);
  }
  if (p.has_state("m")) {
    k.psi.push_back(p.symbols.get("m") - 1);
    k.psi_names.push_back("m - 1");
    k.fixed_states.push_back("m");
  }
  k.psi_inequality.assign(k.psi.size(), false);
  k.psi_t.assign(k.psi.size(), 0);
  k.free_parameters.push_back({theta,
                               "true anomaly on the departure orbit " + k.id +
                                   " (rad; from the node where the "
                                   "orbit is circular, from the x axis where it is also equatorial)",
                               0, 2 * M_PI});
  // The node and the argument of periapsis the departure leaves free (orbit_point turns P and Q by them).
  if (!angle(node, "raan").is_zero())
    k.free_parameters.push_back({node, "ascending node of the departure orbit " + k.id + " (rad)", 0, 2 * M_PI});
  if (!angle(argp, "argp").is_zero())
    k.free_parameters.push_back({argp, "argument of periapsis of the departure orbit " + k.id + " (rad)", 0, 2 * M_PI});
  return k;
}

// An orbit on the way: at a free epoch inside the window the arriving state x- is on the orbit
// (its rows, orbit_rows, written in x-), the position on it free; the state goes on unchanged.
InteriorEvent orbit_on_the_way(Problem& p, InteriorEvent e, const std::vector<ex>& xm) {
  const std::string where = "constraint '" + e.id + "'";
  if (e.target.at("kind") != "orbital_elements")
    throw std::invalid_argument(where + ": an orbit on the way needs a target of kind orbital_elements");
  if (e.target.contains("free"))
    throw std::invalid_argument(where +
                                ": target/free is for a departure orbit (a target's unstated elements are free)");
  require_known_start(p, where, "an orbit on the way");
  GiNaC::exmap arriving;
  for (std::size_t j = 0; j < p.states.size(); ++j) arriving[p.symbols.get(p.states[j].name)] = xm[j];
  const OrbitRows rows = orbit_rows(p, e.id, e.target);
  for (std::size_t j = 0; j < rows.psi.size(); ++j) {
    e.c.push_back(rows.psi[j].subs(arriving));
    e.c_names.push_back(rows.names[j]);
    e.c_inequality.push_back(false);
  }
  for (const auto& side : rows.must_be_positive)
    e.must_be_positive.push_back({side.expression.subs(arriving), side.meaning});
  window_rows(p, e);
  e.map = xm;
  return e;
}

}  // namespace

// An interior event: conditions c on the arriving state and the map g to the leaving state.
InteriorEvent interior_event(Problem& p, const json& c) {
  auto& S = p.symbols;
  InteriorEvent e = event_window(p, c);
  const std::string where = "constraint '" + e.id + "'";
  const double drop = c.value("mass_drop_kg", 0.0) / p.units.mass_kg;
  if ((e.duration > 0 || drop > 0) && e.kind != "rendezvous")
    throw std::invalid_argument(where + ": only a rendezvous has a stay or a mass drop");
  if (drop > 0 && !p.has_state("m")) throw std::invalid_argument(where + ": a mass drop needs a mass state");

  std::vector<ex> xm;
  for (const auto& s : p.states) xm.push_back(S.get(names::before(s.name, e.id)));
  for (const auto& s : p.states) S.get(names::after(s.name, e.id));
  S.get(names::event_time(e.id));
  if (e.kind == "orbit_insertion") return orbit_on_the_way(p, std::move(e), xm);
  std::vector<ex> rates;
  const std::vector<ex> arrival = target_state(p, e.id, e.target, e.id, true, rates);
  arrival_conditions(p, c, e, xm, arrival);
  e.map = xm;  // continuous unless changed below
  if (e.kind == "rendezvous" && e.duration > 0) {
    // After the stay the spacecraft leaves from the target's state at t_<id> + stay.
    const std::string departure_label = names::departure_label(e.id);
    const std::vector<ex> departure = target_state(p, departure_label, e.target, departure_label, true, rates);
    for (std::size_t j = 0; j < 6; ++j) e.map[j] = departure[j];
  }
  if (drop > 0) {
    const std::string name = "drop_" + e.id;
    p.parameters.push_back({name, "mass left at " + e.id, "initial mass", drop});
    const std::size_t m = 6;
    e.map[m] = xm[m] - S.get(name);
  }
  if (e.kind == "gravity_assist") gravity_assist(p, c, e, xm, arrival);
  return e;
}

void refuse_free_node_by_symmetry(const json& spec) {
  const json* departure = nullptr;
  bool symmetric = true;
  for (const auto& q : spec.at("dynamics").value("perturbations", json::array()))
    symmetric = symmetric && find_perturbation(q.at("kind").get<std::string>()) &&
                find_perturbation(q.at("kind").get<std::string>())->axially_symmetric;
  for (const auto& c : spec.at("constraints")) {
    const json& t = c.at("target");
    const json free = t.value("free", json::array());
    if (c.at("at") == "t0" && std::find(free.begin(), free.end(), "raan") != free.end()) {
      departure = &c;
    } else if (c.at("kind") == "orbit_insertion") {
      symmetric = symmetric && !t.contains("raan_deg");
    } else if (c.at("kind") == "state_conditions") {
      static const std::regex turning(R"(\b(x|y|vx|vy|hx|hy)\b)");
      for (const auto& condition : t.at("conditions"))
        symmetric = symmetric && !std::regex_search(condition.at("expression").get<std::string>(), turning);
    } else {
      symmetric = false;  // a state, a body or an event fixes a direction in the plane
    }
  }
  if (departure && symmetric)
    throw std::invalid_argument("constraint '" + departure->at("id").get<std::string>() +
                                "': target/free lists the node, but nothing else changes when turned about the z axis: "
                                "every node gives the same transfer, turned; state one (e.g. raan_deg 0)");
}

// psi(t_k, x(t_k), p) of an endpoint constraint: the state meets the target (a flyby in
// position only), a flyby's bounded relative speed, and the mass where it is known.
EndpointConstraint endpoint_constraint(Problem& p, const json& c) {
  auto& S = p.symbols;
  EndpointConstraint k;
  k.id = c.at("id").get<std::string>();
  k.kind = c.at("kind").get<std::string>();
  k.at = c.at("at").get<std::string>();
  k.target = c.at("target");
  const std::string where = "constraint '" + k.id + "'";
  if (k.kind == "orbit_insertion" && k.target.contains("free"))
    throw std::invalid_argument(where +
                                ": target/free is for a departure orbit (a target's unstated elements are free)");
  if (k.kind == "orbit_insertion") return orbit_insertion(p, std::move(k));
  if (k.kind == "state_conditions") return state_conditions(p, std::move(k));
  if (k.kind == "initial_state" && k.target.at("kind") == "orbital_elements") {
    if (k.at != "t0") throw std::invalid_argument(where + ": an initial state must be at t0");
    return orbit_departure(p, std::move(k));
  }
  if (k.kind != "initial_state" && k.kind != "rendezvous" && !(k.kind == "flyby" && k.at == "tf"))
    throw std::invalid_argument(where + ": a " + k.kind + " is an interior event, not at " + k.at);
  if (k.target.at("kind") == "coasting" && p.free_departure)
    throw std::invalid_argument(where + ": a coasting target needs a fixed departure epoch");
  // The event moves when its own time is free, or with a sliding departure (tf = t0 + tof).
  const bool moving = (k.at == "tf" && p.free_final_time) || p.free_departure;
  std::vector<ex> rates;
  const std::vector<ex> target = target_state(p, k.id, k.target, k.at, moving, rates);
  const std::size_t matched = k.kind == "flyby" ? 3 : 6;  // a flyby matches position only
  for (std::size_t j = 0; j < matched; ++j) {
    const std::string& n = kPositionVelocity[j];
    k.psi.push_back(S.get(n) - target[j]);
    k.psi_names.push_back(n + " - " + to_text(target[j]));
    k.psi_inequality.push_back(false);
    k.fixed_states.push_back(n);
    k.psi_t.push_back(-rates[j]);
  }
  if (c.contains("max_relative_speed_km_s")) {
    if (k.kind != "flyby") throw std::invalid_argument(where + ": only a flyby has a relative speed to bound");
    std::vector<ex> relative(3);
    for (int i = 0; i < 3; ++i) relative[i] = S.get(kPositionVelocity[3 + i]) - target[3 + i];
    ex rate = 0;
    for (int i = 0; i < 3; ++i) rate += 2 * relative[i] * -rates[3 + i];
    k.psi.push_back(speed_bound(p, k.id, relative, c.at("max_relative_speed_km_s").get<double>()));
    k.psi_names.push_back("|v - v_" + k.id + "|^2 - vmax_" + k.id + "^2 (<= 0)");
    k.psi_inequality.push_back(true);
    k.psi_t.push_back(rate);
  }
  const auto fix_mass = [&](const ex& value, const std::string& name) {
    k.psi.push_back(S.get("m") - value);
    k.psi_names.push_back(name);
    k.psi_inequality.push_back(false);
    k.fixed_states.push_back("m");
    k.psi_t.push_back(0);
  };
  if (k.kind == "initial_state") {
    if (k.at != "t0") throw std::invalid_argument(where + ": an initial state must be at t0");
    if (k.target.at("kind") == "coasting") throw std::invalid_argument(where + ": a departure cannot coast");
    // The spacecraft's initial mass is known: mass is fixed at t0 as well.
    if (p.has_state("m") && !p.free_initial_mass) fix_mass(1, "m - 1");
  } else if (k.at != "tf") {
    throw std::invalid_argument(where + ": rendezvous is supported at tf only");
  } else if (p.free_initial_mass) {
    // Minimum initial mass: the final (dry + payload) mass is given.
    fix_mass(p.final_mass, "m - m_final");
  }
  return k;
}

}  // namespace helios::pmp

#include "helios/pmp/model.hpp"

#include <cmath>
#include <stdexcept>

#include "helios/astro/constants.hpp"
#include "helios/spec/parse.hpp"
#include "helios/spec/units.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using io::json;
using symbolic::to_text;

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

std::string costate_name(const std::string& state) {
  return "l_" + state;
}
std::string at_event(const std::string& name, const std::string& event) {
  return name + "_" + event;
}
std::string before_event(const std::string& name, const std::string& event) {
  return name + "_" + event + "_m";
}
std::string after_event(const std::string& name, const std::string& event) {
  return name + "_" + event + "_p";
}
std::string event_time_name(const std::string& event) {
  return "t_" + event;
}

bool Problem::has_state(const std::string& name) const {
  for (const auto& s : states)
    if (s.name == name) return true;
  return false;
}

namespace {

// Two-body gravity plus the J2 zonal term (z along the central body's pole):
// a_J2 = -3/2 J2 mu R^2 / r^5 [x (1 - 5 z^2/r^2), y (1 - 5 z^2/r^2), z (3 - 5 z^2/r^2)].
std::vector<ex> gravity(const std::vector<ex>& r, const ex& mu, const ex* j2, const ex* radius) {
  const ex r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  const ex r3 = GiNaC::pow(r2, GiNaC::numeric(3, 2));
  std::vector<ex> g = {-mu * r[0] / r3, -mu * r[1] / r3, -mu * r[2] / r3};
  if (j2) {
    const ex k = -GiNaC::numeric(3, 2) * (*j2) * mu * (*radius) * (*radius) / GiNaC::pow(r2, GiNaC::numeric(5, 2));
    const ex zz = 5 * r[2] * r[2] / r2;
    g[0] += k * r[0] * (1 - zz);
    g[1] += k * r[1] * (1 - zz);
    g[2] += k * r[2] * (3 - zz);
  }
  return g;
}

// A user-written acceleration (spec units: km, km/s, kg, s) in normalized units.
std::vector<ex> user_acceleration(const json& pert, Problem& p, const ex& mass) {
  symbolic::SymbolTable vars;
  for (const char* v : spec::kAccelerationVariables) vars.get(v);
  const Units& U = p.units;
  auto& S = p.symbols;
  const ex rx = S.get("rx"), ry = S.get("ry"), rz = S.get("rz");
  GiNaC::exmap to_model = {
      {vars.get("x"), rx * U.length_km},
      {vars.get("y"), ry * U.length_km},
      {vars.get("z"), rz * U.length_km},
      {vars.get("r"), GiNaC::sqrt(rx * rx + ry * ry + rz * rz) * U.length_km},
      {vars.get("vx"), S.get("vx") * U.speed_km_s()},
      {vars.get("vy"), S.get("vy") * U.speed_km_s()},
      {vars.get("vz"), S.get("vz") * U.speed_km_s()},
      {vars.get("m"), mass * U.mass_kg},
      {vars.get("t"), S.get("t") * U.time_s},
  };
  // The spec unit of accelerations is mm/s^2 = 1e-6 km/s^2.
  const double to_km_s2 = spec::to_spec_unit(spec::Dimension::Acceleration, pert.at("unit")) * 1e-6;
  const double scale = to_km_s2 * U.time_s * U.time_s / U.length_km;
  std::vector<ex> a;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string where =
        "field /dynamics/perturbations (" + pert.at("name").get<std::string>() + ")/components/" + std::to_string(i);
    a.push_back(vars.parse(pert.at("components")[i].get<std::string>(), where).subs(to_model) * scale);
  }
  return a;
}

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
    const std::string name = prefix + "_" + n;
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
        const std::string rname = name + "_rate";
        p.parameters.push_back({rname, "time derivative of " + name + " (of the ephemeris model)", unit + "/" + T, 0.0,
                                "ephemeris_rate:" + body + ":" + event});
        rate = S.get(rname);
      }
    } else {
      const std::string start = name + "_0";
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

// The conditions c on the arriving state x-: it meets the target (a flyby or swing-by in
// position only), a flyby's bounded relative speed, and the window as two bounds on the epoch
// (two-pass): window_lo - t <= 0 and t - window_hi <= 0.
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
  const ex t = p.symbols.get(event_time_name(e.id));
  e.c.push_back(e.window_lo - t);
  e.c_names.push_back("window start - " + event_time_name(e.id) + " (<= 0: not before the window)");
  e.c_inequality.push_back(true);
  e.c.push_back(t - e.window_hi);
  e.c_names.push_back(event_time_name(e.id) + " - window end (<= 0: not after the window)");
  e.c_inequality.push_back(true);
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

// An interior event: conditions c on the arriving state and the map g to the leaving state.
InteriorEvent interior_event(Problem& p, const json& c) {
  auto& S = p.symbols;
  InteriorEvent e = event_window(p, c);
  const std::string where = "constraint '" + e.id + "'";
  const double drop = c.value("mass_drop_kg", 0.0) / p.units.mass_kg;
  if ((e.duration > 0 || drop > 0) && e.kind != "rendezvous")
    throw std::invalid_argument(where + ": only a rendezvous has a stay or a mass drop");
  if (drop > 0 && !p.has_state("m")) throw std::invalid_argument(where + ": a mass drop needs a mass state");

  std::vector<ex> rates;
  const std::vector<ex> arrival = target_state(p, e.id, e.target, e.id, true, rates);
  std::vector<ex> xm;
  for (const auto& s : p.states) xm.push_back(S.get(before_event(s.name, e.id)));
  for (const auto& s : p.states) S.get(after_event(s.name, e.id));
  S.get(event_time_name(e.id));
  arrival_conditions(p, c, e, xm, arrival);
  e.map = xm;  // continuous unless changed below
  if (e.kind == "rendezvous" && e.duration > 0) {
    // After the stay the spacecraft leaves from the target's state at t_<id> + stay.
    const std::vector<ex> departure = target_state(p, e.id + "_dep", e.target, e.id + "_dep", true, rates);
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

// The problem's name, its dynamics model (with its perturbations) and its objective and units;
// returns whether J2 is one of the perturbations.
bool describe(Problem& p, const json& spec) {
  p.id = spec.at("problem").at("id").get<std::string>();
  const json& dyn = spec.at("dynamics");
  p.propulsion = dyn.at("propulsion").get<std::string>();
  bool j2 = false;
  for (const auto& q : dyn.value("perturbations", json::array())) {
    if (q.at("kind") == "j2") {
      j2 = true;
      p.perturbations.push_back("j2");
    } else {
      p.perturbations.push_back(q.at("name").get<std::string>());
    }
  }
  p.dynamics_model = dyn.at("model").get<std::string>() + (j2 ? "_j2" : "") + "_" +
                     dyn.at("coordinates").get<std::string>() + "_" + p.propulsion;
  p.objective = spec.at("objective").at("kind").get<std::string>();
  p.units = units_for(spec.at("central_body"));
  return j2;
}

// The states, controls and parameters: position and velocity in the central body's field, and
// a sail's normal, or a thruster's throttle and direction with the mass it burns.
void spacecraft(Problem& p, const json& spec, bool j2) {
  const json& central = spec.at("central_body");
  const json& sc = spec.at("spacecraft");
  const bool sail = p.propulsion == "solar_sail";
  // Minimum initial mass: m0 is unknown and the final (dry + payload) mass is given, so it sets the
  // mass scale; otherwise m0 does.
  p.free_initial_mass = p.objective == "minimum_initial_mass";
  const std::string mass_field = p.free_initial_mass ? "final_mass_kg" : "initial_mass_kg";
  if (!sail) {
    if (!sc.contains(mass_field))
      throw std::invalid_argument("field /spacecraft/" + mass_field + " is missing (objective " + p.objective + ")");
    p.units.mass_kg = sc.at(mass_field).get<double>();
  }
  const std::string mass_unit = p.free_initial_mass ? "final mass" : "initial mass";
  const Units& U = p.units;
  const double mu =
      central.at("mu_km3_s2").get<double>() * U.time_s * U.time_s / (U.length_km * U.length_km * U.length_km);
  const std::string L = U.length_name, T = U.time_name;

  p.states = {{"rx", "position x", L},           {"ry", "position y", L},           {"rz", "position z", L},
              {"vx", "velocity x", L + "/" + T}, {"vy", "velocity y", L + "/" + T}, {"vz", "velocity z", L + "/" + T}};
  p.parameters = {{"mu", "gravitational parameter of the central body", L + "^3/" + T + "^2", mu}};
  if (j2) {
    p.parameters.push_back({"J2", "J2 zonal coefficient of the central body", "1", central.at("j2").get<double>()});
    p.parameters.push_back(
        {"Req", "equatorial radius of the central body", L, central.at("radius_km").get<double>() / U.length_km});
  }
  if (sail) {
    const double ac =
        sc.at("sail_characteristic_acceleration_mm_s2").get<double>() * 1e-6 * U.time_s * U.time_s / U.length_km;
    const double ref = sc.at("sail_reference_distance_AU").get<double>() * helios::astro::AU_KM / U.length_km;
    p.controls = {{"nx", "sail normal x (unit vector, n.r >= 0)", "sail_normal"},
                  {"ny", "sail normal y (unit vector, n.r >= 0)", "sail_normal"},
                  {"nz", "sail normal z (unit vector, n.r >= 0)", "sail_normal"}};
    p.parameters.push_back({"ac", "characteristic acceleration of the sail", L + "/" + T + "^2", ac});
    p.parameters.push_back({"rref", "distance at which the characteristic acceleration holds", L, ref});
  } else {
    const double thrust = sc.at("thrust_N").get<double>() / U.force_N();
    const double exhaust = sc.at("isp_s").get<double>() * helios::astro::G0_M_S2 * 1e-3 / U.speed_km_s();
    if (!(thrust > 0) || !(exhaust > 0)) throw std::domain_error("field /spacecraft: thrust and Isp must be positive");
    p.states.push_back({"m", "mass", mass_unit});
    p.controls = {{"u", "throttle T/Tmax in [0, 1]", "throttle"},
                  {"ax", "thrust direction x (unit vector)", "direction"},
                  {"ay", "thrust direction y (unit vector)", "direction"},
                  {"az", "thrust direction z (unit vector)", "direction"}};
    p.parameters.push_back({"Tmax", "maximum thrust", mass_unit + "*" + L + "/" + T + "^2", thrust});
    p.parameters.push_back({"c", "exhaust velocity Isp*g0", L + "/" + T, exhaust});
  }
}

// The symbols of the model, in a fixed order: GiNaC orders terms by the symbols' creation, so
// this order fixes the text of every expression derived from them.
void register_symbols(Problem& p) {
  auto& S = p.symbols;
  for (const auto& s : p.states) {
    S.get(s.name);
    S.get(costate_name(s.name));
  }
  for (const auto& c : p.controls) S.get(c.name);
  for (const auto& q : p.parameters) S.get(q.name);
  S.get("lambda0");
  S.get("t");
  S.get("eps");
}

// f(x, u): gravity (with J2), the sail's or the thruster's acceleration, the user's
// accelerations, and the thruster's mass flow; the coast dynamics for coasting targets.
void dynamics(Problem& p, const json& perturbations, bool j2) {
  auto& S = p.symbols;
  const bool sail = p.propulsion == "solar_sail";
  const std::vector<ex> r = {S.get("rx"), S.get("ry"), S.get("rz")}, v = {S.get("vx"), S.get("vy"), S.get("vz")};
  const ex MU = S.get("mu");
  ex J2sym, Rsym;
  if (j2) {
    J2sym = S.get("J2");
    Rsym = S.get("Req");
  }
  const std::vector<ex> g = gravity(r, MU, j2 ? &J2sym : nullptr, j2 ? &Rsym : nullptr);
  p.coast_f = {v[0], v[1], v[2], g[0], g[1], g[2]};

  std::vector<ex> accel = g;
  ex mass = 1;
  if (sail) {
    // Ideal flat sail: a = ac (rref/r)^2 (n.rhat)^2 n, n the unit normal pointing away from the Sun.
    const ex rn = GiNaC::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const std::vector<ex> n = {S.get("nx"), S.get("ny"), S.get("nz")};
    const ex cos_cone = (n[0] * r[0] + n[1] * r[1] + n[2] * r[2]) / rn;
    const ex k = S.get("ac") * GiNaC::pow(S.get("rref") / rn, 2);
    for (int i = 0; i < 3; ++i) accel[i] += k * GiNaC::pow(cos_cone, 2) * n[i];
    p.sail = {k, {r[0] / rn, r[1] / rn, r[2] / rn}, {"vx", "vy", "vz"}};
  } else {
    mass = S.get("m");
    const ex u = S.get("u"), TM = S.get("Tmax");
    const std::vector<ex> a = {S.get("ax"), S.get("ay"), S.get("az")};
    for (int i = 0; i < 3; ++i) accel[i] += TM * u * a[i] / mass;
  }
  for (const auto& q : perturbations)
    if (q.at("kind") == "acceleration") {
      const std::vector<ex> a = user_acceleration(q, p, mass);
      for (int i = 0; i < 3; ++i) accel[i] += a[i];
    }
  p.f = {v[0], v[1], v[2], accel[0], accel[1], accel[2]};
  if (!sail) p.f.push_back(-S.get("Tmax") * S.get("u") / S.get("c"));
}

// The running cost L (no endpoint cost).
void objective(Problem& p) {
  auto& S = p.symbols;
  if (p.objective == "minimum_fuel" || p.objective == "minimum_initial_mass") {
    if (p.propulsion == "solar_sail")
      throw std::invalid_argument("field /objective/kind: a solar sail uses no fuel; minimize the time instead");
    // Fuel (mass flow) with the quadratic homotopy term: eps = 1 is an energy-like problem,
    // eps = 0 the bang-bang fuel-optimal one (Bertrand & Epenoy; Jiang, Baoyin & Li 2012).
    // With m(tf) fixed, the fuel m0 - m(tf) is m0 up to a constant: the same running cost
    // minimizes the initial mass.
    const ex TM = S.get("Tmax"), C = S.get("c"), u = S.get("u"), eps = S.get("eps");
    p.running_cost = TM / C * (u - eps * u * (1 - u));
  } else if (p.objective == "minimum_time") {
    p.running_cost = 1;
  } else {
    throw std::invalid_argument("field /objective/kind: " + p.objective + " is not supported");
  }
  p.endpoint_cost = 0;
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

}  // namespace

Problem build_problem(const json& spec) {
  Problem p;
  const bool j2 = describe(p, spec);
  spacecraft(p, spec, j2);
  register_symbols(p);
  dynamics(p, spec.at("dynamics").value("perturbations", json::array()), j2);
  objective(p);
  times(p, spec.at("time"));
  for (const auto& c : spec.at("constraints")) {
    if (c.at("at") == "interior")
      p.events.push_back(interior_event(p, c));
    else
      p.constraints.push_back(endpoint_constraint(p, c));
  }
  for (std::size_t i = 1; i < p.events.size(); ++i)
    if (p.events[i].window_lo < p.events[i - 1].window_lo)
      throw std::invalid_argument("constraint '" + p.events[i].id + "': interior events must be listed in time order");
  return p;
}

}  // namespace helios::pmp

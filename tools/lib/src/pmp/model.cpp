// The problem of a spec in the solver's normalized units: the spacecraft's states, controls
// and parameters, the dynamics f(x, u), the running cost and the times; the constraints are
// built in constraints.cpp.
#include "helios/pmp/model.hpp"

#include <cmath>
#include <stdexcept>

#include "constraints.hpp"
#include "helios/astro/constants.hpp"
#include "helios/spec/parse.hpp"
#include "helios/spec/units.hpp"
#include "helios/symbolic/expr.hpp"

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
    // The schema asks for positive values; a zero here is an underflow in normalized units.
    if (!(thrust > 0) || !(exhaust > 0))
      throw std::domain_error("field /spacecraft: the " +
                              std::string(thrust > 0 ? "exhaust velocity" : "maximum thrust") +
                              " is 0 in normalized units: the spacecraft's magnitudes (thrust, Isp, mass) are beyond "
                              "the range of double precision");
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
    S.get(names::costate(s.name));
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
  check_magnitudes(p);
  return p;
}

}  // namespace helios::pmp

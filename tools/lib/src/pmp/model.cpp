#include "helios/pmp/model.hpp"

#include <cmath>
#include <stdexcept>

#include "helios/astro/constants.hpp"

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
    const double radius = name == "Earth" ? R_EARTH_KM : name == "Mars" ? R_MARS_KM : 0.0;
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

Problem build_problem(const json& spec) {
  Problem p;
  p.id = spec.at("problem").at("id").get<std::string>();
  const json& dyn = spec.at("dynamics");
  p.dynamics_model = dyn.at("model").get<std::string>() + "_" + dyn.at("coordinates").get<std::string>() + "_" +
                     dyn.at("propulsion").get<std::string>();
  if (p.dynamics_model != "two_body_cartesian_low_thrust")
    throw std::invalid_argument("field /dynamics: model " + p.dynamics_model +
                                " is not supported by the builtin engine");
  p.objective = spec.at("objective").at("kind").get<std::string>();
  p.units = units_for(spec.at("central_body"));
  const Units& U = p.units;

  const json& sc = spec.at("spacecraft");
  const double m0 = sc.at("initial_mass_kg").get<double>();
  p.units.mass_kg = m0;
  const double thrust = sc.at("thrust_N").get<double>() / p.units.force_N();
  const double exhaust = sc.at("isp_s").get<double>() * helios::astro::G0_M_S2 * 1e-3 / U.speed_km_s();
  const double mu = spec.at("central_body").at("mu_km3_s2").get<double>() * U.time_s * U.time_s /
                    (U.length_km * U.length_km * U.length_km);
  if (!(thrust > 0) || !(exhaust > 0)) throw std::domain_error("field /spacecraft: thrust and Isp must be positive");

  const std::string L = U.length_name, T = U.time_name;
  p.states = {{"rx", "position x", L},           {"ry", "position y", L},           {"rz", "position z", L},
              {"vx", "velocity x", L + "/" + T}, {"vy", "velocity y", L + "/" + T}, {"vz", "velocity z", L + "/" + T},
              {"m", "mass", "initial mass"}};
  p.controls = {{"u", "throttle T/Tmax in [0, 1]", "throttle"},
                {"ax", "thrust direction x (unit vector)", "direction"},
                {"ay", "thrust direction y (unit vector)", "direction"},
                {"az", "thrust direction z (unit vector)", "direction"}};
  p.parameters = {{"mu", "gravitational parameter of the central body", L + "^3/" + T + "^2", mu},
                  {"Tmax", "maximum thrust", "initial mass*" + L + "/" + T + "^2", thrust},
                  {"c", "exhaust velocity Isp*g0", L + "/" + T, exhaust}};

  auto& S = p.symbols;
  for (const auto& s : p.states) {
    S.get(s.name);
    S.get(costate_name(s.name));
  }
  for (const auto& c : p.controls) S.get(c.name);
  for (const auto& q : p.parameters) S.get(q.name);
  const ex rx = S.get("rx"), ry = S.get("ry"), rz = S.get("rz"), vx = S.get("vx"), vy = S.get("vy"), vz = S.get("vz"),
           m = S.get("m"), u = S.get("u"), ax = S.get("ax"), ay = S.get("ay"), az = S.get("az"), MU = S.get("mu"),
           TM = S.get("Tmax"), C = S.get("c"), eps = S.get("eps");
  S.get("lambda0");

  // Two-body dynamics with thrust u*Tmax along the unit vector a; mass flow Tmax*u/c.
  const ex r3 = GiNaC::pow(rx * rx + ry * ry + rz * rz, GiNaC::numeric(3, 2));
  p.f = {vx,
         vy,
         vz,
         -MU * rx / r3 + TM * u * ax / m,
         -MU * ry / r3 + TM * u * ay / m,
         -MU * rz / r3 + TM * u * az / m,
         -TM * u / C};
  if (p.objective != "minimum_fuel")
    throw std::invalid_argument("field /objective/kind: " + p.objective + " is not supported");
  // Fuel (mass flow) with the quadratic homotopy term: eps = 1 is an energy-like problem,
  // eps = 0 the bang-bang fuel-optimal one (Bertrand & Epenoy; Jiang, Baoyin & Li 2012).
  p.running_cost = TM / C * (u - eps * u * (1 - u));
  p.endpoint_cost = 0;

  const json& time = spec.at("time");
  p.t0 = 0;
  p.tf = time.at("tof_days").get<double>() * helios::astro::DAY_S / U.time_s;
  p.initial_mass = 1;
  if (time.contains("epoch_mjd2000")) {
    p.epoch_mjd2000 = time.at("epoch_mjd2000").get<double>();
    p.has_epoch = true;
  }

  const std::vector<std::string> pos = {"rx", "ry", "rz"}, vel = {"vx", "vy", "vz"};
  for (const auto& c : spec.at("constraints")) {
    EndpointConstraint k;
    k.id = c.at("id").get<std::string>();
    k.kind = c.at("kind").get<std::string>();
    k.at = c.at("at").get<std::string>();
    k.target = c.at("target");
    if (k.target.at("kind") == "body" && !time.contains("epoch_mjd2000"))
      throw std::invalid_argument("field /time/epoch_mjd2000 is missing but constraint '" + k.id +
                                  "' follows a body's ephemeris");
    // psi compares position and velocity with the target's, named <id>_<state>.
    for (const auto& names : {pos, vel})
      for (const auto& n : names) {
        const std::string tname = k.id + "_" + n;
        k.psi.push_back(S.get(n) - S.get(tname));
        k.psi_names.push_back(n + " - " + tname);
        k.fixed_states.push_back(n);
        if (k.target.at("kind") == "fixed_state") {
          const bool is_pos = n[0] == 'r';
          const int i = n[1] - 'x';
          const double v = is_pos ? k.target.at("position_km")[i].get<double>() / U.length_km
                                  : k.target.at("velocity_km_s")[i].get<double>() / U.speed_km_s();
          p.parameters.push_back({tname, std::string(is_pos ? "position " : "velocity ") + n[1] + " of target " + k.id,
                                  is_pos ? L : L + "/" + T, v});
        } else {
          const std::string body = k.target.at("body").get<std::string>();
          p.parameters.push_back({tname, n + " of " + body + " (JPL low-precision ephemeris at " + k.at + ")",
                                  n[0] == 'r' ? L : L + "/" + T, 0.0, "ephemeris:" + body + ":" + k.at});
        }
      }
    if (k.kind == "initial_state") {
      if (k.at != "t0") throw std::invalid_argument("constraint '" + k.id + "': an initial state must be at t0");
      // The spacecraft's initial mass is known: mass is fixed at t0 as well.
      k.psi.push_back(m - 1);
      k.psi_names.push_back("m - 1");
      k.fixed_states.push_back("m");
    } else if (k.at != "tf") {
      throw std::invalid_argument("constraint '" + k.id + "': rendezvous is supported at tf only");
    }
    p.constraints.push_back(k);
  }
  return p;
}

}  // namespace helios::pmp

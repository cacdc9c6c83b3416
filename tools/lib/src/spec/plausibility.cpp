// What cannot be, found once the whole text is read, as facts and not guesses: an orbit or a position
// inside the central body (its periapsis at or below the surface), a constant of a named body far from
// the body's known value (a unit slipped: the Earth's mu in m^3/s^2 is 1e9 times too small), and an
// objective the other facts make constant (a fixed time of flight minimized, a fixed final radius
// maximized). Each is refused at the sentence that states it, saying how to state it.
#include <cmath>

#include "grammar.hpp"
#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {
namespace {

// Farther than this (relative) from a body's known constant, a stated one is another body's or a
// slipped unit: the values published for one body differ by less than 1e-3.
constexpr double kKnownConstantTolerance = 0.01;

std::string km(double v) {
  return io::short_number(v) + " km";
}

// Why a radius `r_km` from the centre lies at or below the surface of radius `surface_km`. A length
// written in a unit smaller than the km (`unit`, "" when not known) may have been meant in km.
std::string below(const std::string& what, double r_km, const std::string& body, double surface_km,
                  const std::string& unit = "") {
  std::string why =
      what + " is " + km(r_km) + " from the centre of " + body + ", " +
      (r_km > 0 && r_km < surface_km ? km(surface_km - r_km) + " below its surface" : "not above its surface") +
      " (equatorial radius " + km(surface_km) + "): a radius counts from the centre";
  const double km_per_unit = unit.empty() ? 1.0 : to_spec_unit(Dimension::Length, unit);
  if (km_per_unit < 1 && r_km / km_per_unit > surface_km)
    why += "; if it was meant in km, write " + km(r_km / km_per_unit);
  else
    why += " (an altitude above the surface reads 'at an altitude of Q')";
  return why;
}

double norm(const json& v) {
  return std::hypot(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

// "the Earth", "Mars": a body as a sentence names it.
std::string the(const std::string& body) {
  const std::string key = lowercase(body);
  return key == "earth" || key == "sun" || key == "moon" ? "the " + body : body;
}

}  // namespace

void Builder::check_physics() const {
  const std::string name = central_body.value("name", "");
  const std::optional<double> radius = central_body.contains("radius_km")
                                           ? std::optional<double>(central_body["radius_km"].get<double>())
                                       : central_on_purpose ? std::nullopt
                                                            : surface_radius(name);
  if (!radius) return;
  const double r_surface = *radius;
  const std::string body = the(name);
  const auto orbit = [&](const json& t, const Where& w, const std::string& what) {
    if (t.value("kind", "") != "orbital_elements" || !t.contains("semi_major_axis_km")) return;
    const double a = t["semi_major_axis_km"].get<double>(), e = t.value("eccentricity", 0.0);
    if (a * (1 - e) > r_surface) return;
    const std::string unit = t.value("length_unit", "");
    fail(w, e > 0 ? below(what + "'s periapsis (a = " + km(a) + ", e = " + io::short_number(e) + ")", a * (1 - e), body,
                          r_surface, unit)
                  : below(what + "'s radius", a, body, r_surface, unit));
  };
  const auto position = [&](const json& t, const Where& w, const std::string& what) {
    if (!t.contains("position_km")) return;
    const double r = norm(t["position_km"]);
    if (r <= r_surface) fail(w, below(what, r, body, r_surface, t.value("length_unit", "")));
  };
  orbit(departure->target, departure->where, "the departure orbit");
  position(departure->target, departure->where, "the initial position");
  for (const auto& e : events) orbit(e.target, e.where, "the orbit on the way");
  orbit(arrival->target, arrival->where, "the final orbit");
  position(arrival->target, arrival->where, "the final position");
  if (arrival->kind == "state_conditions")
    for (const auto& c : arrival->target["conditions"])
      if (c["expression"] == "r" && c["equals"].get<double>() <= r_surface)
        fail(arrival->where, below("the final radius", c["equals"].get<double>(), body, r_surface));
  for (const auto& o : orbits) {
    const double q = o.elements["a_AU"].get<double>() * (1 - o.elements["e"].get<double>()) * astro::AU_KM;
    if (q <= r_surface) fail(o.where, below("the perihelion of " + o.name, q, body, r_surface));
  }
  for (const auto& s : stated_radii)
    if (s.km <= r_surface) fail(s.where, below(s.what, s.km, body, r_surface));
}

// A constant of a body HELIOS knows, stated far from the known value, unless the body is said to be
// scaled on purpose.
void Builder::check_constants() const {
  if (central_on_purpose) return;
  const std::string name = central_body.value("name", "");
  const std::pair<const char*, std::optional<double>> known[] = {
      {"mu_km3_s2", known_mu(name)},
      {"radius_km", known_radius(name)},
      {"j2", lowercase(name) == "earth" ? std::optional<double>(astro::J2_EARTH) : std::nullopt}};
  static const std::map<std::string, std::pair<std::string, std::string>> words = {
      {"mu_km3_s2", {"gravitational parameter", " km^3/s^2"}},
      {"radius_km", {"equatorial radius", " km"}},
      {"j2", {"J2 coefficient", ""}}};
  for (const auto& [key, value] : known) {
    if (!value || !constant_where.count(key) || !central_body.contains(key)) continue;
    const double stated = central_body[key].get<double>();
    if (std::fabs(stated / *value - 1) <= kKnownConstantTolerance) continue;
    const auto& [what, unit] = words.at(key);
    const double ratio = stated / *value;
    fail(constant_where.at(key),
         "the " + what + " of " + the(name) + " is known: " + io::short_number(*value) + unit + ", and " +
             io::short_number(stated) + unit + " is " +
             (ratio > 1 ? io::short_number(ratio) + " times more" : io::short_number(1 / ratio) + " times less") +
             " (a unit slipped?); state the known value, or call the body 'a scaled " + name +
             "' ('The central body is a scaled " + name + " with ...') if the text means another on purpose");
  }
}

// An objective the other facts make constant is no objective: a fixed time of flight minimized, the
// final radius or energy maximized where the final condition fixes it, the fuel of an engine at full
// throttle throughout.
void Builder::check_objective() const {
  const std::string kind = objective.value("kind", "");
  const Where w = objective_where.value_or(here);
  if (kind == "minimum_time" && time.value("final_time", "") == "fixed")
    fail(w, "the time of flight is fixed (" + io::short_number(time["tof_days"].get<double>()) +
                " d), so minimizing it minimizes a constant: make it free ('The time of flight is free, at most "
                "Q.') or minimize the fuel");
  const json& t = arrival->target;
  const bool position_fixed = arrival->kind == "rendezvous" || arrival->kind == "flyby";
  bool radius_fixed = position_fixed || (arrival->kind == "orbit_insertion" && t.contains("semi_major_axis_km") &&
                                         t.value("eccentricity", -1.0) == 0.0);
  if (arrival->kind == "state_conditions")
    for (const auto& c : t["conditions"]) radius_fixed = radius_fixed || c["expression"] == "r";
  const bool energy_fixed =
      arrival->kind == "rendezvous" || (arrival->kind == "orbit_insertion" && t.contains("semi_major_axis_km"));
  const auto constant = [&](const std::string& what, const Where& by) {
    fail(w, "the final condition ('" + by.text + "', line " + std::to_string(by.line) + ") fixes the final " + what +
                ", so maximizing it maximizes a constant: leave the " + what +
                " free in the final condition (e.g. 'At the final time the spacecraft is on a circular orbit.')");
  };
  if (kind == "maximum_final_radius" && radius_fixed) constant("radius", arrival->where);
  if (kind == "maximum_final_energy" && energy_fixed) constant("energy", arrival->where);
  if ((kind == "minimum_fuel" || kind == "minimum_initial_mass") && spacecraft.value("full_throttle", false))
    fail(w,
         "the engine thrusts at full throttle throughout, so the propellant is the mass flow times the time of "
         "flight: minimize the time of flight, or let the engine throttle");
}

}  // namespace helios::spec::grammar

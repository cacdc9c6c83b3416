#pragma once
// JPL low-precision planetary ephemerides (Standish, "Keplerian Elements for Approximate Positions
// of the Major Planets", Table 1, valid 1800-2050), following pykep's jpl_lp convention.
// Standard library only: also compiled into the shooting runtime (templates/runtime/runtime.cpp).
#include "helios/astro/constants.hpp"
#include "helios/astro/kepler.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace helios::astro {

enum class Planet { EarthMoonBarycenter, Mars, Jupiter, Venus };

namespace ephemeris_detail {

// a [AU], e [-], I [deg], L [deg], varpi [deg], Omega [deg] at J2000, then rates per Julian century.
struct JplLpRow {
  double el[6];
  double rate[6];
};

inline const JplLpRow& jpl_lp_row(Planet p) {
  static const JplLpRow emb{{1.00000261, 0.01671123, -0.00001531, 100.46457166, 102.93768193, 0.0},
                            {0.00000562, -0.00004392, -0.01294668, 35999.37244981, 0.32327364, 0.0}};
  static const JplLpRow mars{{1.52371034, 0.09339410, 1.84969142, -4.55343205, -23.94362959, 49.55953891},
                             {0.00001847, 0.00007882, -0.00813131, 19140.30268499, 0.44441088, -0.29257343}};
  static const JplLpRow jupiter{{5.20288700, 0.04838624, 1.30439695, 34.39644051, 14.72847983, 100.47390909},
                                {-0.00011607, -0.00013253, -0.00183714, 3034.74612775, 0.21252668, 0.20469106}};
  static const JplLpRow venus{{0.72333566, 0.00677672, 3.39467605, 181.97909950, 131.60246718, 76.67984255},
                              {0.00000390, -0.00004107, -0.00078890, 58517.81538729, 0.00268329, -0.27769418}};
  switch (p) {
    case Planet::EarthMoonBarycenter:
      return emb;
    case Planet::Mars:
      return mars;
    case Planet::Jupiter:
      return jupiter;
    case Planet::Venus:
      return venus;
  }
  throw std::invalid_argument("jpl_lp: unknown Planet enumerator");
}

}  // namespace ephemeris_detail

namespace ephemeris_detail {

// Elements (a in km, angles in rad) from the table's a [AU], e, I, L, varpi, Omega [deg].
inline Elements from_table(const double (&x)[6]) {
  Elements el{};
  el.a = x[0] * AU_KM;
  el.e = x[1];
  el.i = x[2] * DEG_TO_RAD;
  el.raan = x[5] * DEG_TO_RAD;
  el.argp = (x[4] - x[5]) * DEG_TO_RAD;          // omega = varpi - Omega
  el.mean_anomaly = (x[3] - x[4]) * DEG_TO_RAD;  // M = L - varpi
  return el;
}

}  // namespace ephemeris_detail

// Osculating elements (a in km, angles in rad) of the JPL low-precision model at mjd2000.
inline Elements jpl_lp_elements(Planet p, double mjd2000) {
  const auto& row = ephemeris_detail::jpl_lp_row(p);
  // Julian centuries from J2000.0 (JD 2451545.0 = MJD2000 0.5).
  const double T = (mjd2000 - (JD_J2000 - JD_OF_MJD2000)) / JULIAN_CENTURY_DAYS;
  double x[6];
  for (int k = 0; k < 6; ++k) x[k] = row.el[k] + row.rate[k] * T;
  return ephemeris_detail::from_table(x);
}

// The elements' constant drift per day (a in km/day, angles in rad/day).
inline Elements jpl_lp_element_rates(Planet p) {
  const auto& row = ephemeris_detail::jpl_lp_row(p);
  double x[6];
  for (int k = 0; k < 6; ++k) x[k] = row.rate[k] / JULIAN_CENTURY_DAYS;
  return ephemeris_detail::from_table(x);
}

// Heliocentric ecliptic J2000 position [km] and velocity [km/s] at mjd2000 (days).
inline std::array<double, 6> jpl_lp_state(Planet p, double mjd2000) {
  return elements_to_state(jpl_lp_elements(p, mjd2000), MU_SUN_KM3_S2);
}

// d/dt of jpl_lp_state per day (km/day, km/s/day): the model's own rate, elements drift included
// (it is not the Kepler velocity the state reports).
inline std::array<double, 6> jpl_lp_state_rate(Planet p, double mjd2000) {
  return elements_to_state_rate(jpl_lp_elements(p, mjd2000), jpl_lp_element_rates(p), MU_SUN_KM3_S2);
}

// "Earth" is the Earth-Moon barycentre, as in the JPL table. Case-insensitive.
inline Planet planet_from_name(const std::string& name) {
  std::string s;
  s.reserve(name.size());
  for (char c : name) s.push_back(c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c);
  if (s == "earth" || s == "emb") return Planet::EarthMoonBarycenter;
  if (s == "mars") return Planet::Mars;
  if (s == "jupiter") return Planet::Jupiter;
  if (s == "venus") return Planet::Venus;
  throw std::invalid_argument("unknown planet name '" + name + "' (expected one of: Earth, EMB, Mars, Jupiter, Venus)");
}

}  // namespace helios::astro

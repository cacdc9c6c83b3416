// The rows psi(x) = 0 that put the state on an orbit given by some of its classical elements, the
// other elements and the position on the orbit free. They are written with the position r, the
// velocity v, the angular momentum h = r x v and the energy, never with the elements' angles, so
// every row is smooth and the rows independent on circular and equatorial orbits, where the node,
// the argument of periapsis and the anomaly are undefined:
//   semi-major axis a             |v|^2/2 - mu/|r| + mu/(2a) = 0                         1 row
//   circular, radius a            |r| - a = 0, r.v = 0, |v|^2 - mu/a = 0                 3 rows
//   circular, radius free         r.v = 0, |r| |v|^2 - mu = 0                            2 rows
//   eccentricity e > 0            |e_vec|^2 - e^2 = 0, e_vec = v x h/mu - r/|r|          1 row
//   inclination i and node W      h.N = 0, h.(n x N) = 0: h along the plane's normal     2 rows
//                                 n = (sin i sin W, -sin i cos W, cos i), N = (cos W, sin W, 0)
//   (equatorial: i = 0, W = 0: h_x = 0, h_y = 0)
//   inclination i, node free      h_z - |h| cos i = 0 (0 < i < 180 deg; the rows above at 0)  1 row
// The gradient of |e_vec|^2 vanishes at e = 0, and that of h_z - |h| cos i at i = 0: those two are
// refused there and the circular and equatorial rows used instead.
#include <cmath>
#include <optional>
#include <stdexcept>

#include "constraints.hpp"
#include "helios/astro/constants.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;

ex dot(const std::vector<ex>& a, const std::vector<ex>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::vector<ex> cross(const std::vector<ex>& a, const std::vector<ex>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

OrbitRows orbit_rows(Problem& p, const std::string& id, const io::json& target) {
  auto& S = p.symbols;
  const std::string where = "constraint '" + id + "'";
  const std::vector<ex> r = {S.get("rx"), S.get("ry"), S.get("rz")}, v = {S.get("vx"), S.get("vy"), S.get("vz")};
  const ex mu = S.get("mu");
  const ex r_norm = GiNaC::sqrt(dot(r, r)), v2 = dot(v, v);
  const std::vector<ex> h = cross(r, v);
  OrbitRows rows;
  const auto add = [&](const ex& row, const std::string& meaning) {
    rows.psi.push_back(row);
    rows.names.push_back(meaning);
  };
  const auto parameter = [&](const std::string& stem, const std::string& meaning, const std::string& unit,
                             double value) {
    const std::string name = stem + "_" + id;
    p.parameters.push_back({name, meaning + " of target orbit " + id, unit, value});
    return ex(S.get(name));
  };
  const auto field = [&](const char* key) -> std::optional<double> {
    if (!target.contains(key)) return std::nullopt;
    return target.at(key).get<double>();
  };
  const std::optional<double> a_km = field("semi_major_axis_km"), e = field("eccentricity"),
                              i_deg = field("inclination_deg"), node_deg = field("raan_deg");
  if (!a_km && !e && !i_deg) throw std::invalid_argument(where + ": an orbit target needs an element to meet");
  if (e && !(*e >= 0 && *e < 1)) throw std::invalid_argument(where + ": eccentricity must lie in [0, 1)");
  if (a_km && !(*a_km > 0)) throw std::invalid_argument(where + ": semi_major_axis_km must be positive");
  if (e && *e == 0) {
    if (a_km) {
      const ex a = parameter("a", "radius", p.units.length_name, *a_km / p.units.length_km);
      add(r_norm - a, "|r| - a_" + id);
      add(dot(r, v), "r.v");
      add(v2 - mu / a, "|v|^2 - mu/a_" + id);
    } else {
      add(dot(r, v), "r.v");
      add(r_norm * v2 - mu, "|r| |v|^2 - mu");
    }
  } else {
    if (a_km) {
      const ex a = parameter("a", "semi-major axis", p.units.length_name, *a_km / p.units.length_km);
      add(v2 / 2 - mu / r_norm + mu / (2 * a), "|v|^2/2 - mu/|r| + mu/(2 a_" + id + ")");
    }
    if (e) {
      const ex ecc = parameter("e", "eccentricity", "1", *e);
      std::vector<ex> e_vec = cross(v, h);
      for (int k = 0; k < 3; ++k) e_vec[k] = e_vec[k] / mu - r[k] / r_norm;
      add(dot(e_vec, e_vec) - ecc * ecc, "|e_vec|^2 - e_" + id + "^2");
    }
  }
  if (node_deg && !i_deg) throw std::invalid_argument(where + ": a node needs the inclination");
  if (i_deg) {
    if (!(*i_deg >= 0 && *i_deg <= 180)) throw std::invalid_argument(where + ": inclination_deg must lie in [0, 180]");
    const bool planar = node_deg || *i_deg == 0 || *i_deg == 180;
    // The node first: the parameters' order is the derivation's.
    const ex W = planar ? parameter("raan", "ascending node (rad)", "1", node_deg.value_or(0.0) * astro::DEG_TO_RAD)
                        : ex(0);
    const ex I = parameter("inc", "inclination (rad)", "1", *i_deg * astro::DEG_TO_RAD);
    if (planar) {
      // The plane's normal n and its node line N; n x N = (-cos i sin W, cos i cos W, sin i).
      add(h[0] * cos(W) + h[1] * sin(W), "h.N_" + id);
      add(-h[0] * cos(I) * sin(W) + h[1] * cos(I) * cos(W) + h[2] * sin(I), "h.(n x N)_" + id);
    } else {
      add(h[2] - GiNaC::sqrt(dot(h, h)) * cos(I), "h_z - |h| cos(inc_" + id + ")");
    }
  }
  return rows;
}

}  // namespace helios::pmp

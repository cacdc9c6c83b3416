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
//   argument of periapsis w       e_vec.Q = 0: the periapsis along P in the plane            1 row
//                                 (e > 0 and the plane given; P, Q below)
// The plane's rows also hold with h along -n, and e_vec.Q = 0 with the periapsis along -P: the
// mirrors are told apart by h.n > 0 and e_vec.P > 0, conditions the runtime checks on every
// extremal (no two smooth rows on the sphere of directions vanish at one point only).
// The gradient of |e_vec|^2 vanishes at e = 0, and that of h_z - |h| cos i at i = 0: those two are
// refused there and the circular and equatorial rows used instead.
#include <algorithm>
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

// The elements an orbit states, and its parameters <element>_<id>.
struct OrbitElements {
  OrbitElements(Problem& problem, std::string orbit_id, const io::json& target)
      : p(problem), id(std::move(orbit_id)), where("constraint '" + id + "'") {
    const auto field = [&](const char* key) -> std::optional<double> {
      if (!target.contains(key)) return std::nullopt;
      return target.at(key).get<double>();
    };
    a_km = field("semi_major_axis_km"), e = field("eccentricity"), i_deg = field("inclination_deg"),
    node_deg = field("raan_deg"), argp_deg = field("argp_deg");
    if (e && !(*e >= 0 && *e < 1)) throw std::invalid_argument(where + ": eccentricity must lie in [0, 1)");
    if (a_km && !(*a_km > 0)) throw std::invalid_argument(where + ": semi_major_axis_km must be positive");
    if (i_deg && !(*i_deg >= 0 && *i_deg <= 180))
      throw std::invalid_argument(where + ": inclination_deg must lie in [0, 180]");
    if (node_deg && !i_deg) throw std::invalid_argument(where + ": a node needs the inclination");
    if (argp_deg && !(e && *e > 0))
      throw std::invalid_argument(where + ": an argument of periapsis needs an eccentricity above 0");
    const io::json free = target.value("free", io::json::array());
    if (argp_deg && !planar() && std::find(free.begin(), free.end(), "raan") == free.end())
      throw std::invalid_argument(where + ": an argument of periapsis needs the orbit's plane (inclination and node)");
  }
  // The plane is given: by its inclination and node, or as equatorial (the node undefined, 0).
  bool planar() const { return i_deg && (node_deg || *i_deg == 0 || *i_deg == 180); }
  ex parameter(const std::string& stem, const std::string& meaning, const std::string& unit, double value) const {
    const std::string name = stem + "_" + id;
    p.parameters.push_back({name, meaning + " of orbit " + id, unit, value});
    return p.symbols.get(name);
  }
  ex semi_major_axis(const std::string& meaning) const {
    return parameter("a", meaning, p.units.length_name, *a_km / p.units.length_km);
  }
  ex eccentricity() const { return parameter("e", "eccentricity", "1", *e); }
  ex angle(const std::string& stem, const std::string& meaning, double deg) const {
    return parameter(stem, meaning + " (rad)", "1", deg * astro::DEG_TO_RAD);
  }
  // The node and the inclination of a given plane (0 where undefined), the node first: the
  // parameters' order is the derivation's.
  std::pair<ex, ex> plane() const {
    const ex node =
        node_deg || (*i_deg != 0 && *i_deg != 180) ? angle("raan", "ascending node", node_deg.value_or(0)) : ex(0);
    return {node, *i_deg == 0 ? ex(0) : angle("inc", "inclination", *i_deg)};
  }

  Problem& p;
  std::string id, where;
  std::optional<double> a_km, e, i_deg, node_deg, argp_deg;
};

// The unit vectors P (to the periapsis) and Q (90 deg ahead in the sense of motion) of the orbit
// with node W, inclination I and argument of periapsis w.
std::pair<std::vector<ex>, std::vector<ex>> perifocal_axes(const ex& W, const ex& I, const ex& w) {
  const ex cW = cos(W), sW = sin(W), cI = cos(I), sI = sin(I), cw = cos(w), sw = sin(w);
  return {{cW * cw - sW * sw * cI, sW * cw + cW * sw * cI, sw * sI},
          {-cW * sw - sW * cw * cI, -sW * sw + cW * cw * cI, cw * sI}};
}

}  // namespace

OrbitRows orbit_rows(Problem& p, const std::string& id, const io::json& target) {
  auto& S = p.symbols;
  const OrbitElements el(p, id, target);
  const std::vector<ex> r = {S.get("rx"), S.get("ry"), S.get("rz")}, v = {S.get("vx"), S.get("vy"), S.get("vz")};
  const ex mu = S.get("mu");
  const ex r_norm = GiNaC::sqrt(dot(r, r)), v2 = dot(v, v);
  const std::vector<ex> h = cross(r, v);
  OrbitRows rows;
  const auto add = [&](const ex& row, const std::string& meaning) {
    rows.psi.push_back(row);
    rows.names.push_back(meaning);
  };
  if (!el.a_km && !el.e && !el.i_deg)
    throw std::invalid_argument(el.where + ": an orbit target needs an element to meet");
  std::vector<ex> e_vec = cross(v, h);
  for (int k = 0; k < 3; ++k) e_vec[k] = e_vec[k] / mu - r[k] / r_norm;
  if (el.e && *el.e == 0) {
    if (el.a_km) {
      const ex a = el.semi_major_axis("radius");
      add(r_norm - a, "|r| - a_" + id);
      add(dot(r, v), "r.v");
      add(v2 - mu / a, "|v|^2 - mu/a_" + id);
    } else {
      add(dot(r, v), "r.v");
      add(r_norm * v2 - mu, "|r| |v|^2 - mu");
    }
  } else {
    if (el.a_km) {
      const ex a = el.semi_major_axis("semi-major axis");
      add(v2 / 2 - mu / r_norm + mu / (2 * a), "|v|^2/2 - mu/|r| + mu/(2 a_" + id + ")");
    }
    if (el.e) {
      const ex ecc = el.eccentricity();
      add(dot(e_vec, e_vec) - ecc * ecc, "|e_vec|^2 - e_" + id + "^2");
    }
  }
  if (el.planar()) {
    // The plane's normal n and its node line N; n x N = (-cos i sin W, cos i cos W, sin i).
    const auto [W, I] = el.plane();
    add(h[0] * cos(W) + h[1] * sin(W), "h.N_" + id);
    add(-h[0] * cos(I) * sin(W) + h[1] * cos(I) * cos(W) + h[2] * sin(I), "h.(n x N)_" + id);
    rows.must_be_positive.push_back(
        {h[0] * sin(I) * sin(W) - h[1] * sin(I) * cos(W) + h[2] * cos(I),
         "h.n_" + id + " > 0: the orbit runs the stated way round its plane, not on its retrograde mirror"});
    if (el.argp_deg) {
      const ex w = el.angle("argp", "argument of periapsis", *el.argp_deg);
      const auto [P, Q] = perifocal_axes(W, I, w);
      add(dot(e_vec, Q), "e_vec.Q_" + id);
      rows.must_be_positive.push_back(
          {dot(e_vec, P), "e_vec.P_" + id + " > 0: the periapsis at the stated argument, not opposite it"});
    }
  } else if (el.i_deg) {
    const ex I = el.angle("inc", "inclination", *el.i_deg);
    add(h[2] - GiNaC::sqrt(dot(h, h)) * cos(I), "h_z - |h| cos(inc_" + id + ")");
  }
  return rows;
}

std::vector<ex> orbit_point(Problem& p, const std::string& id, const io::json& target, const FreeOrbitAngles& angles) {
  const OrbitElements el(p, id, target);
  const io::json free = target.value("free", io::json::array());
  const auto is_free = [&](const char* element) { return std::find(free.begin(), free.end(), element) != free.end(); };
  const auto need = [&](bool given, const std::string& what) {
    if (!given)
      throw std::invalid_argument(el.where + ": a departure orbit needs its " + what +
                                  " (only the position on it may be free)");
  };
  need(el.a_km.has_value(), "semi-major axis (or radius)");
  need(el.e.has_value(), "eccentricity (or the word circular)");
  need(el.i_deg.has_value(), "inclination (or the word equatorial)");
  const bool equatorial = *el.i_deg == 0 || *el.i_deg == 180, node_free = is_free("raan"), argp_free = is_free("argp");
  if (node_free && equatorial)
    throw std::invalid_argument(el.where + ": an equatorial orbit has no node to leave free");
  if (argp_free && *el.e == 0)
    throw std::invalid_argument(el.where + ": a circular orbit has no periapsis to leave free");
  need(el.planar() || node_free, "node (or free: \"free\": [\"raan\"])");
  need(*el.e == 0 || el.argp_deg.has_value() || argp_free, "argument of periapsis (or free: \"free\": [\"argp\"])");
  const ex semi_latus = el.parameter("p", "semi-latus rectum a (1 - e^2)", p.units.length_name,
                                     *el.a_km * (1 - *el.e * *el.e) / p.units.length_km);
  const ex e = *el.e == 0 ? ex(0) : el.eccentricity();
  // P and Q as parameters of their own: the orbit's orientation in six numbers, not in the angles
  // (at node 0 and argument of periapsis 0 where those are free).
  const double deg = astro::DEG_TO_RAD;
  const auto [P_value, Q_value] = perifocal_axes(node_free ? 0.0 : el.node_deg.value_or(0) * deg, *el.i_deg * deg,
                                                 argp_free ? 0.0 : el.argp_deg.value_or(0) * deg);
  std::vector<ex> P, Q;
  for (int k = 0; k < 3; ++k) {
    const std::string c(1, static_cast<char>('x' + k));
    P.push_back(el.parameter("P" + c, c + " of the unit vector to the periapsis (the node if circular)", "1",
                             GiNaC::ex_to<GiNaC::numeric>(P_value[k].evalf()).to_double()));
    Q.push_back(el.parameter("Q" + c, c + " of the unit vector 90 deg ahead of P in the sense of motion", "1",
                             GiNaC::ex_to<GiNaC::numeric>(Q_value[k].evalf()).to_double()));
  }
  if (argp_free) {  // turned in the plane by the argument of periapsis
    const std::vector<ex> P0 = P, Q0 = Q;
    for (int k = 0; k < 3; ++k) {
      P[k] = cos(angles.argp) * P0[k] + sin(angles.argp) * Q0[k];
      Q[k] = -sin(angles.argp) * P0[k] + cos(angles.argp) * Q0[k];
    }
  }
  if (node_free)  // turned about z by the node
    for (std::vector<ex>* axis : {&P, &Q}) {
      const std::vector<ex> a = *axis;
      *axis = {cos(angles.node) * a[0] - sin(angles.node) * a[1], sin(angles.node) * a[0] + cos(angles.node) * a[1],
               a[2]};
    }
  const ex& theta = angles.theta;
  const ex radius = semi_latus / (1 + e * cos(theta));
  const ex speed = GiNaC::sqrt(p.symbols.get("mu") / semi_latus);
  std::vector<ex> x(6);
  for (int k = 0; k < 3; ++k) {
    x[k] = radius * (cos(theta) * P[k] + sin(theta) * Q[k]);
    x[3 + k] = speed * (-sin(theta) * P[k] + (e + cos(theta)) * Q[k]);
  }
  return x;
}

}  // namespace helios::pmp

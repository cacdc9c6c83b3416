// The constraints' psi against their targets: each endpoint constraint's rows must put the state on
// the set its target names (a fixed state, a body's or a coasting target's state, an orbit given by
// some of its elements, equations of the final state), re-derived here from the target as written
// with the verifier's own formulas (elements to state by Kepler's equation, not the deriver's
// rows); the initial values must meet the rows at t0.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>

#include "family.hpp"
#include "helios/astro/kepler.hpp"

namespace helios::verify::detail {
namespace {

// A row misses the target when the state at a point of the target's set is farther than this from
// the row's zero set, relative to 1 + |x| (the distance |psi| / |grad psi|, to first order).
constexpr double kOffTarget = 1e-9;
// A row counts towards a rank when what is left of it after the rows before is above this share of
// its length.
constexpr double kRankShare = 1e-9;
// A state is on an orbit of the stated elements when each matches to this (relative, or rad).
constexpr double kElementTolerance = 1e-6;

using Matrix = std::vector<std::vector<double>>;

double norm(const std::vector<double>& a) {
  double s = 0;
  for (const double x : a) s += x * x;
  return std::sqrt(s);
}

// The number of independent rows of `a`: Gram-Schmidt against the unit rows before.
int rank_of(Matrix a) {
  std::vector<std::vector<double>> basis;
  for (auto& row : a) {
    const double length = norm(row);
    for (const auto& b : basis) {
      double d = 0;
      for (std::size_t i = 0; i < row.size(); ++i) d += row[i] * b[i];
      for (std::size_t i = 0; i < row.size(); ++i) row[i] -= d * b[i];
    }
    const double left = norm(row);
    if (!(length > 0) || !(left > kRankShare * length)) continue;
    for (double& x : row) x /= left;
    basis.push_back(row);
  }
  return static_cast<int>(basis.size());
}

// x of the square system m x = b (partial pivoting); false when m is singular.
bool solve_square(Matrix m, std::vector<double> b, std::vector<double>& x) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t best = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[best][c])) best = r;
    if (!(std::fabs(m[best][c]) > 1e-300)) return false;
    std::swap(m[c], m[best]);
    std::swap(b[c], b[best]);
    for (std::size_t r = c + 1; r < n; ++r) {
      const double f = m[r][c] / m[c][c];
      for (std::size_t k = c; k < n; ++k) m[r][k] -= f * m[c][k];
      b[r] -= f * b[c];
    }
  }
  x.assign(n, 0);
  for (std::size_t c = n; c-- > 0;) {
    double s = b[c];
    for (std::size_t k = c + 1; k < n; ++k) s -= m[c][k] * x[k];
    x[c] = s / m[c][c];
  }
  return true;
}

// Rows r_j of some variables (slots of a Point) with their gradients in them; the first `sized` of
// the variables are the state, whose size scales the distances.
struct Rows {
  std::vector<Compiled> value;
  std::vector<std::vector<Compiled>> gradient;  // [row][variable]
  std::vector<int> variables;                   // slots
  std::size_t sized = 0;
};

// The rows' values, their gradients and their distances |r_j| / (|grad r_j| (1 + |x|)) at p.
struct RowsAt {
  std::vector<double> value, distance;
  Matrix gradient;
  double worst = 0;
};

RowsAt evaluate(const Rows& rows, const Point& p) {
  RowsAt at;
  std::vector<double> x;
  for (std::size_t k = 0; k < rows.sized; ++k) x.push_back(p[static_cast<std::size_t>(rows.variables[k])]);
  const double size = 1 + norm(x);
  for (std::size_t j = 0; j < rows.value.size(); ++j) {
    at.value.push_back(rows.value[j](p));
    std::vector<double> g;
    for (const auto& d : rows.gradient[j]) g.push_back(d(p));
    const double length = norm(g), r = std::fabs(at.value.back());
    const double distance = r == 0 ? 0 : length > 0 && std::isfinite(r) ? r / (length * size) : INFINITY;
    at.distance.push_back(distance);
    at.worst = std::max(at.worst, distance);
    at.gradient.push_back(std::move(g));
  }
  return at;
}

// Moves the variables [from, n) of p to a zero of the rows from where they are: Gauss-Newton on the
// rows those variables move, each row divided by its whole gradient's length, the least-norm step where
// there are fewer rows than variables and the least-squares one where there are more, halved until
// it lowers the sum of the squared scaled rows. Returns the largest distance at the end.
double to_zero(const Rows& rows, Point& p, std::size_t from = 0) {
  const std::size_t n = rows.variables.size() - from;
  const auto scaled = [&](const RowsAt& at, Matrix* J) {
    std::vector<double> r;
    for (std::size_t j = 0; j < at.value.size(); ++j) {
      const std::vector<double> g(at.gradient[j].begin() + static_cast<std::ptrdiff_t>(from), at.gradient[j].end());
      const double length = norm(at.gradient[j]);
      if (!(norm(g) > 0)) continue;  // a row these variables do not move
      r.push_back(at.value[j] / length);
      if (J) {
        J->push_back(g);
        for (double& x : J->back()) x /= length;
      }
    }
    return r;
  };
  const auto merit = [](const std::vector<double>& r) {
    double s = 0;
    for (const double x : r) s += x * x;
    return std::isfinite(s) ? s : INFINITY;
  };
  RowsAt at = evaluate(rows, p);
  for (int iteration = 0; iteration < 60 && at.worst > 1e-15 && std::isfinite(at.worst); ++iteration) {
    Matrix J;
    const std::vector<double> r = scaled(at, &J);
    const std::size_t m = r.size();
    std::vector<double> step(n, 0);
    if (m <= n) {  // step = -J^T (J J^T)^-1 r
      Matrix JJ(m, std::vector<double>(m, 0));
      for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b)
          for (std::size_t k = 0; k < n; ++k) JJ[a][b] += J[a][k] * J[b][k];
      std::vector<double> y;
      if (!solve_square(JJ, r, y)) break;
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t a = 0; a < m; ++a) step[k] -= J[a][k] * y[a];
    } else {  // step = -(J^T J)^-1 J^T r
      Matrix JJ(n, std::vector<double>(n, 0));
      std::vector<double> Jr(n, 0);
      for (std::size_t a = 0; a < n; ++a) {
        for (std::size_t b = 0; b < n; ++b)
          for (std::size_t j = 0; j < m; ++j) JJ[a][b] += J[j][a] * J[j][b];
        for (std::size_t j = 0; j < m; ++j) Jr[a] += J[j][a] * r[j];
      }
      if (!solve_square(JJ, Jr, step)) break;
      for (double& x : step) x = -x;
    }
    const double before = merit(r);
    bool moved = false;
    for (double scale = 1; scale > 1e-9 && !moved; scale /= 2) {
      Point q = p;
      for (std::size_t k = 0; k < n; ++k) q[static_cast<std::size_t>(rows.variables[from + k])] += scale * step[k];
      RowsAt next = evaluate(rows, q);
      if (merit(scaled(next, nullptr)) < before) {
        p = std::move(q);
        at = std::move(next);
        moved = true;
      }
    }
    if (!moved) break;
  }
  return at.worst;
}

// The slots of the Cartesian state: position, velocity and mass.
struct StateSlots {
  std::vector<int> r, v;
  int m = -1;
  std::vector<int> all() const {
    std::vector<int> out = r;
    out.insert(out.end(), v.begin(), v.end());
    if (m >= 0) out.push_back(m);
    return out;
  }
};

// The elements an orbital_elements target states (a departure's free ones left out), in the
// derivation's units and radians.
struct StatedElements {
  std::optional<double> a, e, i, raan, argp;
  bool planar() const { return i && (raan || *i == 0 || std::fabs(*i - M_PI) < 1e-15); }
  // The conditions they put on (r, v): a 1, e 1 (circular 2), the plane 2 (the inclination alone
  // 1), the argument of periapsis 1.
  int conditions() const {
    return (a ? 1 : 0) + (e ? (*e == 0 ? 2 : 1) : 0) + (planar() ? 2 : i ? 1 : 0) + (argp ? 1 : 0);
  }
};

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double length(const std::array<double, 3>& a) {
  return std::sqrt(dot(a, a));
}

// The unit vectors to the periapsis (P) and along the orbit's normal (n) of node W, inclination I
// and argument of periapsis w.
std::pair<std::array<double, 3>, std::array<double, 3>> orientation(double W, double I, double w) {
  return {{std::cos(W) * std::cos(w) - std::sin(W) * std::sin(w) * std::cos(I),
           std::sin(W) * std::cos(w) + std::cos(W) * std::sin(w) * std::cos(I), std::sin(w) * std::sin(I)},
          {std::sin(I) * std::sin(W), -std::sin(I) * std::cos(W), std::cos(I)}};
}

// True when the state (r, v) is on an orbit of the stated elements about mu.
bool on_orbit(const StatedElements& el, const std::array<double, 3>& r, const std::array<double, 3>& v, double mu) {
  const std::array<double, 3> h = cross(r, v), vh = cross(v, h);
  const double energy = dot(v, v) / 2 - mu / length(r);
  if (!(length(h) > 0) || !(energy < 0)) return false;
  std::array<double, 3> e_vec;
  for (int k = 0; k < 3; ++k) e_vec[k] = vh[k] / mu - r[k] / length(r);
  const double a = -mu / (2 * energy), e = length(e_vec);
  if (el.a && std::fabs(a - *el.a) > kElementTolerance * *el.a) return false;
  if (el.e && std::fabs(e - *el.e) > kElementTolerance) return false;
  const auto [P, n] = orientation(el.raan.value_or(0), el.i.value_or(0), el.argp.value_or(0));
  const auto apart = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  };
  std::array<double, 3> h_unit = h;
  for (double& x : h_unit) x /= length(h);
  if (el.planar() && apart(h_unit, n) > kElementTolerance) return false;
  if (el.i && !el.planar() && std::fabs(std::acos(std::clamp(h_unit[2], -1.0, 1.0)) - *el.i) > kElementTolerance)
    return false;
  if (el.argp) {
    std::array<double, 3> e_unit = e_vec;
    for (double& x : e_unit) x /= e;
    if (el.planar() && apart(e_unit, P) > kElementTolerance) return false;
    if (!el.planar()) {  // from the ascending node, whichever it is
      const std::array<double, 3> node = {-h[1], h[0], 0};
      const double w = std::atan2(dot(cross(node, e_vec), h_unit), dot(node, e_vec));
      if (std::fabs(std::remainder(w - *el.argp, 2 * M_PI)) > kElementTolerance) return false;
    }
  }
  return true;
}

class TargetFamily : public Family {
 public:
  using Family::Family;

  std::vector<Check> run() override {
    if (!read_state_slots()) return {};
    for (std::size_t k = 0; k < ctx.constraints.size(); ++k) check_target(k);
    check_initial_values();
    return std::move(checks);
  }

 private:
  StateSlots slots;

  // The set of states a target asks for: how many conditions it puts on them, a random state of
  // it, and (an orbit) whether a state is on it.
  struct TargetSet {
    std::string text, error;
    int conditions = 0;
    std::function<bool(Point&, std::mt19937_64&)> sample;
    std::function<bool(const Point&)> member;  // set where psi may also hold on the orbit's mirrors
  };

  bool read_state_slots() {
    for (const std::size_t i : ctx.positions) slots.r.push_back(ctx.slot(ctx.states[i]));
    for (const auto& s : ctx.states) {
      const Kind k = ctx.kinds[static_cast<std::size_t>(ctx.slot(s))];
      if (k == Kind::Velocity) slots.v.push_back(ctx.slot(s));
      if (k == Kind::Mass) slots.m = ctx.slot(s);
    }
    if (slots.r.size() == 3 && slots.v.size() == 3) return true;
    Check c = start("targets", "transversality", "structural");
    c.fail(
        "the states are not a Cartesian position and velocity (three each), so the constraints' psi cannot be "
        "compared with their targets; name the states by their meaning (position x, velocity x, ...).");
    checks.push_back(c);
    return false;
  }

  double parameter(const std::string& name) const {
    return ctx.slots.count(name) ? ctx.values[static_cast<std::size_t>(ctx.slot(name))] : std::nan("");
  }

  std::array<double, 3> position(const Point& p) const {
    return {p[static_cast<std::size_t>(slots.r[0])], p[static_cast<std::size_t>(slots.r[1])],
            p[static_cast<std::size_t>(slots.r[2])]};
  }
  std::array<double, 3> velocity(const Point& p) const {
    return {p[static_cast<std::size_t>(slots.v[0])], p[static_cast<std::size_t>(slots.v[1])],
            p[static_cast<std::size_t>(slots.v[2])]};
  }
  void set_state(Point& p, const std::array<double, 6>& x) const {
    for (int k = 0; k < 3; ++k) {
      p[static_cast<std::size_t>(slots.r[k])] = x[k];
      p[static_cast<std::size_t>(slots.v[k])] = x[3 + k];
    }
  }

  // Whether the constraint fixes the mass: a known initial mass at t0 (the mass unit is the initial
  // mass), the given final mass at tf of a minimum-initial-mass problem (the mass unit is the final
  // mass), in normalized units 1 either way.
  bool fixes_mass(const derivation::Constraint& c) const {
    if (slots.m < 0) return false;
    const std::string& mass_unit = ctx.doc.state_quantities[static_cast<std::size_t>(index_of(slots.m))].unit_text;
    if (c.at == "t0") return c.kind == "initial_state" && mass_unit != "final mass";
    return (c.kind == "rendezvous" || c.kind == "flyby") && mass_unit == "final mass";
  }

  // A fixed state in km and km/s: its position (and velocity, but for a flyby) in normalized units.
  TargetSet fixed_state(const derivation::Constraint& c) const {
    TargetSet t;
    const io::json& target = c.target;
    std::array<double, 6> x{};
    const double L = ctx.doc.units.length_km, V = L / ctx.doc.units.time_s;
    for (int k = 0; k < 6; ++k) {
      const io::json& list = target.value(k < 3 ? "position_km" : "velocity_km_s", io::json());
      if (!list.is_array() || list.size() != 3 || !list[static_cast<std::size_t>(k % 3)].is_number()) {
        t.error = "its target has no " + std::string(k < 3 ? "position_km" : "velocity_km_s") + " [x, y, z]";
        return t;
      }
      x[static_cast<std::size_t>(k)] = list[static_cast<std::size_t>(k % 3)].get<double>() / (k < 3 ? L : V);
    }
    const bool position_only = c.kind == "flyby";
    t.conditions = position_only ? 3 : 6;
    t.text = "the state " + target.dump();
    t.sample = [this, x, position_only](Point& p, std::mt19937_64&) {
      const std::array<double, 3> v = velocity(p);
      set_state(p, x);
      if (position_only)
        for (int k = 0; k < 3; ++k) p[static_cast<std::size_t>(slots.v[k])] = v[k];
      return true;
    };
    return t;
  }

  // A body's or a coasting target's state, which the runtime evaluates: the parameters <id>_rx ...
  // with the source that names it.
  TargetSet sourced_state(const derivation::Constraint& c) const {
    TargetSet t;
    const std::string kind = c.target.value("kind", "");
    const std::string source = kind == "coasting"
                                   ? "coast:" + c.id + ":" + c.at
                                   : "ephemeris:" + c.target.value("body", std::string("?")) + ":" + c.at;
    const bool position_only = c.kind == "flyby";
    std::vector<int> components;
    for (const char* n : {"rx", "ry", "rz", "vx", "vy", "vz"}) {
      if (position_only && n[0] == 'v') break;
      const std::string name = names::target_component(c.id, n);
      const auto it = ctx.sources.find(name);
      if (it == ctx.sources.end() || it->second != source) {
        t.error = "its target is " + c.target.dump() + ", whose state the runtime evaluates: psi must use the " +
                  "parameter " + name + " with source " + source +
                  (it == ctx.sources.end() ? ", which is missing" : ", not " + it->second);
        return t;
      }
      components.push_back(ctx.slot(name));
    }
    t.conditions = static_cast<int>(components.size());
    t.text = "the state of " + c.target.dump() + " at " + c.at + " (parameters with source " + source + ")";
    t.sample = [this, components](Point& p, std::mt19937_64&) {
      for (std::size_t k = 0; k < components.size(); ++k)
        p[static_cast<std::size_t>(k < 3 ? slots.r[k] : slots.v[k - 3])] = p[static_cast<std::size_t>(components[k])];
      return true;
    };
    return t;
  }

  // An orbit given by some of its elements: a random state on it (the elements it leaves free drawn
  // too), by Kepler's equation.
  TargetSet orbit(const derivation::Constraint& c) const {
    TargetSet t;
    const io::json& target = c.target;
    const io::json free = target.value("free", io::json::array());
    const double mu = parameter("mu");
    if (!(mu > 0)) {
      t.error = "the parameters have no positive mu (the central body's gravitational parameter) to place its orbit";
      return t;
    }
    StatedElements el;
    const auto stated = [&](const char* key, const char* element, double factor) -> std::optional<double> {
      const bool left_free = std::find(free.begin(), free.end(), element) != free.end();
      if (left_free || !target.contains(key) || !target.at(key).is_number()) return std::nullopt;
      return target.at(key).get<double>() * factor;
    };
    const double deg = astro::DEG_TO_RAD;
    el.a = stated("semi_major_axis_km", "a", 1 / ctx.doc.units.length_km);
    el.e = stated("eccentricity", "e", 1);
    el.i = stated("inclination_deg", "i", deg);
    el.raan = stated("raan_deg", "raan", deg);
    el.argp = stated("argp_deg", "argp", deg);
    if (el.e && *el.e == 0) el.argp.reset();                                       // a circular orbit has no periapsis
    if (el.i && (*el.i == 0 || std::fabs(*el.i - M_PI) < 1e-15)) el.raan.reset();  // an equatorial one no node
    if (el.conditions() == 0 || (el.a && !(*el.a > 0)) || (el.e && !(*el.e >= 0 && *el.e < 1))) {
      t.error = "its target " + target.dump() + " states no usable element";
      return t;
    }
    t.conditions = el.conditions();
    t.text = "the orbit " + target.dump();
    t.sample = [this, el, mu](Point& p, std::mt19937_64& rng) {
      astro::Elements drawn;
      drawn.a = el.a.value_or(uniform(rng, 1, 3));
      drawn.e = el.e.value_or(uniform(rng, 0.05, 0.6));
      drawn.i = el.i.value_or(uniform(rng, 0.1, M_PI - 0.1));
      const bool equatorial = drawn.i == 0 || std::fabs(drawn.i - M_PI) < 1e-15;
      drawn.raan = equatorial ? 0 : el.raan.value_or(uniform(rng, 0, 2 * M_PI));
      drawn.argp = drawn.e == 0 ? 0 : el.argp.value_or(uniform(rng, 0, 2 * M_PI));
      drawn.mean_anomaly = uniform(rng, 0, 2 * M_PI);
      set_state(p, astro::elements_to_state(drawn, mu));
      return true;
    };
    t.member = [this, el, mu](const Point& p) { return on_orbit(el, position(p), velocity(p), mu); };
    return t;
  }

  // Equations of the final state, f(x) = value with f in km, s and kg: a state where they hold, by
  // Gauss-Newton from a random one.
  TargetSet equations(const derivation::Constraint& c) const {
    TargetSet t;
    const io::json& list = c.target.value("conditions", io::json());
    const double mu = parameter("mu");
    if (!list.is_array() || list.empty()) {
      t.error = "its target has no conditions";
      return t;
    }
    const double L = ctx.doc.units.length_km, T = ctx.doc.units.time_s, M = ctx.doc.units.mass_kg;
    symbolic::SymbolTable physical;
    std::vector<ex> r, v;
    for (int k = 0; k < 3; ++k) {
      r.push_back(L * symbol_at(slots.r[k]));
      v.push_back(L / T * symbol_at(slots.v[k]));
    }
    const auto length_of = [](const std::vector<ex>& a) {
      return GiNaC::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    };
    const std::vector<ex> h = {r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0]};
    GiNaC::exmap in_state;
    const std::vector<std::pair<const char*, ex>> meaning = {
        {"x", r[0]},  {"y", r[1]},         {"z", r[2]},  {"r", length_of(r)}, {"vx", v[0]}, {"vy", v[1]},
        {"vz", v[2]}, {"v", length_of(v)}, {"hx", h[0]}, {"hy", h[1]},        {"hz", h[2]}, {"h", length_of(h)}};
    for (const auto& [name, value] : meaning) in_state[physical.get(name)] = value;
    if (ctx.slots.count("mu")) in_state[physical.get("mu")] = L * L * L / (T * T) * ctx.sym("mu");
    if (slots.m >= 0) in_state[physical.get("m")] = M * symbol_at(slots.m);
    Rows rows;
    rows.variables = slots.all();
    rows.sized = rows.variables.size();
    try {
      for (std::size_t j = 0; j < list.size(); ++j) {
        const std::string where = "constraints[" + c.id + "].target.conditions[" + std::to_string(j) + "]";
        const io::json& condition = list[j];
        if (!condition.is_object() || !condition.contains("expression") || !condition.at("expression").is_string() ||
            !condition.contains("equals") || !condition.at("equals").is_number())
          throw std::invalid_argument(where + " is not {expression, equals, unit}");
        const ex f = physical.parse(condition.at("expression").get<std::string>(), where);
        for (const auto& name : symbolic::free_symbols(f))
          if (!in_state.count(physical.get(name)) || (name == "mu" && !(mu > 0)))
            throw std::invalid_argument(where + ": '" + name + "' is not a quantity of the state here");
        const ex row = f.subs(in_state) - condition.at("equals").get<double>();
        rows.value.push_back(ctx.compile(row));
        rows.gradient.emplace_back();
        for (const int s : rows.variables) rows.gradient.back().push_back(ctx.compile(row.diff(symbol_at(s))));
      }
    } catch (const std::exception& e) {
      t.error = std::string("its target cannot be read: ") + e.what();
      return t;
    }
    t.conditions = static_cast<int>(list.size());
    t.text = "the equations " + list.dump();
    t.sample = [rows](Point& p, std::mt19937_64&) { return to_zero(rows, p) <= 1e-13; };
    return t;
  }

  // The state of a slot (its index in ctx.states), and the symbol of any slot.
  int index_of(int slot) const {
    for (std::size_t i = 0; i < ctx.states.size(); ++i)
      if (ctx.slot(ctx.states[i]) == slot) return static_cast<int>(i);
    return -1;
  }
  symbol symbol_at(int slot) const {
    for (const auto& [name, s] : ctx.slots)
      if (s == slot) return GiNaC::ex_to<symbol>(ctx.sym(name));
    throw std::logic_error("no symbol at slot " + std::to_string(slot));
  }

  TargetSet target_set(const derivation::Constraint& c) const {
    const std::string kind = c.target.is_object() ? c.target.value("kind", "") : "";
    TargetSet t;
    if (kind == "fixed_state")
      t = fixed_state(c);
    else if (kind == "body" || kind == "orbit" || kind == "coasting")
      t = sourced_state(c);
    else if (kind == "orbital_elements")
      t = orbit(c);
    else if (kind == "expressions")
      t = equations(c);
    else
      t.error = c.target.is_null() ? "it has no target: copy the spec's constraint target into the derivation"
                                   : "its target kind '" + kind +
                                         "' is not one of fixed_state, body, orbit, coasting, "
                                         "orbital_elements, expressions";
    if (t.error.empty() && fixes_mass(c)) {
      const int m = slots.m;
      const auto sample = t.sample;
      t.sample = [sample, m](Point& p, std::mt19937_64& rng) {
        p[static_cast<std::size_t>(m)] = 1;
        return sample(p, rng);
      };
      ++t.conditions;
      t.text += " with the mass known (m = 1)";
    }
    return t;
  }

  // Which rows of constraint k are equalities (a bound psi_j <= 0 is the shooting's to hold).
  std::vector<std::size_t> equality_rows(const Constraint& k) const {
    std::vector<std::size_t> out;
    for (std::size_t j = 0; j < k.psi.size(); ++j)
      if (!inequality_of(names::constraint_row(k.id, j + 1))) out.push_back(j);
    return out;
  }

  // psi of constraint k (its equality rows) with their gradients in the states and its free
  // parameters.
  Rows psi_rows(const Constraint& k, const std::vector<std::size_t>& rows) const {
    Rows out;
    out.variables = slots.all();
    out.sized = out.variables.size();
    for (const auto& q : k.free_params) out.variables.push_back(ctx.slot(q));
    for (const std::size_t j : rows) {
      out.value.push_back(ctx.compile(k.psi[j]));
      out.gradient.emplace_back();
      for (const int s : out.variables) out.gradient.back().push_back(ctx.compile(k.psi[j].diff(symbol_at(s))));
    }
    return out;
  }

  // The free parameters of psi (a departure orbit's anomaly) that put the state at p on psi's zero
  // set: Gauss-Newton from a grid of starts. Returns the distance left.
  double solve_free(const Constraint& k, const Rows& rows, Point& p) const {
    if (k.free_params.empty()) return evaluate(rows, p).worst;
    double best = INFINITY;
    Point best_p = p;
    const std::size_t n = k.free_params.size(), from = rows.variables.size() - n;
    const std::size_t starts = static_cast<std::size_t>(std::pow(4, static_cast<double>(n)));
    for (std::size_t s = 0; s < starts && best > 1e-14; ++s) {
      Point q = p;
      for (std::size_t i = 0, code = s; i < n; ++i, code /= 4)
        q[static_cast<std::size_t>(rows.variables[from + i])] = M_PI / 2 * static_cast<double>(code % 4);
      const double left = to_zero(rows, q, from);
      if (left < best) {
        best = left;
        best_p = std::move(q);
      }
    }
    p = std::move(best_p);
    return best;
  }

  // The rows of constraint k (and its side conditions) against its target at random states of the
  // target's set.
  void check_target(std::size_t index) {
    const Constraint& k = ctx.constraints[index];
    const derivation::Constraint& written = ctx.doc.constraints[index];
    Check c = start("target:" + k.id, "transversality", "random_points");
    const std::string where = "constraints[" + k.id + "]";
    const TargetSet target = target_set(written);
    if (!target.error.empty()) {
      c.max_rel = 2;
      c.fail(where + ": psi cannot be checked against the target: " + target.error + ".");
      checks.push_back(c);
      return;
    }
    const std::vector<std::size_t> rows = equality_rows(k);
    const Rows psi = psi_rows(k, rows);
    std::vector<Compiled> sides;
    std::vector<std::string> side_texts;
    try {
      GiNaC::exmap to_state;
      for (const auto& s : ctx.states) to_state[ctx.sym(names::at(s, k.at))] = ctx.sym(s);
      for (std::size_t j = 0; j < written.must_be_positive.size(); ++j) {
        side_texts.push_back(written.must_be_positive[j].expression.text);
        sides.push_back(ctx.compile(
            ctx.statement(side_texts.back(), where + ".must_be_positive[" + std::to_string(j) + "]").subs(to_state)));
      }
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail(std::string(e.what()) + ".");
      checks.push_back(c);
      return;
    }
    const int expected_rows = target.conditions + static_cast<int>(k.free_params.size());
    std::uint64_t salt = 0;
    for (const char ch : k.id) salt = salt * 131 + static_cast<unsigned char>(ch);
    std::mt19937_64 rng(0xD1B54A32D192ED03ULL ^ ctx.options.seed ^ salt);
    for (std::size_t n = 0; n < ctx.points.size() && c.pass; ++n) {
      Point p = ctx.points[n];
      if (!target.sample(p, rng)) {
        c.max_rel = 2;
        c.fail(where + ": no state meeting " + target.text +
               " was found from a random one, so psi cannot be checked; "
               "state the target so that it can be met.");
        break;
      }
      const Point on_target = p;
      solve_free(k, psi, p);
      const RowsAt at = evaluate(psi, p);
      c.max_rel = std::max(c.max_rel, at.worst);
      for (std::size_t j = 0; j < rows.size() && c.pass; ++j)
        if (!(at.distance[j] <= kOffTarget))
          c.fail(where + ".psi[" + std::to_string(rows[j]) + "] = " + written.psi[rows[j]].text +
                 " is not 0 on its target, " + target.text + ": at a state there it is " + num(at.value[j]) +
                 " (the state is " + num(at.distance[j]) + " of |x| from where the row vanishes)" +
                 (k.free_params.empty() ? "" : " for every " + join(k.free_params, ", ")) +
                 "; write psi from the target's own numbers (the parameters that hold them).");
      if (!c.pass) break;
      const int rank = rank_of(at.gradient);
      if (rank < static_cast<int>(rows.size()))
        c.fail(where + ".psi has " + std::to_string(rows.size()) + " rows but only " + std::to_string(rank) +
               " are independent on its target; drop or replace the dependent ones.");
      else if (rank != expected_rows)
        c.fail(where + ".psi has " + std::to_string(rank) + " independent rows" +
               (k.free_params.empty() ? "" : " in the state and " + join(k.free_params, ", ")) + ", but " +
               target.text + " puts " + std::to_string(target.conditions) + " conditions on the state" +
               (k.free_params.empty() ? "" : " (plus one row per free parameter)") + ": psi " +
               (rank < expected_rows ? "leaves free what the target fixes" : "fixes what the target leaves free") +
               ".");
      for (std::size_t j = 0; j < sides.size() && c.pass; ++j)
        if (!(sides[j](p) > 0))
          c.fail(where + ".must_be_positive[" + std::to_string(j) + "] = " + side_texts[j] + " is " + num(sides[j](p)) +
                 " at a state on its target, " + target.text +
                 ": it must be positive there (it tells the target from its mirror).");
      if (c.pass && target.member) check_mirrors(c, k, target, psi, sides, on_target);
    }
    checks.push_back(c);
  }

  // The states psi also holds on where it is written with r, v and h (the retrograde mirror (r, -v),
  // the periapsis turned over (-r, -v), both (-r, v)): where such a state is not on the target,
  // a side condition must fail there.
  void check_mirrors(Check& c, const Constraint& k, const TargetSet& target, const Rows& psi,
                     const std::vector<Compiled>& sides, const Point& on_target) const {
    const std::vector<std::pair<std::array<double, 2>, const char*>> mirrors = {
        {{1, -1}, "(r, -v), the orbit run the other way round"},
        {{-1, -1}, "(-r, -v), the orbit turned half a revolution in its plane"},
        {{-1, 1}, "(-r, v)"}};
    for (const auto& [sign, what] : mirrors) {
      Point q = on_target;
      for (int i = 0; i < 3; ++i) {
        q[static_cast<std::size_t>(slots.r[i])] *= sign[0];
        q[static_cast<std::size_t>(slots.v[i])] *= sign[1];
      }
      if (target.member(q)) continue;
      if (!(solve_free(k, psi, q) <= kOffTarget)) continue;
      bool told_apart = false;
      for (const auto& side : sides) told_apart = told_apart || !(side(q) > 0);
      if (!told_apart) {
        c.fail("constraints[" + k.id + "]: psi and must_be_positive also hold at " + what + " of a state on " +
               target.text + ", which is not on it; add the condition that tells them apart to must_be_positive.");
        return;
      }
    }
  }

  // Each initial value (the state at t0 the program starts from) must meet psi at t0.
  void check_initial_values() {
    if (ctx.doc.initial_values.empty()) return;
    Check c = start("initial_values", "transversality", "random_points");
    std::vector<std::pair<int, Compiled>> start;  // the slot of each state given and its value
    try {
      for (const auto& v : ctx.doc.initial_values) {
        if (!ctx.slots.count(v.state) || std::find(ctx.states.begin(), ctx.states.end(), v.state) == ctx.states.end())
          throw std::invalid_argument("initial_values names '" + v.state + "', which is not a state");
        start.emplace_back(ctx.slot(v.state),
                           ctx.compile(ctx.statement(v.value.text, "initial_values[" + v.state + "]")));
      }
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail(std::string(e.what()) + ".");
      checks.push_back(c);
      return;
    }
    const auto given = [&](const std::string& state) {
      return std::any_of(start.begin(), start.end(), [&](const auto& s) { return s.first == ctx.slot(state); });
    };
    for (const auto& k : ctx.constraints) {
      if (k.at != "t0") continue;
      for (const std::size_t j : equality_rows(k)) {
        if (std::any_of(ctx.states.begin(), ctx.states.end(),
                        [&](const std::string& s) { return k.psi[j].has(ctx.sym(s)) && !given(s); }))
          continue;  // a row of a state the program does not start from (a shooting variable's)
        const Rows row = psi_rows(k, {j});
        for (const auto& p : ctx.points) {
          Point q = p;
          for (const auto& [slot, value] : start) q[static_cast<std::size_t>(slot)] = value(p);
          const RowsAt at = evaluate(row, q);
          c.max_rel = std::max(c.max_rel, at.worst);
          if (!(at.worst <= kOffTarget)) {
            c.fail("initial_values: from them constraints[" + k.id + "].psi[" + std::to_string(j) +
                   "] = " + ctx.doc.constraints[static_cast<std::size_t>(&k - ctx.constraints.data())].psi[j].text +
                   " is " + num(at.value[0]) + " at t0, not 0; each initial value must be the one psi fixes.");
            break;
          }
        }
      }
    }
    checks.push_back(c);
  }
};

}  // namespace

std::unique_ptr<Family> target_family(const Context& ctx) {
  return std::make_unique<TargetFamily>(ctx);
}

}  // namespace helios::verify::detail

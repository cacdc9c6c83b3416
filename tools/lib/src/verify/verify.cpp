#include "helios/verify/verify.hpp"

#include <ginac/ginac.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/symbolic/compare.hpp"
#include "helios/symbolic/evaluate.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::verify {
namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;
using io::json;
using symbolic::Compiled;
using symbolic::exact_equal;
using symbolic::exact_proportional;
using symbolic::kExactBudget;
using symbolic::Point;
using symbolic::print;
using symbolic::term_diagnosis;
using symbolic::tidy;
using symbolic::tree_size;

constexpr double kTol = 1e-9;           // |a - b| <= kTol (1 + max(|a|, |b|)) at every point
constexpr int kRandomDirections = 48;   // random unit vectors tried against a* at each point
constexpr int kThrottleGrid = 40;       // intervals of the grid of u in [0, 1]
constexpr int kSailCone = 12;           // cone-angle rows of the grid over the admissible hemisphere
constexpr int kSailClock = 24;          // clock-angle columns of that grid
constexpr int kRandomSailNormals = 64;  // random admissible sail normals tried against n* at each point

// ---------------------------------------------------------------------------------------------
// Small helpers

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// Relative difference in [0, 2]; 2 when a side is not finite.
double rel_diff(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return 2.0;
  return std::fabs(a - b) / (1.0 + std::max(std::fabs(a), std::fabs(b)));
}

// ---------------------------------------------------------------------------------------------

enum class Kind {
  Position,
  Velocity,
  Mass,
  OtherState,
  Costate,
  Multiplier,
  Homotopy,
  Throttle,
  Direction,
  Sail,
  Parameter,
  Sourced,  // a parameter the runtime evaluates (ephemeris, rate, coast): its value may be a placeholder
  EventValue,
  Free
};

Kind state_kind(const std::string& name, const std::string& meaning) {
  const std::string m = lower(meaning);
  if (m.find("mass") != std::string::npos || name == "m" || name == "mass") return Kind::Mass;
  if (m.find("velocity") != std::string::npos || name[0] == 'v') return Kind::Velocity;
  if (m.find("position") != std::string::npos || name == "x" || name == "y" || name == "z" ||
      (name[0] == 'r' && name.size() <= 2))
    return Kind::Position;
  return Kind::OtherState;
}

// max_rel_error as reported: 3 significant digits, and 0 below 1e-13 (agreement to rounding).
// NOTE: GiNaC orders terms by hash values, which vary between runs, so evaluations of some forms
// differ in their last bits from run to run; the report must not.
double reported(double v) {
  if (!std::isfinite(v)) return 2.0;
  if (v < 1e-13) return 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return std::strtod(buf, nullptr);
}

struct Check {
  std::string id, category, method;
  bool pass = true, exact = false;
  int points = 0;
  double max_rel = 0;
  std::string feedback;

  void fail(const std::string& why) {
    pass = false;
    exact = false;
    if (feedback.empty()) feedback = why;
  }
  json to_json() const {
    return {{"id", id},
            {"category", category},
            {"verdict", pass ? "pass" : "fail"},
            {"method", method},
            {"points", points},
            {"exact", exact},
            {"max_rel_error", reported(max_rel)},
            {"feedback", pass ? "" : feedback}};
  }
};

struct Constraint {
  std::string id, at;
  std::vector<ex> psi;                  // in the state symbols
  std::vector<std::string> multipliers;  // nu of each row, as written (may be empty)
};

struct Equation {
  std::string name, text, error;
  bool ok = false;
  ex e;
  Compiled c;
  std::vector<double> values;     // at the sample points
  std::set<std::string> symbols;  // its free symbols
};

// The expected side of an equality: its symbolic form (printed in feedback, used by the exact
// check) and a compiled form evaluated at at(point) (the point itself if `at` is empty).
struct Expected {
  ex symbolic;
  Compiled numeric;
  std::function<Point(const Point&)> at;
};

class Verifier {
 public:
  Verifier(const json& derivation, const VerifyOptions& options)
      : d_(derivation), opt_(options), rng_(0x9E3779B97F4A7C15ULL ^ options.seed) {}

  json run() {
    if (opt_.points < 1) throw std::invalid_argument("the number of sample points must be at least 1");
    read_problem();
    sample_points();
    check_hamiltonian();
    check_odes(true);
    check_odes(false);
    check_direction();
    check_sail();
    check_throttle();
    read_shooting();
    check_coast();
    check_endpoints();
    check_times();
    check_events();
    check_departure();
    check_shooting_shape();
    check_normalization();
    check_state_usage();
    return report();
  }

 private:
  const json& d_;
  VerifyOptions opt_;
  std::mt19937_64 rng_;
  symbolic::SymbolTable table_;
  std::map<std::string, int> slots_;
  std::vector<Kind> kinds_;
  std::vector<double> values_;

  std::vector<std::string> states_, costates_, directions_, sails_, parameters_;
  std::string throttle_, multiplier_, eps_;
  std::vector<std::size_t> positions_;          // indices of the position states (r-hat of the sail)
  std::map<std::string, std::string> sources_;  // parameter -> source ("ephemeris:Mars:tf", ...)
  // Free final time: tf = tf_expression(shooting variables); event values such as H_tf.
  bool free_tf_ = false;
  std::string tf_text_, tf_error_;
  ex tf_expr_;
  std::vector<std::string> tf_vars_;  // symbols of tf_expression declared by it (e.g. tf_frac)
  struct EventValue {
    std::string name, meaning;
    bool hamiltonian = false;  // H under the optimal control at `at`
    std::string at = "tf";     // t0, tf, or <event>_m / <event>_p (just before / after an interior event)
  };
  std::vector<EventValue> events_;
  // Uncontrolled dynamics of coasting targets.
  bool has_coast_ = false;
  std::vector<std::string> coast_states_;
  std::vector<ex> coast_rhs_;
  std::string coast_error_;
  std::vector<ex> grad_n_;  // dH/dn of the sail normal
  std::vector<Compiled> grad_nc_;
  std::vector<ex> f_;
  ex L_, phi_, H_;
  std::vector<Constraint> constraints_;
  Compiled Hc_;
  std::vector<ex> grad_a_;  // dH/da_j
  std::vector<Compiled> grad_ac_;
  std::vector<ex> astar_sym_;  // a* used in the exact throttle checks
  std::vector<Point> points_;
  std::vector<Check> checks_;
  std::vector<Equation> equations_;
  std::vector<std::string> variables_;

  // ----- symbols and points

  int declare(const std::string& name, Kind kind, double value = 0) {
    if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') ||
        !std::all_of(name.begin(), name.end(),
                     [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; }))
      throw input_error("derivation: '" + name + "' is not a valid symbol name");
    if (slots_.count(name)) throw input_error("derivation: the name '" + name + "' is used for two different symbols");
    table_.get(name);
    slots_[name] = static_cast<int>(kinds_.size());
    kinds_.push_back(kind);
    values_.push_back(value);
    return slots_[name];
  }
  int slot(const std::string& name) const { return slots_.at(name); }
  ex sym(const std::string& name) const { return table_.symtab().at(name); }
  Compiled compile(const ex& e) const { return Compiled(e, slots_); }
  ex statement(const json& text, const std::string& where) const {
    if (!text.is_string()) throw input_error("derivation: field " + where + " must be an expression string");
    return table_.parse(text.get<std::string>(), "derivation: " + where);
  }

  double uniform(double a, double b) { return a + (b - a) * (static_cast<double>(rng_() >> 11) * 0x1.0p-53); }
  double gaussian() {
    const double u1 = (static_cast<double>(rng_() >> 11) + 0.5) * 0x1.0p-53, u2 = uniform(0, 1);
    return std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  std::vector<double> random_unit(std::size_t n) {
    std::vector<double> v(n);
    double n2 = 0;
    do {
      n2 = 0;
      for (auto& x : v) {
        x = gaussian();
        n2 += x * x;
      }
    } while (n2 < 1e-12);
    for (auto& x : v) x /= std::sqrt(n2);
    return v;
  }
  Point set_direction(Point p, const std::vector<double>& a) const {
    for (std::size_t j = 0; j < directions_.size(); ++j) p[static_cast<std::size_t>(slot(directions_[j]))] = a[j];
    return p;
  }
  std::vector<double> direction_of(const Point& p) const {
    std::vector<double> a;
    for (const auto& name : directions_) a.push_back(p[static_cast<std::size_t>(slot(name))]);
    return a;
  }

  // The verifier's own minimizing direction a* = -g/|g|, g = dH/da with the throttle at `u`
  // (NaN: the point's own throttle); returns p with the direction controls set to it.
  Point with_direction(const Point& p, double u) const {
    if (directions_.empty()) return p;
    Point q = p;
    if (!throttle_.empty() && !std::isnan(u)) q[static_cast<std::size_t>(slot(throttle_))] = u;
    std::vector<double> g;
    double n2 = 0;
    for (const auto& c : grad_ac_) {
      g.push_back(c(q));
      n2 += g.back() * g.back();
    }
    if (!(n2 > 0) || !std::isfinite(n2)) return p;
    for (auto& x : g) x = -x / std::sqrt(n2);
    return set_direction(p, g);
  }

  // Identifiers of an expression text that are not function names.
  static std::vector<std::string> identifiers(const std::string& text) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < text.size();) {
      const auto ch = static_cast<unsigned char>(text[i]);
      if (!(std::isalpha(ch) || ch == '_') || (i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) ||
                                                         text[i - 1] == '_' || text[i - 1] == '.'))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      std::size_t k = j;
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      if (k >= text.size() || text[k] != '(') out.push_back(text.substr(i, j - i));
      i = j;
    }
    return out;
  }

  // times (free final time: tf_expression in shooting variables it introduces) and event_values.
  void read_times_and_events() {
    const json& times = d_.contains("times") && d_["times"].is_object() ? d_["times"] : json::object();
    free_tf_ = times.value("final_time", "fixed") == "free";
    if (d_.contains("event_values") && d_["event_values"].is_array())
      for (const auto& e : d_["event_values"]) {
        EventValue v;
        v.name = io::require_string(e, "name", "derivation event_values");
        v.meaning = e.value("meaning", "");
        v.hamiltonian = e.value("kind", "") == "hamiltonian";
        if (e.contains("at") && e["at"].is_string())
          v.at = e["at"].get<std::string>();
        else if (v.name.rfind("H_", 0) == 0 && v.name.size() > 2)
          v.at = v.name.substr(2);
        declare(v.name, Kind::EventValue);
        events_.push_back(v);
      }
    read_departure(times);
    if (!free_tf_) return;
    if (!times.contains("tf_expression") || !times["tf_expression"].is_string()) {
      tf_error_ = "times.tf_expression is missing: a free final time needs tf as an expression of a shooting variable";
      return;
    }
    tf_text_ = times["tf_expression"].get<std::string>();
    for (const auto& name : identifiers(tf_text_))
      if (!slots_.count(name) && name != "Pi" && name != "Euler" && name != "Catalan") {
        tf_vars_.push_back(name);
        declare(name, Kind::Free);
      }
    try {
      tf_expr_ = table_.parse(tf_text_, "times.tf_expression");
    } catch (const std::exception& e) {
      tf_error_ = e.what();
    }
    // An endpoint cost may name the final time itself (Mayer form of minimum time).
    if (!slots_.count("tf")) declare("tf", Kind::Free);
  }

  // ----- interior events and a sliding departure: reading

  // A symbol the derivation introduces (event states, multipliers, fractions): declared once.
  void declare_new(const std::string& name, Kind kind) {
    if (!slots_.count(name)) declare(name, kind);
  }
  static bool is_identifier(const std::string& s) {
    return !s.empty() && (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_') &&
           std::all_of(s.begin(), s.end(),
                       [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
  }
  // Declares the identifiers of `text` that are not symbols yet (kind Free); returns them.
  std::vector<std::string> declare_unknown(const std::string& text) {
    std::vector<std::string> out;
    for (const auto& name : identifiers(text))
      if (!slots_.count(name) && name != "Pi" && name != "Euler" && name != "Catalan" && is_identifier(name)) {
        declare(name, Kind::Free);
        out.push_back(name);
      }
    return out;
  }

  // times.departure == "free": t0 = t0_expression(t0_frac), tf = tf_expression = t0 + the fixed total time.
  void read_departure(const json& times) {
    free_t0_ = times.value("departure", "fixed") == "free";
    if (!free_t0_) return;
    try {
      for (const char* key : {"t0_expression", "tf_expression"}) {
        if (!times.contains(key) || !times[key].is_string())
          throw std::invalid_argument(std::string("times.") + key +
                                      " is missing: a sliding departure needs t0 and tf " +
                                      "as expressions of a shooting variable (t0_frac)");
        const std::string text = times[key].get<std::string>();
        for (const auto& name : declare_unknown(text)) t0_vars_.push_back(name);
        (std::string(key) == "t0_expression" ? t0_expr_ : t0_tf_expr_) =
            table_.parse(text, std::string("times.") + key);
      }
    } catch (const std::exception& e) {
      t0_error_ = e.what();
    }
  }
  bool free_t0_ = false;
  std::string t0_error_;
  ex t0_expr_, t0_tf_expr_;
  std::vector<std::string> t0_vars_;

  struct CostateEntry {
    bool given = false, is_variable = false;
    std::string variable, text;
    ex expr;
  };
  struct Event {
    std::string id, kind, error;
    std::vector<ex> psi;
    std::vector<std::string> psi_text, multiplier_text;
    std::vector<ex> map;  // state_map, in state order
    std::vector<std::string> map_text;
    std::vector<CostateEntry> costate_map;  // in state order
    std::vector<std::string> free_params;   // symbols psi or state_map introduce (Category C parameters)
    std::vector<std::string> time_vars;     // symbols time.expression introduces (the epoch's fraction)
    std::string time_text;
    ex time_expr;
    std::vector<double> window;
    std::string Hm, Hp;  // event values: H just before / just after
  };
  std::vector<Event> interior_;

  std::string before(const std::string& name, const std::string& id) const { return name + "_" + id + "_m"; }
  std::string after(const std::string& name, const std::string& id) const { return name + "_" + id + "_p"; }

  void read_interior_events() {
    if (!d_.contains("events") || !d_["events"].is_array()) return;
    std::size_t index = 0;
    for (const auto& je : d_["events"]) {
      Event e;
      e.id = je.is_object() ? je.value("id", "") : "";
      if (!is_identifier(e.id)) e.id = "#" + std::to_string(index);
      ++index;
      const std::string where = "events[" + e.id + "]";
      try {
        if (!is_identifier(e.id)) throw std::invalid_argument(where + " has no valid id");
        e.kind = je.value("kind", "");
        for (std::size_t i = 0; i < states_.size(); ++i) {
          const Kind k = kinds_[static_cast<std::size_t>(slot(states_[i]))];
          declare_new(before(states_[i], e.id), k);
          declare_new(after(states_[i], e.id), k);
          declare_new(before(costates_[i], e.id), Kind::Costate);
          declare_new(after(costates_[i], e.id), Kind::Costate);
        }
        declare_new("t_" + e.id, Kind::Free);
        for (const auto& v : events_)
          if (v.hamiltonian && v.at == e.id + "_m")
            e.Hm = v.name;
          else if (v.hamiltonian && v.at == e.id + "_p")
            e.Hp = v.name;
        const json& time = io::require(je, "time", where);
        e.time_text = io::require_string(time, "expression", where + ".time");
        e.time_vars = declare_unknown(e.time_text);
        e.time_expr = table_.parse(e.time_text, where + ".time.expression");
        if (time.contains("window") && time["window"].is_array() && time["window"].size() == 2)
          for (const auto& w : time["window"]) e.window.push_back(w.is_number() ? w.get<double>() : std::nan(""));
        const json& mult = io::require(je, "multipliers", where);
        for (const auto& m : mult) {
          e.multiplier_text.push_back(m.is_string() ? m.get<std::string>() : "");
          if (is_identifier(e.multiplier_text.back())) declare_new(e.multiplier_text.back(), Kind::Free);
        }
        const json& psi = io::require(je, "psi", where);
        for (std::size_t j = 0; j < psi.size(); ++j) {
          if (!psi[j].is_string())
            throw std::invalid_argument(where + ".psi[" + std::to_string(j) + "] is not a string");
          e.psi_text.push_back(psi[j].get<std::string>());
          for (const auto& q : declare_unknown(e.psi_text.back())) e.free_params.push_back(q);
          e.psi.push_back(table_.parse(e.psi_text.back(), where + ".psi[" + std::to_string(j) + "]"));
        }
        e.map.assign(states_.size(), ex(0));
        e.map_text.assign(states_.size(), "");
        for (const auto& m : io::require(je, "state_map", where)) {
          const std::string s = io::require_string(m, "state", where + ".state_map");
          const auto it = std::find(states_.begin(), states_.end(), s);
          if (it == states_.end()) throw std::invalid_argument(where + ".state_map names '" + s + "', not a state");
          const auto i = static_cast<std::size_t>(it - states_.begin());
          e.map_text[i] = io::require_string(m, "expression", where + ".state_map[" + s + "]");
          for (const auto& q : declare_unknown(e.map_text[i])) e.free_params.push_back(q);
          e.map[i] = table_.parse(e.map_text[i], where + ".state_map[" + s + "]");
        }
        for (std::size_t i = 0; i < states_.size(); ++i)
          if (e.map_text[i].empty())
            throw std::invalid_argument(where + ".state_map has no entry for state " + states_[i]);
        e.costate_map.assign(states_.size(), CostateEntry{});
        for (const auto& m : io::require(je, "costate_map", where)) {
          const std::string l = io::require_string(m, "costate", where + ".costate_map");
          const auto it = std::find(costates_.begin(), costates_.end(), l);
          if (it == costates_.end())
            throw std::invalid_argument(where + ".costate_map names '" + l + "', not a costate");
          CostateEntry& c = e.costate_map[static_cast<std::size_t>(it - costates_.begin())];
          c.given = true;
          if (m.contains("variable")) {
            c.is_variable = true;
            c.variable = io::require_string(m, "variable", where + ".costate_map[" + l + "]");
            if (is_identifier(c.variable)) declare_new(c.variable, Kind::Costate);
          } else {
            c.text = io::require_string(m, "expression", where + ".costate_map[" + l + "]");
            declare_unknown(c.text);
            c.expr = table_.parse(c.text, where + ".costate_map[" + l + "]");
          }
        }
      } catch (const std::exception& x) {
        e.error = x.what();
      }
      interior_.push_back(e);
    }
  }

  // coast_dynamics: the state symbols of the coasting target and their uncontrolled dynamics.
  void read_coast() {
    if (!d_.contains("coast_dynamics")) return;
    has_coast_ = true;
    const json& c = d_["coast_dynamics"];
    try {
      if (!c.is_object() || !c.contains("states") || !c["states"].is_array() || !c.contains("rhs") ||
          !c["rhs"].is_array())
        throw std::invalid_argument("coast_dynamics must have arrays states and rhs");
      std::vector<std::size_t> rv;
      for (std::size_t i = 0; i < states_.size(); ++i) {
        const Kind k = kinds_[static_cast<std::size_t>(slot(states_[i]))];
        if (k == Kind::Position || k == Kind::Velocity) rv.push_back(i);
      }
      for (std::size_t i = 0; i < c["states"].size(); ++i) {
        const std::string name = c["states"][i].is_string() ? c["states"][i].get<std::string>() : "";
        const Kind k = i < rv.size() ? kinds_[static_cast<std::size_t>(slot(states_[rv[i]]))] : Kind::Free;
        // The coast states may reuse the problem's own r, v names (same order), or be new symbols.
        if (!(i < rv.size() && name == states_[rv[i]])) {
          if (slots_.count(name))
            throw std::invalid_argument("coast_dynamics.states: '" + name + "' is already a symbol of the problem");
          declare(name, k);
        }
        coast_states_.push_back(name);
      }
      for (std::size_t i = 0; i < c["rhs"].size(); ++i)
        coast_rhs_.push_back(statement(c["rhs"][i], "coast_dynamics.rhs[" + std::to_string(i) + "]"));
    } catch (const std::exception& e) {
      coast_error_ = e.what();
    }
  }

  // ----- the sail normal n: |n| = 1, n.r_hat >= 0

  using Vec3 = std::array<double, 3>;
  static double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  Vec3 r_hat(const Point& p) const {
    Vec3 r{};
    for (std::size_t k = 0; k < 3; ++k) r[k] = p[static_cast<std::size_t>(slot(states_[positions_[k]]))];
    const double n = std::sqrt(dot(r, r));
    for (auto& x : r) x /= n;
    return r;
  }
  Point set_sail(Point p, const Vec3& n) const {
    for (std::size_t k = 0; k < 3; ++k) p[static_cast<std::size_t>(slot(sails_[k]))] = n[k];
    return p;
  }
  Vec3 sail_of(const Point& p) const {
    Vec3 n{};
    for (std::size_t k = 0; k < 3; ++k) n[k] = p[static_cast<std::size_t>(slot(sails_[k]))];
    return n;
  }
  Vec3 random_admissible(const Point& p) {
    const Vec3 rh = r_hat(p);
    const auto u = random_unit(3);
    Vec3 n{u[0], u[1], u[2]};
    const double c = dot(n, rh);
    if (c < 0)
      for (std::size_t k = 0; k < 3; ++k) n[k] -= 2 * c * rh[k];
    return n;
  }
  // n = cos(theta) r_hat + sin(theta) (cos(phi) e1 + sin(phi) e2), theta in [0, pi/2].
  struct SailFrame {
    Vec3 r, e1, e2;
    Vec3 at(double theta, double phi) const {
      Vec3 n{};
      for (std::size_t k = 0; k < 3; ++k)
        n[k] = std::cos(theta) * r[k] + std::sin(theta) * (std::cos(phi) * e1[k] + std::sin(phi) * e2[k]);
      return n;
    }
  };
  SailFrame sail_frame(const Point& p) const {
    SailFrame f;
    f.r = r_hat(p);
    const std::size_t k = std::fabs(f.r[0]) < 0.6 ? 0 : (std::fabs(f.r[1]) < 0.6 ? 1 : 2);
    Vec3 t{};
    t[k] = 1;
    const double c = dot(t, f.r);
    for (std::size_t j = 0; j < 3; ++j) f.e1[j] = t[j] - c * f.r[j];
    const double n = std::sqrt(dot(f.e1, f.e1));
    for (auto& x : f.e1) x /= n;
    f.e2 = {f.r[1] * f.e1[2] - f.r[2] * f.e1[1], f.r[2] * f.e1[0] - f.r[0] * f.e1[2],
            f.r[0] * f.e1[1] - f.r[1] * f.e1[0]};
    return f;
  }

  // The verifier's own minimizer of H over the admissible hemisphere, found numerically (a grid
  // in cone and clock angle, then a shrinking pattern search): it knows nothing of a closed form.
  Vec3 optimal_sail(const Point& p) const {
    const SailFrame f = sail_frame(p);
    const double half_pi = 1.5707963267948966, two_pi = 6.283185307179586;
    auto h = [&](double theta, double phi) {
      theta = std::clamp(theta, 0.0, half_pi);
      return Hc_(set_sail(p, f.at(theta, phi)));
    };
    // Grid rows: uniform in the cone angle, plus rows closing in on the rim geometrically (a
    // minimum next to the rim sits in a thin sliver a uniform grid can miss).
    std::vector<double> rows;
    for (int i = 1; i <= kSailCone; ++i) rows.push_back(half_pi * i / kSailCone);
    for (int k = 5; k <= 17; k += 3) rows.push_back(half_pi * (1 - std::ldexp(1.0, -k)));
    struct Start {
      double h, t, p;
    };
    std::vector<Start> grid{{h(0, 0), 0, 0}};
    for (double t : rows)
      for (int j = 0; j < kSailClock; ++j) grid.push_back({h(t, two_pi * j / kSailClock), t, two_pi * j / kSailClock});
    std::sort(grid.begin(), grid.end(), [](const Start& a, const Start& b) { return a.h < b.h; });
    Vec3 best{};
    double best_h = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s < std::min<std::size_t>(3, grid.size()); ++s) {
      double bt = grid[s].t, bp = grid[s].p, bh = grid[s].h;
      double step_t = std::max(1e-4, std::min(half_pi / kSailCone, (half_pi - bt) / 2)), step_p = two_pi / kSailClock;
      while (step_t > 1e-9) {
        bool moved = false;
        for (const auto& [dt, dp] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}) {
          const double t = std::clamp(bt + dt * step_t, 0.0, half_pi), ph = bp + dp * step_p, v = h(t, ph);
          if (v < bh) {
            bh = v;
            bt = t;
            bp = ph;
            moved = true;
          }
        }
        if (!moved) {
          step_t /= 2;
          step_p /= 2;
        }
      }
      const Vec3 n = polish_sail(p, f.at(bt, bp));
      const double hn = Hc_(set_sail(p, n));
      if (hn < best_h) {
        best_h = hn;
        best = n;
      }
    }
    return best;
  }

  // Relative norm of the part of dH/dn tangent to the unit sphere at n (0 at an interior optimum).
  double sail_tangential(const Point& p, const Vec3& n) const {
    const Point q = set_sail(p, n);
    const Vec3 g{grad_nc_[0](q), grad_nc_[1](q), grad_nc_[2](q)};
    const double gn = dot(g, n);
    Vec3 t{};
    for (std::size_t k = 0; k < 3; ++k) t[k] = g[k] - gn * n[k];
    return std::isfinite(gn) ? std::sqrt(dot(t, t)) / (1 + std::sqrt(dot(g, g))) : 2.0;
  }

  // Comparing values of H finds n* only to ~sqrt(machine epsilon); Newton on the tangential part
  // of dH/dn (zero at an interior minimum) brings it to full precision.
  Vec3 polish_sail(const Point& p, Vec3 n) const {
    const Vec3 rh = r_hat(p);
    if (dot(n, rh) < 1e-3) return n;  // on (or next to) the rim: no stationarity to solve
    auto unit = [](Vec3 v) {
      const double l = std::sqrt(dot(v, v));
      for (auto& x : v) x /= l;
      return v;
    };
    const double h0 = Hc_(set_sail(p, n));
    Vec3 best = n;
    for (int it = 0; it < 6; ++it) {
      // Tangent basis at n, and F(s, t) = tangential gradient at unit(n + s b1 + t b2) on (b1, b2).
      Vec3 b1{}, b2{};
      const Vec3 seed = std::fabs(n[0]) < 0.6 ? Vec3{1, 0, 0} : (std::fabs(n[1]) < 0.6 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
      const double c = dot(seed, n);
      for (std::size_t k = 0; k < 3; ++k) b1[k] = seed[k] - c * n[k];
      b1 = unit(b1);
      b2 = {n[1] * b1[2] - n[2] * b1[1], n[2] * b1[0] - n[0] * b1[2], n[0] * b1[1] - n[1] * b1[0]};
      auto F = [&](double s, double t) {
        Vec3 m{};
        for (std::size_t k = 0; k < 3; ++k) m[k] = n[k] + s * b1[k] + t * b2[k];
        m = unit(m);
        const Point q = set_sail(p, m);
        const Vec3 g{grad_nc_[0](q), grad_nc_[1](q), grad_nc_[2](q)};
        const double gm = dot(g, m);
        return std::array<double, 2>{dot(g, b1) - gm * dot(m, b1), dot(g, b2) - gm * dot(m, b2)};
      };
      const auto F0 = F(0, 0);
      if (std::fabs(F0[0]) + std::fabs(F0[1]) < 1e-15) break;
      const double e = 1e-7;
      const auto Fs = F(e, 0), Ft = F(0, e);
      const double j11 = (Fs[0] - F0[0]) / e, j21 = (Fs[1] - F0[1]) / e, j12 = (Ft[0] - F0[0]) / e,
                   j22 = (Ft[1] - F0[1]) / e, det = j11 * j22 - j12 * j21;
      if (!(std::fabs(det) > 0) || !std::isfinite(det)) break;
      const double ds = -(j22 * F0[0] - j12 * F0[1]) / det, dt = -(-j21 * F0[0] + j11 * F0[1]) / det;
      if (std::fabs(ds) + std::fabs(dt) > 0.1) break;
      Vec3 m{};
      for (std::size_t k = 0; k < 3; ++k) m[k] = n[k] + ds * b1[k] + dt * b2[k];
      n = unit(m);
    }
    // Keep the polished point only if it is admissible and no worse than the search's.
    const double h1 = Hc_(set_sail(p, n));
    if (dot(n, rh) >= 0 && std::isfinite(h1) && h1 <= h0 + 1e-12 * (1 + std::fabs(h0))) best = n;
    return best;
  }

  // p with the controls at the verifier's own optimum: a* = -g/|g|, n* numerically, and (with
  // `throttle`) u* minimizing H over [0, 1] (grid, then golden section).
  Point optimal_controls(const Point& p, bool throttle) const {
    Point q = p;
    if (!sails_.empty()) q = set_sail(q, optimal_sail(q));
    if (throttle && !throttle_.empty()) {
      const auto us = static_cast<std::size_t>(slot(throttle_));
      auto h = [&](double u) {
        Point r = q;
        r[us] = u;
        return Hc_(with_direction(r, u));
      };
      int best = 0;
      for (int k = 1; k <= kThrottleGrid; ++k)
        if (h(static_cast<double>(k) / kThrottleGrid) < h(static_cast<double>(best) / kThrottleGrid)) best = k;
      double a = std::max(0, best - 1) / static_cast<double>(kThrottleGrid);
      double b = std::min(kThrottleGrid, best + 1) / static_cast<double>(kThrottleGrid);
      const double g = 0.6180339887498949;
      for (int it = 0; it < 80 && b - a > 1e-13; ++it) {
        const double x1 = b - g * (b - a), x2 = a + g * (b - a);
        if (h(x1) <= h(x2))
          b = x2;
        else
          a = x1;
      }
      double u = 0.5 * (a + b);
      for (double end : {0.0, 1.0})
        if (h(end) <= h(u)) u = end;
      q[us] = u;
      return with_direction(q, u);
    }
    return with_direction(q, std::nan(""));
  }

  // The point as seen at tf: states and costates take their _tf values, controls their optimum.
  Point at_tf(const Point& p) const {
    Point q = p;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      q[static_cast<std::size_t>(slot(states_[i]))] = p[static_cast<std::size_t>(slot(states_[i] + "_tf"))];
      q[static_cast<std::size_t>(slot(costates_[i]))] = p[static_cast<std::size_t>(slot(costates_[i] + "_tf"))];
    }
    return optimal_controls(q, true);
  }

  // The point as seen at `label` (t0, tf, <event>_m, <event>_p): states and costates take their
  // values there (where the derivation has such symbols), controls their optimum.
  Point at_label(const Point& p, const std::string& label) const {
    if (label == "tf") return at_tf(p);
    Point q = p;
    for (std::size_t i = 0; i < states_.size(); ++i)
      for (const auto* name : {&states_[i], &costates_[i]}) {
        const auto it = slots_.find(*name + "_" + label);
        if (it != slots_.end()) q[static_cast<std::size_t>(slot(*name))] = p[static_cast<std::size_t>(it->second)];
      }
    return optimal_controls(q, true);
  }

  // control_law.sail.definitions: named intermediate expressions (e.g. sail_A, sail_B, sail_alpha),
  // each in the problem's symbols and the earlier definitions; the sail law is read with them inlined.
  void read_sail_definitions() {
    if (!d_.contains("control_law") || !d_["control_law"].is_object() || !d_["control_law"].contains("sail") ||
        !d_["control_law"]["sail"].is_object() || !d_["control_law"]["sail"].contains("definitions"))
      return;
    try {
      const json& defs = d_["control_law"]["sail"]["definitions"];
      if (!defs.is_array()) throw std::invalid_argument("control_law.sail.definitions must be an array");
      for (const auto& def : defs) {
        const std::string name = def.is_object() ? def.value("name", "") : "";
        const std::string where = "control_law.sail.definitions[" + name + "]";
        if (slots_.count(name)) throw std::invalid_argument(where + ": the name is already a symbol of the problem");
        const ex e = statement(def.is_object() && def.contains("expression") ? def["expression"] : json(), where);
        declare(name, Kind::Free);
        sail_definitions_[sym(name)] = e.subs(sail_definitions_);
      }
    } catch (const std::exception& e) {
      sail_definitions_error_ = e.what();
    }
  }
  GiNaC::exmap sail_definitions_;
  std::string sail_definitions_error_;

  void read_problem() {
    const json& d = d_;
    if (!d.is_object()) throw input_error("derivation: not a JSON object");
    const json& states = io::require(d, "states", "derivation");
    const json& controls = io::require(d, "controls", "derivation");
    const json& parameters = io::require(d, "parameters", "derivation");
    multiplier_ = io::require_string(d, "multiplier", "derivation");
    eps_ = io::require_string(io::require(d, "homotopy", "derivation"), "symbol", "derivation homotopy");
    if (!states.is_array() || states.empty()) throw input_error("derivation: field states must be a non-empty array");
    for (const auto& s : states) {
      const std::string name = io::require_string(s, "name", "derivation states");
      states_.push_back(name);
      costates_.push_back(io::require_string(s, "costate", "derivation state " + name));
      const Kind k = state_kind(name, s.value("meaning", ""));
      declare(name, k);
      declare(name + "_t0", k);
      declare(name + "_tf", k);
    }
    for (const auto& c : costates_) {
      declare(c, Kind::Costate);
      declare(c + "_t0", Kind::Costate);
      declare(c + "_tf", Kind::Costate);
    }
    for (const auto& c : controls) {
      const std::string name = io::require_string(c, "name", "derivation controls");
      const std::string kind = io::require_string(c, "kind", "derivation control " + name);
      if (kind == "throttle") {
        if (!throttle_.empty())
          throw input_error("derivation: more than one throttle control (" + throttle_ + ", " + name + ")");
        throttle_ = name;
        declare(name, Kind::Throttle);
      } else if (kind == "direction") {
        directions_.push_back(name);
        declare(name, Kind::Direction);
      } else if (kind == "sail_normal") {
        sails_.push_back(name);
        declare(name, Kind::Sail);
      } else {
        throw input_error("derivation: control " + name + " has unknown kind '" + kind + "'");
      }
    }
    for (std::size_t i = 0; i < states_.size(); ++i)
      if (kinds_[static_cast<std::size_t>(slot(states_[i]))] == Kind::Position) positions_.push_back(i);
    if (!sails_.empty() && (sails_.size() != 3 || positions_.size() != 3))
      throw input_error(
          "derivation: a sail normal needs three controls of kind sail_normal and three position states, got " +
          std::to_string(sails_.size()) + " and " + std::to_string(positions_.size()));
    for (const auto& p : parameters) {
      const std::string name = io::require_string(p, "name", "derivation parameters");
      parameters_.push_back(name);
      const bool sourced = p.contains("source") && p["source"].is_string();
      declare(name, sourced ? Kind::Sourced : Kind::Parameter,
              io::require_number(p, "value", "derivation parameter " + name));
      if (sourced) sources_[name] = p["source"].get<std::string>();
    }
    declare(multiplier_, Kind::Multiplier);
    declare(eps_, Kind::Homotopy);
    read_times_and_events();
    if (d.contains("constraints") && d["constraints"].is_array())
      for (const auto& c : d["constraints"])
        if (c.contains("multipliers") && c["multipliers"].is_array())
          for (const auto& m : c["multipliers"])
            if (m.is_string() && !slots_.count(m.get<std::string>())) declare(m.get<std::string>(), Kind::Free);
    read_interior_events();

    // The problem statement: dynamics, costs, endpoint constraints.
    const json& dyn = io::require(d, "dynamics", "derivation");
    const json& rhs = io::require(dyn, "state_rhs", "derivation dynamics");
    if (!rhs.is_array() || rhs.size() != states_.size())
      throw input_error("derivation: dynamics.state_rhs must have one expression per state (" +
                        std::to_string(states_.size()) + ")");
    for (std::size_t i = 0; i < rhs.size(); ++i)
      f_.push_back(statement(rhs[i], "dynamics.state_rhs[" + states_[i] + "]"));
    L_ = statement(io::require(dyn, "running_cost", "derivation dynamics"), "dynamics.running_cost");
    phi_ = statement(io::require(dyn, "endpoint_cost", "derivation dynamics"), "dynamics.endpoint_cost");
    GiNaC::exmap tf_to_state;  // an endpoint cost written in x_tf is read in x
    for (const auto& s : states_) tf_to_state[sym(s + "_tf")] = sym(s);
    phi_ = phi_.subs(tf_to_state);
    if (d.contains("constraints")) {
      for (const auto& c : d["constraints"]) {
        Constraint k;
        k.id = io::require_string(c, "id", "derivation constraints");
        k.at = io::require_string(c, "at", "derivation constraint " + k.id);
        if (k.at != "t0" && k.at != "tf")
          throw input_error("derivation: constraint " + k.id + " is at '" + k.at + "', expected t0 or tf");
        GiNaC::exmap to_state;
        for (const auto& s : states_) to_state[sym(s + "_" + k.at)] = sym(s);
        const json& psi = io::require(c, "psi", "derivation constraint " + k.id);
        for (std::size_t j = 0; j < psi.size(); ++j)
          k.psi.push_back(statement(psi[j], "constraints[" + k.id + "].psi[" + std::to_string(j) + "]").subs(to_state));
        for (const auto& m : c.value("multipliers", json::array()))
          k.multipliers.push_back(m.is_string() ? m.get<std::string>() : "");
        constraints_.push_back(k);
      }
    }

    read_coast();
    read_sail_definitions();

    H_ = sym(multiplier_) * L_;
    for (std::size_t i = 0; i < states_.size(); ++i) H_ += sym(costates_[i]) * f_[i];
    Hc_ = compile(H_);
    for (const auto& a : directions_) {
      grad_a_.push_back(H_.diff(GiNaC::ex_to<symbol>(sym(a))));
      grad_ac_.push_back(compile(grad_a_.back()));
    }
    for (const auto& n : sails_) {
      grad_n_.push_back(H_.diff(GiNaC::ex_to<symbol>(sym(n))));
      grad_nc_.push_back(compile(grad_n_.back()));
    }
    // Until the derivation's own law is verified, exact checks use a* = -g/|g| at full thrust.
    ex norm2 = 0;
    std::vector<ex> g;
    for (const auto& gj : grad_a_) {
      g.push_back(throttle_.empty() ? gj : gj.subs(sym(throttle_) == 1));
      norm2 += GiNaC::pow(g.back(), 2);
    }
    for (const auto& gj : g) astar_sym_.push_back(-gj / GiNaC::sqrt(norm2));
  }

  void sample_points() {
    std::vector<Compiled> statement;
    statement.push_back(compile(L_));
    for (const auto& fi : f_) statement.push_back(compile(fi));
    statement.push_back(Hc_);
    for (const auto& c : grad_ac_) statement.push_back(c);
    for (const auto& c : grad_nc_) statement.push_back(c);
    const int max_draws = 200 * opt_.points;
    for (int draw = 0; draw < max_draws && static_cast<int>(points_.size()) < opt_.points; ++draw) {
      Point p(values_.size());
      for (std::size_t i = 0; i < p.size(); ++i) {
        switch (kinds_[i]) {
          case Kind::Position:
            p[i] = (uniform(0, 1) < 0.5 ? -1 : 1) * uniform(0.5, 2);
            break;
          case Kind::Velocity:
            p[i] = uniform(-2, 2);
            break;
          case Kind::Mass:
            p[i] = uniform(0.3, 1);
            break;
          case Kind::OtherState:
            p[i] = uniform(0.5, 1.5);
            break;
          case Kind::Costate:
            p[i] = uniform(-1, 1);
            break;
          case Kind::Multiplier:
            p[i] = uniform(0.1, 1);
            break;
          case Kind::Homotopy:
            p[i] = uniform(0.05, 1);
            break;
          case Kind::Throttle:
            p[i] = uniform(0, 1);
            break;
          case Kind::Direction:
          case Kind::Sail:
          case Kind::EventValue:
            p[i] = 0;
            break;
          case Kind::Parameter:
            p[i] = values_[i];
            break;
          case Kind::Sourced:
            p[i] = (uniform(0, 1) < 0.5 ? -1 : 1) * uniform(0.5, 1.5);
            break;
          case Kind::Free:
            p[i] = uniform(-1, 1);
            break;
        }
      }
      if (!directions_.empty()) p = set_direction(p, random_unit(directions_.size()));
      if (!sails_.empty()) p = set_sail(p, random_admissible(p));
      bool finite = true;
      for (const auto& c : statement) finite = finite && std::isfinite(c(p));
      if (!finite) continue;
      // Event values are what the runtime evaluates: H_tf is H at the _tf values, optimal controls;
      // H_t0 at the _t0 values, H_<id>_m / H_<id>_p at the states and costates around an event.
      for (const auto& v : events_)
        if (v.hamiltonian) {
          const double h = Hc_(at_label(p, v.at));
          if (!std::isfinite(h)) finite = false;
          p[static_cast<std::size_t>(slot(v.name))] = h;
        }
      if (finite) points_.push_back(std::move(p));
    }
    if (points_.empty() || static_cast<int>(points_.size()) < opt_.points)
      throw std::domain_error(
          "derivation: the dynamics and running cost are not finite at random points of the state space");
  }

  Check start(const std::string& id, const std::string& category, const std::string& method) const {
    Check c;
    c.id = id;
    c.category = category;
    c.method = method;
    c.points = method == "structural" ? 0 : static_cast<int>(points_.size());
    return c;
  }

  // ----- equality of a derivation's expression with the recomputed one

  Check equality(const std::string& id, const std::string& category, const std::string& label,
                 const std::string& expected_name, const Expected& expected, const json& given_text, bool diagnose,
                 const std::vector<std::string>& forbidden = {}) const {
    Check c = start(id, category, "random_points+exact");
    ex given;
    Compiled gc;
    try {
      if (!given_text.is_string()) throw std::invalid_argument(label + ": not an expression string");
      given = table_.parse(given_text.get<std::string>(), label);
      gc = compile(given);
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail(std::string(e.what()) + "; expected " + expected_name + " = " + print(tidy(expected.symbolic)) + ".");
      return c;
    }
    double worst = -1, we = 0, wg = 0;
    bool negated = true;
    for (const auto& p : points_) {
      const double e = expected.numeric(expected.at ? expected.at(p) : p), g = gc(p);
      const double r = rel_diff(e, g);
      if (r > worst) {
        worst = r;
        we = e;
        wg = g;
      }
      if (rel_diff(e, -g) > kTol) negated = false;
    }
    c.max_rel = worst;
    c.exact = exact_equal(expected.symbolic, given);
    c.pass = worst <= kTol || c.exact;
    if (c.pass) return c;
    std::vector<std::string> diag;
    std::vector<std::string> bad;
    for (const auto& name : forbidden)
      if (slots_.count(name) && given.has(sym(name))) bad.push_back(name);
    if (!bad.empty()) diag.push_back("it must not depend on " + join(bad, ", "));
    if (negated) {
      diag.push_back("the sign of the whole expression is flipped");
    } else if (diagnose) {
      const std::string t = term_diagnosis(expected.symbolic, given);
      if (!t.empty()) diag.push_back(t);
    }
    c.fail(label + ": expected " + expected_name + " = " + print(tidy(expected.symbolic)) + ", got " +
           given_text.get<std::string>() + (diag.empty() ? "" : "; " + join(diag, "; ")) + " (relative difference " +
           num(worst) + " at a sample point: " + num(we) + " expected, " + num(wg) + " given).");
    return c;
  }

  void check_hamiltonian() {
    const std::string sum =
        join(std::vector<std::string>{multiplier_ + "*running_cost", "sum of costate*state_rhs"}, " + ");
    const json text = d_.contains("hamiltonian") ? d_["hamiltonian"] : json();
    checks_.push_back(equality("hamiltonian", "hamiltonian", "hamiltonian", sum, {H_, Hc_, {}}, text, true));
  }

  // State ODEs (dH/dl_i) or costate ODEs (-dH/dx_i), one per state, in state order.
  void check_odes(bool state) {
    const std::string field = state ? "state_odes" : "costate_odes", key = state ? "state" : "costate";
    const json empty = json::array();
    const json& list = d_.contains(field) && d_[field].is_array() ? d_[field] : empty;
    std::set<std::string> known;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const std::string name = state ? states_[i] : costates_[i];
      known.insert(name);
      const std::string by = state ? costates_[i] : states_[i];
      const ex expected =
          state ? H_.diff(GiNaC::ex_to<symbol>(sym(by))) : (-H_.diff(GiNaC::ex_to<symbol>(sym(by)))).expand();
      const std::string expected_name = std::string(state ? "dH/d" : "-dH/d") + by;
      const std::string id = std::string(state ? "state_ode:" : "costate_ode:") + name;
      const std::string category = state ? "state_odes" : "costate_odes";
      const json* entry = nullptr;
      std::string order;
      if (i < list.size() && list[i].is_object() && list[i].value(key, "") == name) {
        entry = &list[i];
      } else {
        for (std::size_t k = 0; k < list.size() && !entry; ++k)
          if (list[k].is_object() && list[k].value(key, "") == name) {
            entry = &list[k];
            order = field + "[" + std::to_string(k) + "] is the equation of " + name + " but must be entry " +
                    std::to_string(i) + " (the order of states)";
          }
      }
      if (!entry) {
        Check c = start(id, category, "random_points+exact");
        c.max_rel = 2;
        c.fail(field + " has no equation for " + name + ": expected " + expected_name + " = " + print(expected) + ".");
        checks_.push_back(c);
        continue;
      }
      const json given_text = entry->contains("rhs") ? (*entry)["rhs"] : json();
      // A right-hand side with the optimal control substituted (no control symbols left) is
      // compared with the expected one at the verifier's own optimal controls: at the optimum
      // both are the same function (envelope theorem).
      std::function<Point(const Point&)> at;
      ex given;
      bool parsed = false;
      try {
        given = statement(given_text, field + "[" + name + "]");
        parsed = true;
      } catch (const std::exception&) {
      }
      if (parsed) {
        bool dropped = false, throttle_dropped = false;
        for (const auto* list : {&directions_, &sails_})
          for (const auto& u : *list) dropped = dropped || (expected.has(sym(u)) && !given.has(sym(u)));
        if (!throttle_.empty()) throttle_dropped = expected.has(sym(throttle_)) && !given.has(sym(throttle_));
        if (dropped || throttle_dropped)
          at = [this, throttle_dropped](const Point& p) { return optimal_controls(p, throttle_dropped); };
      }
      Check c = equality(id, category, field + "[" + name + "]", expected_name, {expected, compile(expected), at},
                         given_text, true);
      if (!c.pass && !state && parsed && !at && c.feedback.find("whole expression is flipped") == std::string::npos) {
        const std::string j = jacobian_diagnosis(i, given);
        if (!j.empty()) c.feedback += " " + j;
      }
      if (!order.empty() && c.pass) c.fail(order + ".");
      checks_.push_back(c);
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string name = list[k].is_object() ? list[k].value(key, "") : "";
      if (known.count(name)) continue;
      Check c =
          start(std::string(state ? "state_ode:" : "costate_ode:") + (name.empty() ? "#" + std::to_string(k) : name),
                state ? "state_odes" : "costate_odes", "structural");
      c.fail(field + "[" + std::to_string(k) + "] is for '" + name + "', which is not a " + key +
             " of this problem; remove it.");
      checks_.push_back(c);
    }
  }

  // Which block of -dH/dx_i = -lambda0 dL/dx_i - sum_j lambda_j df_j/dx_i a wrong costate
  // equation gets wrong: its coefficient of each multiplier against the Jacobian entry.
  std::string jacobian_diagnosis(std::size_t i, const ex& given) const {
    const symbol& x = GiNaC::ex_to<symbol>(sym(states_[i]));
    std::vector<std::string> parts;
    for (std::size_t j = 0; j <= states_.size(); ++j) {
      const bool cost = j == states_.size();
      const std::string lname = cost ? multiplier_ : costates_[j];
      const symbol& l = GiNaC::ex_to<symbol>(sym(lname));
      const ex want = -(cost ? L_ : f_[j]).diff(x), got = given.diff(l);
      const Compiled wc = compile(want), gc = compile(got);
      double worst = 0;
      for (const auto& p : points_) worst = std::max(worst, rel_diff(wc(p), gc(p)));
      if (worst <= 1e-7) continue;
      const std::string entry = cost ? "dynamics.running_cost" : "dynamics.state_rhs[" + states_[j] + "]";
      const ex miss = tidy((want - got).expand());
      const std::string miss_text = print(miss);
      std::string part = "its coefficient of " + lname + " must be -d(" + entry + ")/d" + states_[i];
      if (got.expand().is_zero())
        part += ", but " + lname + " is missing altogether";
      else if (miss_text.size() <= 240)
        part += ", and it misses " + lname + "*(" + miss_text + ")";
      parts.push_back(part + " (the Jacobian entry d" + (cost ? "L" : states_[j] + "'") + "/d" + states_[i] + ")");
    }
    if (parts.empty()) return "";
    return "In costate_odes[" + costates_[i] + "]: " + join(parts, "; ") + ".";
  }

  std::string gradient_text() const {
    std::vector<std::string> g;
    for (const auto& e : grad_a_) g.push_back(print(e));
    return "(" + join(g, ", ") + ")";
  }

  void check_direction() {
    if (directions_.empty()) return;
    Check c = start("control_direction", "control", "random_points+exact");
    const std::string names = "(" + join(directions_, ", ") + ")";
    const std::string advice = "a* = -g/|g| with g = dH/da = " + gradient_text() + " minimizes H over unit vectors";
    const json* dir = nullptr;
    if (d_.contains("control_law") && d_["control_law"].is_object() && d_["control_law"].contains("direction"))
      dir = &d_["control_law"]["direction"];
    if (!dir || !dir->is_object()) {
      c.fail("control_law.direction is missing: give the law of the thrust direction " + names + "; " + advice + ".");
      checks_.push_back(c);
      return;
    }
    const json controls = dir->value("controls", json::array());
    std::vector<std::string> listed;
    for (const auto& x : controls) listed.push_back(x.is_string() ? x.get<std::string>() : x.dump());
    if (listed != directions_) {
      c.fail("control_law.direction.controls is (" + join(listed, ", ") + "), expected " + names +
             " (the controls of kind direction, in order).");
      checks_.push_back(c);
      return;
    }
    const json law_text = dir->value("law", json::array());
    if (!law_text.is_array() || law_text.size() != directions_.size()) {
      c.fail("control_law.direction.law must give one expression per direction control " + names + "; " + advice + ".");
      checks_.push_back(c);
      return;
    }
    std::vector<ex> law;
    std::vector<Compiled> lc;
    try {
      for (std::size_t j = 0; j < directions_.size(); ++j) {
        const std::string where = "control_law.direction.law[" + directions_[j] + "]";
        if (!law_text[j].is_string()) throw std::invalid_argument(where + ": not an expression string");
        law.push_back(table_.parse(law_text[j].get<std::string>(), where));
        for (const auto& a : directions_)
          if (law.back().has(sym(a))) throw std::invalid_argument(where + " depends on the direction control " + a);
        lc.push_back(compile(law.back()));
      }
    } catch (const std::exception& e) {
      c.fail(std::string(e.what()) + "; " + advice + ".");
      checks_.push_back(c);
      return;
    }
    std::mt19937_64 saved = rng_;
    rng_.seed(0xD1B54A32D192ED03ULL ^ opt_.seed);
    double unit_err = 0, flip = 0, worse = 0;
    std::string unit_msg, flip_msg, worse_msg;
    for (const auto& p : points_) {
      std::vector<double> A;
      double n2 = 0;
      for (const auto& f : lc) {
        A.push_back(f(p));
        n2 += A.back() * A.back();
      }
      const double ue = rel_diff(std::sqrt(n2), 1.0);
      if (ue > unit_err) {
        unit_err = ue;
        unit_msg = "control_law.direction.law is not a unit vector: |a*| = " + num(std::sqrt(n2)) +
                   " at a sample point; " + advice + ".";
      }
      const double hA = Hc_(set_direction(p, A));
      auto compare = [&](const std::vector<double>& b, bool is_flip) {
        const double hb = Hc_(set_direction(p, b));
        const double v = std::isfinite(hA) ? (hA - hb) / (1 + std::max(std::fabs(hA), std::fabs(hb))) : 2.0;
        if (is_flip && v > flip) {
          flip = v;
          flip_msg = "control_law.direction.law maximizes H instead of minimizing it: H(-a*) = " + num(hb) +
                     " < H(a*) = " + num(hA) + " at a sample point (G2); flip its sign: " + advice + ".";
        } else if (!is_flip && v > worse) {
          worse = v;
          std::vector<std::string> bt;
          for (double x : b) bt.push_back(num(x));
          worse_msg = "control_law.direction.law does not minimize H over unit vectors: H(a*) = " + num(hA) +
                      " but H(a) = " + num(hb) + " for a = (" + join(bt, ", ") + ") at a sample point; " + advice + ".";
        }
      };
      std::vector<double> minus = A;
      for (auto& x : minus) x = -x;
      compare(minus, true);
      compare(direction_of(with_direction(p, std::nan(""))), false);
      for (int k = 0; k < kRandomDirections; ++k) compare(random_unit(directions_.size()), false);
    }
    rng_ = saved;
    c.max_rel = std::max({unit_err, flip, worse});
    // Exact: |a*|^2 = 1 and a* parallel to g, shown symbolically (the sign is the numeric part).
    ex n2 = 0;
    for (const auto& l : law) n2 += l * l;
    bool exact = exact_equal(n2, 1);
    for (std::size_t j = 0; exact && j < law.size(); ++j)
      for (std::size_t k = j + 1; exact && k < law.size(); ++k)
        exact = exact_equal(law[j] * grad_a_[k], law[k] * grad_a_[j]);
    if (unit_err > kTol) {
      c.fail(unit_msg);
    } else if (flip > kTol) {
      c.fail(flip_msg);
    } else if (worse > kTol) {
      c.fail(worse_msg);
    } else {
      c.exact = exact;
      astar_sym_ = law;  // verified: the exact throttle checks may use the derivation's own form
    }
    checks_.push_back(c);
  }

  std::string vec_text(const Vec3& v) const { return "(" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + ")"; }
  static double cone_of(const Vec3& n, const Vec3& r) {
    const Vec3 x{n[1] * r[2] - n[2] * r[1], n[2] * r[0] - n[0] * r[2], n[0] * r[1] - n[1] * r[0]};
    return std::atan2(std::sqrt(dot(x, x)), dot(n, r));
  }

  // The sail law: n* admissible (|n*| = 1, n*.r_hat >= 0), stationary on the unit sphere (the
  // tangential part of dH/dn vanishes, so dH/dalpha = 0 in the plane of r_hat and n*), and the
  // minimum of H over the hemisphere (against the verifier's own numerical minimizer and random
  // admissible normals). The cone angle must be the angle between n* and r_hat.
  void check_sail() {
    if (sails_.empty()) return;
    Check c = start("control_sail", "control", "random_points");
    Check ca = start("control_sail_cone_angle", "control", "random_points");
    const std::string names = "(" + join(sails_, ", ") + ")";
    const std::string set = "the admissible hemisphere |n| = 1, n.r_hat >= 0";
    const json* sail = nullptr;
    if (d_.contains("control_law") && d_["control_law"].is_object() && d_["control_law"].contains("sail"))
      sail = &d_["control_law"]["sail"];
    std::vector<Compiled> lc;
    Compiled cone;
    std::string error;
    try {
      if (!sail || !sail->is_object())
        throw std::invalid_argument("control_law.sail is missing: give the law of the sail normal " + names +
                                    " minimizing H over " + set + ", and its cone angle");
      std::vector<std::string> listed;
      for (const auto& x : sail->value("controls", json::array()))
        listed.push_back(x.is_string() ? x.get<std::string>() : x.dump());
      if (listed != sails_)
        throw std::invalid_argument("control_law.sail.controls is (" + join(listed, ", ") + "), expected " + names +
                                    " (the controls of kind sail_normal, in order)");
      const json law = sail->value("law", json::array());
      if (!law.is_array() || law.size() != 3)
        throw std::invalid_argument("control_law.sail.law must give one expression per sail control " + names);
      if (!sail_definitions_error_.empty()) throw std::invalid_argument(sail_definitions_error_);
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string where = "control_law.sail.law[" + sails_[k] + "]";
        const ex e = statement(law[k], where).subs(sail_definitions_);
        for (const auto& n : sails_)
          if (e.has(sym(n))) throw std::invalid_argument(where + " depends on the sail control " + n);
        lc.push_back(compile(e));
      }
      const ex a =
          statement(sail->contains("cone_angle") ? (*sail)["cone_angle"] : json(), "control_law.sail.cone_angle")
              .subs(sail_definitions_);
      cone = compile(a);
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (!error.empty()) {
      c.max_rel = ca.max_rel = 2;
      c.fail(error + ".");
      ca.fail(error + ".");
      checks_.push_back(c);
      checks_.push_back(ca);
      return;
    }
    std::mt19937_64 saved = rng_;
    rng_.seed(0x8CB92BA72F3D8DD7ULL ^ opt_.seed);
    double unit_err = 0, adm_err = 0, worse = 0, stat_err = 0;
    std::string unit_msg, adm_msg, worse_msg, stat_msg;
    std::vector<Vec3> laws;
    for (const auto& p : points_) {
      const Vec3 n{lc[0](p), lc[1](p), lc[2](p)}, rh = r_hat(p);
      laws.push_back(n);
      const double norm = std::sqrt(dot(n, n));
      const double ue = rel_diff(norm, 1.0);
      if (ue > unit_err) {
        unit_err = ue;
        unit_msg = "control_law.sail.law is not a unit vector: |n*| = " + num(norm) + " at a sample point.";
      }
      const double nr = dot(n, rh);
      if (std::isfinite(nr) && -nr > adm_err) {
        adm_err = -nr;
        adm_msg = "control_law.sail.law leaves the admissible set: n*.r_hat = " + num(nr) +
                  " < 0 at a sample point (the sail cannot face away from the Sun; cone angle in [0, pi/2]).";
      }
      const double hn = Hc_(set_sail(p, n));
      auto compare = [&](const Vec3& m) {
        const double hm = Hc_(set_sail(p, m));
        const double v = std::isfinite(hn) ? (hn - hm) / (1 + std::max(std::fabs(hn), std::fabs(hm))) : 2.0;
        if (v > worse) {
          worse = v;
          worse_msg = "control_law.sail.law does not minimize H over " + set +
                      ": at a sample point it gives n* = " + vec_text(n) + " (cone angle " + num(cone_of(n, rh)) +
                      " rad) with H = " + num(hn) + ", but n = " + vec_text(m) + " (cone angle " + num(cone_of(m, rh)) +
                      " rad) gives H = " + num(hm);
        }
      };
      compare(optimal_sail(p));
      for (int k = 0; k < kRandomSailNormals; ++k) compare(random_admissible(p));
      // Stationarity on the unit sphere where n* is inside the hemisphere.
      const Point q = set_sail(p, n);
      const Vec3 g{grad_nc_[0](q), grad_nc_[1](q), grad_nc_[2](q)};
      if (nr > 1e-6 && std::fabs(norm - 1) < 1e-6) {
        const double gn = dot(g, n);
        Vec3 t{};
        for (std::size_t k = 0; k < 3; ++k) t[k] = g[k] - gn * n[k];
        const double se = std::isfinite(gn) ? std::sqrt(dot(t, t)) / (1 + std::sqrt(dot(g, g))) : 2.0;
        if (se > stat_err) {
          stat_err = se;
          stat_msg =
              "control_law.sail.law is not a stationary point of H on the unit sphere: at a sample point the "
              "part of dH/dn = " +
              vec_text(g) + " tangent to the sphere at n* = " + vec_text(n) + " has norm " + num(std::sqrt(dot(t, t))) +
              " (dH/dalpha != 0 at the given cone angle); solve dH/dalpha = 0 for the cone angle alpha in the "
              "plane of r_hat and the costate direction and take the root of smallest H.";
        }
      }
    }
    rng_ = saved;
    c.max_rel = std::min(2.0, std::max({unit_err, adm_err, worse, stat_err}));
    if (unit_err > kTol) {
      c.fail(unit_msg);
    } else if (adm_err > kTol) {
      c.fail(adm_msg);
    } else if (worse > kTol) {
      c.fail(worse_msg + (stat_err <= kTol
                              ? "; the law is a stationary point of H but not its minimum (a wrong root "
                                "of dH/dalpha = 0, or a maximizer): take the root of smallest H."
                              : "; solve dH/dalpha = 0 for the cone angle and take the root of smallest H."));
    } else if (stat_err > kTol) {
      c.fail(stat_msg);
    }
    // The cone angle: against the law once verified, else against the verifier's own minimizer
    // where that is an interior stationary point resolved to full precision.
    const double tol = c.pass ? kTol : 1e-6;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Point& p = points_[i];
      const Vec3 rh = r_hat(p), n = c.pass ? laws[i] : optimal_sail(p);
      const double want = cone_of(n, rh), got = cone(p);
      const bool comparable = c.pass || (dot(n, rh) > 1e-3 && sail_tangential(p, n) < 1e-12);
      const double err = comparable ? rel_diff(got, want) : 0.0;
      ca.max_rel = std::max(ca.max_rel, err);
      if (!(got >= -kTol && got <= 1.5707963267948966 + kTol))
        ca.fail("control_law.sail.cone_angle gives " + num(got) + " rad at a sample point, outside [0, pi/2].");
      else if (err > tol)
        ca.fail("control_law.sail.cone_angle is not the angle between r_hat and the " +
                std::string(c.pass ? "sail law" : "sail normal minimizing H") + ": at a sample point it gives " +
                num(got) + " rad, expected " + num(want) + " rad.");
    }
    checks_.push_back(c);
    checks_.push_back(ca);
  }

  void check_throttle() {
    if (throttle_.empty()) return;
    const json* t = nullptr;
    if (d_.contains("control_law") && d_["control_law"].is_object() && d_["control_law"].contains("throttle") &&
        d_["control_law"]["throttle"].is_object())
      t = &d_["control_law"]["throttle"];
    if (!t) {
      Check c = start("throttle_switching", "control", "structural");
      c.fail(
          "control_law.throttle is missing: give the switching function dH/du (at eps = 0, a* substituted), "
          "dH_du_at_lower, dH_du_at_upper and the interior law of the throttle " +
          throttle_ + ".");
      checks_.push_back(c);
      return;
    }
    const symbol& u = GiNaC::ex_to<symbol>(sym(throttle_));
    const symbol& eps = GiNaC::ex_to<symbol>(sym(eps_));
    const int us = slot(throttle_), es = slot(eps_);
    GiNaC::exmap astar;
    for (std::size_t j = 0; j < directions_.size(); ++j) astar[sym(directions_[j])] = astar_sym_[j];
    const ex Hu = H_.diff(u), Huu = Hu.diff(u);
    const ex Hu_star = Hu.subs(astar);
    const Compiled Hu_c = compile(Hu), Huu_c = compile(Huu);
    auto at = [this, us, es](double uval, bool eps0) {
      return [this, us, es, uval, eps0](const Point& p) {
        Point q = with_direction(p, 1.0);
        if (!std::isnan(uval)) q[static_cast<std::size_t>(us)] = uval;
        if (eps0) q[static_cast<std::size_t>(es)] = 0;
        return q;
      };
    };
    const std::string a_note = directions_.empty() ? "" : " with a* substituted";
    std::vector<std::string> no_u_a = directions_, no_u_a_eps = directions_;
    no_u_a.push_back(throttle_);
    no_u_a_eps.push_back(throttle_);
    no_u_a_eps.push_back(eps_);
    const json none;
    auto field = [&](const char* name) -> const json& { return t->contains(name) ? (*t)[name] : none; };

    checks_.push_back(equality("throttle_switching", "control", "control_law.throttle.switching_function",
                               "dH/d" + throttle_ + " at " + eps_ + " = 0" + a_note,
                               {Hu_star.subs(GiNaC::lst{u == 0, eps == 0}), Hu_c, at(0, true)},
                               field("switching_function"), true, no_u_a_eps));
    checks_.push_back(equality("throttle_dH_du_at_lower", "control", "control_law.throttle.dH_du_at_lower",
                               "dH/d" + throttle_ + " at " + throttle_ + " = 0" + a_note,
                               {Hu_star.subs(u == 0), Hu_c, at(0, false)}, field("dH_du_at_lower"), true, no_u_a));
    checks_.push_back(equality("throttle_dH_du_at_upper", "control", "control_law.throttle.dH_du_at_upper",
                               "dH/d" + throttle_ + " at " + throttle_ + " = 1" + a_note,
                               {Hu_star.subs(u == 1), Hu_c, at(1, false)}, field("dH_du_at_upper"), true, no_u_a));
    if (t->contains("d2H_du2"))
      checks_.push_back(equality("throttle_d2H_du2", "control", "control_law.throttle.d2H_du2",
                                 "d2H/d" + throttle_ + "2" + a_note, {Huu.subs(astar), Huu_c, at(std::nan(""), false)},
                                 field("d2H_du2"), true, directions_));

    // Convexity: dH/du = 0 must be a minimum (lambda0 > 0, eps > 0 at every sample point).
    {
      Check c = start("throttle_convexity", "control", "random_points");
      for (const auto& p : points_) {
        const double v = Huu_c(at(std::nan(""), false)(p));
        const double viol = std::isfinite(v) ? std::max(0.0, -v) / (1 + std::fabs(v)) : 2.0;
        if (viol > c.max_rel) c.max_rel = viol;
        if (viol > kTol)
          c.fail("d2H/d" + throttle_ + "2 = " + print(tidy(Huu.subs(astar))) + " is " + num(v) +
                 " < 0 at a sample point with " + multiplier_ + " > 0, " + eps_ +
                 " > 0: dH/du = 0 is then a maximum of H; the " + eps_ +
                 " smoothing in running_cost must make H convex in " + throttle_ + ".");
      }
      checks_.push_back(c);
    }

    // Interior law: dH/du = 0 there.
    const bool smooth = !Huu.expand().is_zero();
    ex interior;
    Compiled interior_c;
    std::string interior_error;
    try {
      const json& it = field("interior");
      if (!it.is_string()) throw std::invalid_argument("control_law.throttle.interior: not an expression string");
      interior = table_.parse(it.get<std::string>(), "control_law.throttle.interior");
      interior_c = compile(interior);
    } catch (const std::exception& e) {
      interior_error = e.what();
    }
    if (smooth) {
      Check c = start("throttle_interior", "control", "random_points+exact");
      if (!interior_error.empty()) {
        c.max_rel = 2;
        c.fail(interior_error + "; expected the " + throttle_ + " solving " + print(tidy(Hu_star)) + " = 0.");
      } else {
        double worst = 0, wv = 0, wu = 0;
        for (const auto& p : points_) {
          const double ui = interior_c(p);
          const double r = Hu_c(at(ui, false)(p));
          const double scale = std::max(std::fabs(Hu_c(at(0, false)(p))), std::fabs(Hu_c(at(1, false)(p))));
          const double rel = std::isfinite(r) && std::isfinite(scale) ? std::fabs(r) / (1 + scale) : 2.0;
          if (rel > worst) {
            worst = rel;
            wv = r;
            wu = ui;
          }
        }
        c.max_rel = worst;
        c.exact = exact_equal(Hu_star.subs(u == interior), 0);
        c.pass = worst <= kTol || c.exact;
        if (!c.pass)
          c.fail("control_law.throttle.interior = " + field("interior").get<std::string>() + " does not solve dH/d" +
                 throttle_ + " = " + print(tidy(Hu_star)) + " = 0: at a sample point it gives " + throttle_ + " = " +
                 num(wu) + " where dH/d" + throttle_ + " = " + num(wv) + ".");
      }
      checks_.push_back(c);
    }

    // The clamped law minimizes H over a grid of u in [0, 1].
    {
      Check c = start("throttle_law", "control", "random_points");
      const json bounds = field("bounds");
      const bool bounds_ok = bounds.is_array() && bounds.size() == 2 && bounds[0].is_number() &&
                             bounds[1].is_number() && bounds[0].get<double>() == 0 && bounds[1].get<double>() == 1;
      Compiled lo, hi;
      std::string error = interior_error;
      try {
        for (const bool lower_end : {true, false}) {
          const char* name = lower_end ? "dH_du_at_lower" : "dH_du_at_upper";
          const json& f = field(name);
          const std::string where = std::string("control_law.throttle.") + name;
          if (!f.is_string()) throw std::invalid_argument(where + ": not an expression string");
          (lower_end ? lo : hi) = compile(table_.parse(f.get<std::string>(), where));
        }
      } catch (const std::exception& e) {
        if (error.empty()) error = e.what();
      }
      const std::string control = t->value("control", "");
      if (control != throttle_) {
        c.fail("control_law.throttle.control is '" + control + "', expected '" + throttle_ +
               "' (the control of kind throttle).");
      } else if (!bounds_ok) {
        c.fail("control_law.throttle.bounds must be [0, 1] (the throttle is T/Tmax).");
      } else if (!error.empty()) {
        c.max_rel = 2;
        c.fail("cannot evaluate the throttle law: " + error + ".");
      } else {
        for (const auto& p : points_) {
          const double s0 = lo(p), s1 = hi(p);
          const double ustar = s0 >= 0 ? 0.0 : (s1 <= 0 ? 1.0 : interior_c(p));
          const Point q = with_direction(p, 1.0);
          auto H_at = [&](double uv) {
            Point r = q;
            r[static_cast<std::size_t>(us)] = uv;
            return Hc_(r);
          };
          const double hs = H_at(ustar);
          if (!std::isfinite(ustar) || ustar < -kTol || ustar > 1 + kTol || !std::isfinite(hs)) {
            c.max_rel = 2;
            c.fail("the throttle law (u = 0 if dH_du_at_lower >= 0, 1 if dH_du_at_upper <= 0, else interior) gives " +
                   throttle_ + " = " + num(ustar) + " outside [0, 1] at a sample point.");
            break;
          }
          for (int k = 0; k <= kThrottleGrid; ++k) {
            const double uk = static_cast<double>(k) / kThrottleGrid, hk = H_at(uk);
            const double v = (hs - hk) / (1 + std::max(std::fabs(hs), std::fabs(hk)));
            if (v > c.max_rel) c.max_rel = v;
            if (v > kTol)
              c.fail(
                  "the throttle law (u = 0 if dH_du_at_lower >= 0, 1 if dH_du_at_upper <= 0, else interior) does not "
                  "minimize H over " +
                  throttle_ + " in [0, 1]: at a sample point it gives " + throttle_ + " = " + num(ustar) +
                  " with H = " + num(hs) + ", but " + throttle_ + " = " + num(uk) + " gives H = " + num(hk) + ".");
          }
        }
      }
      checks_.push_back(c);
    }
  }

  // The field `key` of the shooting equation `name` as written, or null.
  const json* equation_field(const std::string& name, const std::string& key) const {
    if (!d_.contains("shooting") || !d_["shooting"].is_object() || !d_["shooting"].contains("equations")) return nullptr;
    for (const auto& eq : d_["shooting"]["equations"])
      if (eq.is_object() && eq.value("name", "") == name && eq.contains(key)) return &eq[key];
    return nullptr;
  }

  // A bound psi_j <= 0 (the row `name`, multiplier nu): the solver makes it inactive (its equation
  // nu = 0) or active (psi_j = 0), so the inequality must name the row's own multiplier, and the
  // inactive equation must be that multiplier; the sense is psi_j <= 0 (nu >= 0 when active).
  void check_bound(const std::string& name, const json& bound, const ex& nu) {
    Check k = start("bound:" + name, "events", "structural");
    const std::string where = "shooting.equations[" + name + "].inequality";
    const std::string multiplier = bound.is_object() ? bound.value("multiplier", "") : "";
    if (!bound.is_object() || bound.value("sense", "") != "expression <= 0") {
      k.fail(where + ".sense must be 'expression <= 0' (the bound psi <= 0, its multiplier >= 0 when active).");
    } else if (multiplier != print(nu)) {
      k.fail(where + ".multiplier = '" + multiplier + "' is not " + print(nu) + ", the multiplier of the row " + name + ".");
    } else {
      bool inactive_ok = false;
      std::string got = "(none)";
      try {
        got = bound.at("inactive_expression").get<std::string>();
        inactive_ok = (table_.parse(got, where + ".inactive_expression") - nu).expand().is_zero();
      } catch (const std::exception&) {
      }
      if (!inactive_ok)
        k.fail(where + ".inactive_expression = '" + got + "' must be " + print(nu) +
               ": an inactive bound's equation is its multiplier = 0.");
    }
    checks_.push_back(k);
  }

  // ----- shooting system

  void read_shooting() {
    const json empty = json::array();
    const json& sh = d_.contains("shooting") && d_["shooting"].is_object() ? d_["shooting"] : json::object();
    const json& vars = sh.contains("variables") && sh["variables"].is_array() ? sh["variables"] : empty;
    const json& eqs = sh.contains("equations") && sh["equations"].is_array() ? sh["equations"] : empty;
    for (const auto& v : vars) variables_.push_back(v.is_object() ? v.value("name", "") : "");
    for (std::size_t k = 0; k < eqs.size(); ++k) {
      Equation e;
      e.name = eqs[k].is_object() ? eqs[k].value("name", "") : "";
      if (e.name.empty()) e.name = "#" + std::to_string(k);
      const std::string where = "shooting.equations[" + e.name + "]";
      try {
        if (!eqs[k].is_object() || !eqs[k].contains("expression") || !eqs[k]["expression"].is_string())
          throw std::invalid_argument(where + ": no expression string");
        e.text = eqs[k]["expression"].get<std::string>();
        e.e = table_.parse(e.text, where);
        e.c = compile(e.e);
        for (const auto& p : points_) e.values.push_back(e.c(p));
        for (auto& name : symbolic::free_symbols(e.e)) e.symbols.insert(std::move(name));
        e.ok = true;
      } catch (const std::exception& x) {
        e.error = x.what();
      }
      equations_.push_back(e);
    }
  }

  // The mismatch of `g` with k * `e` for the best constant k != 0 (k from the point of largest |e|).
  double proportional_mismatch(const Compiled& e, const Compiled& g) const {
    std::vector<double> gv;
    for (const auto& p : points_) gv.push_back(g(p));
    return proportional_mismatch(e, gv);
  }
  double proportional_mismatch(const Compiled& e, const std::vector<double>& gv) const {
    double best = 0, k = std::nan("");
    std::vector<double> ev;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      ev.push_back(e(points_[i]));
      if (std::isfinite(ev.back()) && std::fabs(ev.back()) > best) {
        best = std::fabs(ev.back());
        k = gv[i] / ev.back();
      }
    }
    if (!(best > 0) || !std::isfinite(k) || std::fabs(k) < 1e-12) return 2.0;
    double m = 0;
    for (std::size_t i = 0; i < ev.size(); ++i) m = std::max(m, rel_diff(gv[i], k * ev[i]));
    return m;
  }

  // Looks for an equation equivalent to `expected` = 0 (up to a constant factor).
  void find_equation(Check& c, const ex& expected, const std::string& missing) const {
    const Compiled ec = compile(expected);
    double best = 2;
    for (const auto& eq : equations_) {
      if (!eq.ok) continue;
      const double m = proportional_mismatch(ec, eq.values);
      if (m <= kTol) {
        c.max_rel = m;
        c.exact = exact_proportional(eq.e, expected);
        return;
      }
      best = std::min(best, m);
    }
    c.max_rel = best;
    c.fail(missing);
  }

  void check_endpoints() {
    const ex lambda0 = sym(multiplier_);
    GiNaC::exmap to_tf, to_t0;
    for (const auto& s : states_) {
      to_tf[sym(s)] = sym(s + "_tf");
      to_t0[sym(s)] = sym(s + "_t0");
    }
    auto states_in = [this](const ex& e, std::set<std::string>& out) {
      for (const auto& s : states_)
        if (e.has(sym(s))) out.insert(s);
    };
    std::set<std::string> at_tf, at_t0;
    for (const auto& k : constraints_)
      for (const auto& psi : k.psi) states_in(psi, k.at == "tf" ? at_tf : at_t0);
    // Final state: a state no psi fixes has lambda(tf) = lambda0 dphi/dx(tf).
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const std::string& s = states_[i];
      if (at_tf.count(s)) continue;
      const ex expected =
          (sym(costates_[i] + "_tf") - lambda0 * phi_.diff(GiNaC::ex_to<symbol>(sym(s))).subs(to_tf)).expand();
      Check c = start("transversality:" + s, "transversality", "random_points+exact");
      find_equation(c, expected,
                    "missing transversality condition " + print(expected) + " = 0: " + s +
                        "(tf) is free (no final constraint involves it); add it to shooting.equations.");
      checks_.push_back(c);
    }
    // Each final constraint component psi(x(tf)) = 0.
    for (const auto& k : constraints_) {
      if (k.at != "tf") continue;
      for (std::size_t j = 0; j < k.psi.size(); ++j) {
        const ex expected = k.psi[j].subs(to_tf);
        Check c = start("endpoint:" + k.id + "_" + std::to_string(j + 1), "transversality", "random_points+exact");
        find_equation(c, expected,
                      "missing endpoint condition " + print(expected) + " = 0 (constraints[" + k.id + "].psi[" +
                          std::to_string(j) + "] at tf); add it to shooting.equations.");
        checks_.push_back(c);
        const std::string name = "psi_" + k.id + "_" + std::to_string(j + 1);
        if (const json* bound = equation_field(name, "inequality")) {
          const std::string nu = j < k.multipliers.size() ? k.multipliers[j] : "";
          if (is_identifier(nu)) check_bound(name, *bound, sym(nu));
        }
      }
    }
    // Initial state not fixed by a constraint: lambda(t0) = 0 (the endpoint cost is at tf).
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const std::string& s = states_[i];
      if (at_t0.count(s)) continue;
      Check c = start("transversality_t0:" + s, "transversality", "random_points+exact");
      find_equation(c, sym(costates_[i] + "_t0"),
                    "missing transversality condition " + costates_[i] + "_t0 = 0: " + s +
                        "(t0) is free (no initial constraint involves it); add it to shooting.equations.");
      checks_.push_back(c);
    }
    fixed_at_t0_ = at_t0;
    if (free_tf_) check_free_tf(to_tf);
  }

  // Time derivatives of the parameters that move with tf: an ephemeris component has its
  // ephemeris_rate partner (same body; the parameter named <name>_rate, else the same position
  // among that body's rates), a coasting target's component the coast dynamics.
  std::map<std::string, ex> tf_rates(std::vector<std::string>& problems) const { return rates_at("tf", problems); }

  // The same for the parameters evaluated at `label` (t0, tf, an interior event's id, <id>_dep).
  std::map<std::string, ex> rates_at(const std::string& label, std::vector<std::string>& problems) const {
    std::map<std::string, ex> rates;
    std::map<std::string, std::vector<std::string>> ephem, rate, coast;  // by body / constraint
    for (const auto& name : parameters_) {
      const auto it = sources_.find(name);
      if (it == sources_.end()) continue;
      const std::string& src = it->second;
      const auto a = src.find(':'), b = src.rfind(':');
      if (a == std::string::npos || b == a || src.substr(b + 1) != label) continue;
      const std::string kind = src.substr(0, a), owner = src.substr(a + 1, b - a - 1);
      (kind == "ephemeris" ? ephem : kind == "ephemeris_rate" ? rate : coast)[owner].push_back(name);
    }
    for (const auto& [body, names] : ephem) {
      const auto& r = rate[body];
      for (std::size_t k = 0; k < names.size(); ++k) {
        const auto named = std::find(r.begin(), r.end(), names[k] + "_rate");
        if (named != r.end())
          rates[names[k]] = sym(*named);
        else if (r.size() == names.size())
          rates[names[k]] = sym(r[k]);
        else
          problems.push_back("parameter " + names[k] + " (source ephemeris:" + body + ":" + label + ") moves with " +
                             (label == "tf" || label == "t0" ? label : "the epoch of " + label) +
                             " but has no parameter with source ephemeris_rate:" + body + ":" + label);
      }
    }
    for (const auto& [owner, names] : coast) {
      if (!has_coast_ || !coast_error_.empty() || names.size() != coast_states_.size() ||
          coast_rhs_.size() != coast_states_.size()) {
        problems.push_back("the coasting target of " + owner + " (" + join(names, ", ") +
                           ") has no usable coast_dynamics to give its rate");
        continue;
      }
      GiNaC::exmap to_params;
      for (std::size_t k = 0; k < names.size(); ++k) to_params[sym(coast_states_[k])] = sym(names[k]);
      for (std::size_t k = 0; k < names.size(); ++k) rates[names[k]] = coast_rhs_[k].subs(to_params);
    }
    return rates;
  }

  // Free final time: H(tf) + dPhi/dtf = 0 with Phi = lambda0 phi + nu.psi, where nu is eliminated
  // through lambda(tf) = dPhi/dx(tf) and dpsi/dtf comes from the parameters that move with tf.
  void check_free_tf(GiNaC::exmap to_tf) {
    Check c = start("transversality_tf", "transversality", "random_points+exact");
    for (const auto& l : costates_) to_tf[sym(l)] = sym(l + "_tf");
    std::vector<std::string> problems;
    const std::map<std::string, ex> rates = tf_rates(problems);
    const EventValue* H_tf = nullptr;
    for (const auto& v : events_)
      if (v.hamiltonian && !H_tf) H_tf = &v;
    if (!H_tf)
      problems.push_back(
          "event_values must declare the Hamiltonian at tf (e.g. {\"name\": \"H_tf\", \"meaning\": \"H at tf under "
          "the optimal control\"}) for the free-final-time condition");
    std::vector<ex> psi, dpsi;
    for (const auto& k : constraints_)
      if (k.at == "tf")
        for (const auto& e : k.psi) {
          ex d = slots_.count("tf") ? e.diff(GiNaC::ex_to<symbol>(sym("tf"))) : ex(0);
          for (const auto& [name, rate] : rates) d += e.diff(GiNaC::ex_to<symbol>(sym(name))) * rate;
          psi.push_back(e);
          dpsi.push_back(d);
        }
    // nu from m independent rows of lambda_i(tf) - lambda0 dphi/dx_i = sum_j nu_j dpsi_j/dx_i.
    const ex lambda0 = sym(multiplier_);
    ex expected;
    try {
      if (!problems.empty()) throw std::invalid_argument(join(problems, "; "));
      expected = H_tf ? sym(H_tf->name) : ex(0);
      if (slots_.count("tf")) expected += lambda0 * phi_.diff(GiNaC::ex_to<symbol>(sym("tf")));
      expected += nu_dot(psi, dpsi, [&](std::size_t i) {
        return sym(costates_[i]) - lambda0 * phi_.diff(GiNaC::ex_to<symbol>(sym(states_[i])));
      });
      expected = GiNaC::normal(expected.subs(to_tf)).expand();
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail("cannot form the free-final-time condition H(tf) + dPhi/dtf = 0: " + std::string(e.what()) + ".");
      checks_.push_back(c);
      return;
    }
    const std::string want = print(expected) + " = 0 (H(tf) + dPhi/dtf = 0 with Phi = " + multiplier_ +
                             "*phi + nu.psi and nu eliminated through lambda(tf) = dPhi/dx(tf))";
    find_equation(c, expected, "missing free-final-time condition " + want + "; add it to shooting.equations.");
    if (!c.pass) {
      // Name the equation that was meant to be it: the one called transversality_tf, else the one using H_tf.
      const Equation* meant = nullptr;
      for (const auto& eq : equations_)
        if (eq.ok && (eq.name == "transversality_tf" || (!meant && H_tf && eq.e.has(sym(H_tf->name))))) meant = &eq;
      if (meant) {
        const std::string t = term_diagnosis(expected, meant->e);
        c.feedback = "shooting equation '" + meant->name + "' (" + meant->text + " = 0) is not the free-final-time " +
                     "transversality condition " + want + (t.empty() ? "" : ": " + t) +
                     "; ephemeris targets contribute -lambda(tf).(target rate) through dpsi/dtf.";
      }
    }
    checks_.push_back(c);
  }

  // tf_expression: with a free final time tf is an unknown of the shooting (Rule 0).
  void check_times() {
    if (!events_.empty()) {
      Check c = start("event_values", "counts", "structural");
      c.exact = true;
      std::vector<std::string> unknown;
      for (const auto& v : events_)
        if (!v.hamiltonian) unknown.push_back(v.name + " ('" + v.meaning + "')");
      if (!unknown.empty())
        c.fail("event_values " + join(unknown, ", ") +
               " cannot be recomputed (known: the Hamiltonian at tf under the optimal control, H_tf); express them "
               "in states, costates and parameters at tf instead.");
      checks_.push_back(c);
    }
    if (!free_tf_) return;
    Check c = start("tf_expression", "counts", "structural");
    c.exact = true;
    const json& times = d_["times"];
    const json w = times.value("tf_window", json::array());
    if (!tf_error_.empty()) {
      c.fail(tf_error_ + ".");
    } else if (!w.is_array() || w.size() != 2 || !w[0].is_number() || !w[1].is_number() ||
               !(w[0].get<double>() < w[1].get<double>())) {
      c.fail("times.tf_window must be [lo, hi] with lo < hi (normalized time).");
    } else {
      const std::set<std::string> vars(variables_.begin(), variables_.end());
      std::vector<std::string> used, missing;
      for (const auto& name : symbolic::free_symbols(tf_expr_)) {
        if (vars.count(name)) used.push_back(name);
        if (std::find(tf_vars_.begin(), tf_vars_.end(), name) != tf_vars_.end() && !vars.count(name))
          missing.push_back(name);
      }
      if (!missing.empty())
        c.fail("times.tf_expression = " + tf_text_ + " uses " + join(missing, ", ") +
               ", which shooting.variables lacks: a free final time adds one shooting variable (Rule 0).");
      else if (used.empty())
        c.fail("times.tf_expression = " + tf_text_ +
               " depends on no shooting variable: a free final time must be an unknown of the shooting (Rule 0).");
    }
    checks_.push_back(c);
  }

  // Coasting targets: coast_dynamics.rhs must be the problem's own r, v dynamics with the controls
  // removed (throttle 0), so that the target obeys the same field (J2 included).
  void check_coast() {
    std::map<std::string, std::vector<std::string>> groups;
    for (const auto& [name, src] : sources_)
      if (src.rfind("coast:", 0) == 0) groups[src.substr(6, src.rfind(':') - 6)].push_back(name);
    if (groups.empty() && !has_coast_) return;
    Check c = start("coast_dynamics", "state_odes", "random_points+exact");
    std::vector<std::size_t> rv;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const Kind k = kinds_[static_cast<std::size_t>(slot(states_[i]))];
      if (k == Kind::Position || k == Kind::Velocity) rv.push_back(i);
    }
    std::set<std::string> ids;
    for (const auto& k : constraints_) ids.insert(k.id);
    if (!has_coast_) {
      c.fail(
          "parameters with source coast:<constraint>:tf exist but coast_dynamics is missing: give the "
          "uncontrolled dynamics that carries the target from t0.");
    } else if (!coast_error_.empty()) {
      c.fail(coast_error_ + ".");
    } else if (coast_states_.size() != rv.size() || coast_rhs_.size() != rv.size()) {
      c.fail("coast_dynamics must have one state and one rhs per position and velocity state of the problem (" +
             std::to_string(rv.size()) + "), got " + std::to_string(coast_states_.size()) + " states and " +
             std::to_string(coast_rhs_.size()) + " rhs.");
    } else {
      for (const auto& [owner, names] : groups)
        if (!ids.count(owner))
          c.fail("parameters " + join(names, ", ") + " have source coast:" + owner + ":tf, but no constraint has id " +
                 owner + ".");
        else if (names.size() != coast_states_.size())
          c.fail("the coasting target of " + owner + " has " + std::to_string(names.size()) +
                 " parameters but coast_dynamics has " + std::to_string(coast_states_.size()) + " states.");
      GiNaC::exmap to_coast, off;
      for (std::size_t k = 0; k < rv.size(); ++k) to_coast[sym(states_[rv[k]])] = sym(coast_states_[k]);
      if (!throttle_.empty()) off[sym(throttle_)] = 0;
      for (std::size_t k = 0; k < rv.size() && c.pass; ++k) {
        const ex expected = f_[rv[k]].subs(off).subs(to_coast);
        std::vector<std::string> left;
        for (const auto& name : symbolic::free_symbols(expected)) {
          const Kind kk = kinds_[static_cast<std::size_t>(slot(name))];
          if (kk != Kind::Parameter && kk != Kind::Sourced &&
              std::find(coast_states_.begin(), coast_states_.end(), name) == coast_states_.end())
            left.push_back(name);
        }
        const std::string text = d_["coast_dynamics"]["rhs"][k].get<std::string>();
        if (!left.empty()) {
          c.fail("cannot form the uncontrolled dynamics of " + states_[rv[k]] + ": state_rhs with the throttle at 0 " +
                 "still depends on " + join(left, ", ") + ".");
          break;
        }
        const Compiled ec = compile(expected), gc = compile(coast_rhs_[k]);
        double worst = 0;
        for (const auto& p : points_) worst = std::max(worst, rel_diff(ec(p), gc(p)));
        c.max_rel = std::max(c.max_rel, worst);
        if (worst > kTol && !exact_equal(expected, coast_rhs_[k])) {
          const std::string t = term_diagnosis(expected, coast_rhs_[k]);
          c.fail("coast_dynamics.rhs[" + std::to_string(k) + "] (the rate of " + coast_states_[k] +
                 ") must be dynamics.state_rhs[" + states_[rv[k]] + "] with the controls removed, expected " +
                 print(tidy(expected)) + ", got " + text + (t.empty() ? "" : "; " + t) +
                 " (the target moves in the same field as the spacecraft).");
        }
      }
      c.exact = c.pass;
    }
    checks_.push_back(c);
  }
  std::set<std::string> fixed_at_t0_;

  // ----- interior events and a sliding departure: checks

  // sum_j nu_j dpsi_j with nu solved from rows i of sum_j nu_j dpsi_j/dx_i = rhs(i), the rows taken
  // where the Jacobian of psi is best conditioned at a sample point.
  ex nu_dot(const std::vector<ex>& psi, const std::vector<ex>& dpsi, const std::function<ex(std::size_t)>& rhs) const {
    const std::size_t m = psi.size(), n = states_.size();
    if (m == 0) return 0;
    std::vector<std::vector<ex>> J(m, std::vector<ex>(n));
    std::vector<std::vector<double>> Jn(m, std::vector<double>(n));
    for (std::size_t j = 0; j < m; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        J[j][i] = psi[j].diff(GiNaC::ex_to<symbol>(sym(states_[i])));
        Jn[j][i] = compile(J[j][i])(points_[0]);
      }
    std::vector<std::size_t> rows;
    for (std::size_t j = 0; j < m; ++j) {
      std::size_t best = n;
      for (std::size_t i = 0; i < n; ++i)
        if (std::find(rows.begin(), rows.end(), i) == rows.end() &&
            (best == n || std::fabs(Jn[j][i]) > std::fabs(Jn[j][best])))
          best = i;
      if (best == n || !(std::fabs(Jn[j][best]) > 1e-12))
        throw std::invalid_argument("the constraints' psi are not independent in the states");
      for (std::size_t k = j + 1; k < m; ++k) {
        const double f = Jn[k][best] / Jn[j][best];
        for (std::size_t i = 0; i < n; ++i) Jn[k][i] -= f * Jn[j][i];
      }
      rows.push_back(best);
    }
    const auto um = static_cast<unsigned>(m);
    GiNaC::matrix M(um, um), b(um, 1), nu(um, 1);
    for (unsigned r = 0; r < um; ++r) {
      for (unsigned j = 0; j < um; ++j) M(r, j) = J[j][rows[r]];
      b(r, 0) = rhs(rows[r]);
      nu(r, 0) = symbol("helios_nu_" + std::to_string(r));
    }
    const GiNaC::matrix sol = M.solve(nu, b);
    ex out = 0;
    for (unsigned j = 0; j < um; ++j) out += sol(j, 0) * dpsi[j];
    return out;
  }

  // Term-by-term comparison of two expressions linear in `basis` (multipliers, costates, event
  // values), by evaluation: the given one may be any constant multiple of the expected one.
  struct Linear {
    std::vector<std::string> missing, flipped, wrong, extra;
    bool rest_wrong = false;
    bool ok() const { return missing.empty() && flipped.empty() && wrong.empty() && extra.empty() && !rest_wrong; }
    bool has(const std::vector<std::string>& list, const std::string& name) const {
      return std::find(list.begin(), list.end(), name) != list.end();
    }
    std::string text() const {
      std::vector<std::string> parts;
      if (!missing.empty()) parts.push_back("it lacks the term(s) in " + join(missing, ", "));
      if (!flipped.empty()) parts.push_back("the term(s) in " + join(flipped, ", ") + " have the wrong sign");
      if (!wrong.empty()) parts.push_back("the coefficient(s) of " + join(wrong, ", ") + " are wrong");
      if (!extra.empty()) parts.push_back("it has unexpected term(s) in " + join(extra, ", "));
      if (rest_wrong) parts.push_back("its part free of those symbols is wrong");
      return join(parts, "; ");
    }
  };
  // `anchor`: the basis symbol whose ratio wins a tie for the scale; `fixed`: the scale is 1 (an
  // expression, not an equation).
  Linear linear_compare(const ex& expected, const ex& given, const std::vector<ex>& basis, const ex& anchor = ex(0),
                        bool fixed = false) const {
    GiNaC::exmap zero;
    for (const auto& b : basis) zero[b] = 0;
    std::vector<ex> parts_e, parts_g;
    std::vector<std::string> names;
    for (const auto& b : basis) {
      parts_e.push_back(expected.diff(GiNaC::ex_to<symbol>(b)).subs(zero));
      parts_g.push_back(given.diff(GiNaC::ex_to<symbol>(b)).subs(zero));
      names.push_back(print(b));
    }
    parts_e.push_back(expected.subs(zero));
    parts_g.push_back(given.subs(zero));
    const std::size_t P = parts_e.size();
    std::vector<std::vector<double>> E(P), G(P);
    for (std::size_t k = 0; k < P; ++k) {
      const Compiled ce = compile(parts_e[k]), cg = compile(parts_g[k]);
      for (const auto& p : points_) {
        E[k].push_back(ce(p));
        G[k].push_back(cg(p));
      }
    }
    auto zero_all = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(), [](double x) { return rel_diff(x, 0) <= kTol; });
    };
    auto scaled = [](const std::vector<double>& g, const std::vector<double>& e, double k) {
      for (std::size_t i = 0; i < g.size(); ++i)
        if (rel_diff(g[i], k * e[i]) > kTol) return false;
      return true;
    };
    // The scale: the candidate ratio that matches the most parts.
    double scale = 1;
    int best = fixed ? std::numeric_limits<int>::max() : -1;
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < P; ++k)
      if (k < basis.size() && basis[k].is_equal(anchor))
        order.insert(order.begin(), k);
      else
        order.push_back(k);
    for (const std::size_t k : order) {
      std::size_t at = 0;
      for (std::size_t i = 1; i < E[k].size(); ++i)
        if (std::fabs(E[k][i]) > std::fabs(E[k][at])) at = i;
      if (E[k].empty() || !(std::fabs(E[k][at]) > 1e-12)) continue;
      const double r = G[k][at] / E[k][at];
      if (!std::isfinite(r) || std::fabs(r) < 1e-12) continue;
      int count = 0;
      for (std::size_t j = 0; j < P; ++j) count += !zero_all(E[j]) && scaled(G[j], E[j], r);
      if (count > best) {
        best = count;
        scale = r;
      }
    }
    Linear out;
    for (std::size_t k = 0; k < P; ++k) {
      const bool ez = zero_all(E[k]), gz = zero_all(G[k]);
      const bool rest = k + 1 == P;
      if (ez && gz) continue;
      if (scaled(G[k], E[k], scale)) continue;
      if (rest) {
        out.rest_wrong = true;
      } else if (gz) {
        out.missing.push_back(names[k]);
      } else if (ez) {
        out.extra.push_back(names[k]);
      } else if (scaled(G[k], E[k], -scale)) {
        out.flipped.push_back(names[k]);
      } else {
        out.wrong.push_back(names[k]);
      }
    }
    return out;
  }

  // An equation of shooting.equations equivalent to `expected` = 0 (a constant multiple), the one
  // named `name` first; `resolve` rewrites an equation first (costates the map gives explicitly).
  const Equation* matching_equation(const std::string& name, const ex& expected, Check& c,
                                    const GiNaC::exmap& resolve) const {
    const Compiled ec = compile(expected);
    double best = 2;
    std::vector<const Equation*> order;
    for (const auto& eq : equations_)
      if (eq.ok && eq.name == name)
        order.insert(order.begin(), &eq);
      else if (eq.ok)
        order.push_back(&eq);
    for (const auto* eq : order) {
      bool uses = false;
      for (const auto& [from, to] : resolve) uses = uses || eq->symbols.count(print(from));
      const ex e = uses ? eq->e.subs(resolve) : eq->e;
      const double m = uses ? proportional_mismatch(ec, compile(e)) : proportional_mismatch(ec, eq->values);
      if (m <= kTol) {
        c.max_rel = m;
        c.exact = exact_proportional(e, expected);
        return eq;
      }
      best = std::min(best, m);
    }
    c.max_rel = best;
    return nullptr;
  }
  const Equation* named_equation(const std::string& name) const {
    for (const auto& eq : equations_)
      if (eq.ok && eq.name == name) return &eq;
    return nullptr;
  }
  static std::string short_print(const ex& e) { return tree_size(e, 400) > 400 ? "(a long expression)" : print(e); }

  // d e/dt through an explicit epoch symbol and the parameters that move with it.
  ex time_derivative(const ex& e, const std::string& epoch, const std::map<std::string, ex>& rates) const {
    ex d = slots_.count(epoch) ? e.diff(GiNaC::ex_to<symbol>(sym(epoch))) : ex(0);
    for (const auto& [name, rate] : rates) d += e.diff(GiNaC::ex_to<symbol>(sym(name))) * rate;
    return d;
  }

  void check_events() {
    for (const auto& e : interior_) check_event(e);
  }

  void check_event(const Event& e) {
    const std::string& id = e.id;
    const std::string where = "events[" + id + "]";
    if (!e.error.empty()) {
      Check c = start("event:" + id, "events", "structural");
      c.fail(e.error + ".");
      checks_.push_back(c);
      return;
    }
    const std::size_t n = states_.size();
    std::vector<ex> xm, xp, lm, lp;
    for (std::size_t i = 0; i < n; ++i) {
      xm.push_back(sym(before(states_[i], id)));
      xp.push_back(sym(after(states_[i], id)));
      lm.push_back(sym(before(costates_[i], id)));
      lp.push_back(sym(after(costates_[i], id)));
    }
    auto d = [](const ex& f, const ex& x) { return f.diff(GiNaC::ex_to<symbol>(x)); };
    auto zero_at_points = [&](const ex& f) {
      const Compiled cf = compile(f);
      return std::all_of(points_.begin(), points_.end(), [&](const Point& p) { return rel_diff(cf(p), 0) <= kTol; });
    };

    // 1. psi = [c(t, x-, p); x+ - g(t + D, x-, p)]: rows without x+ are c, each state has one row x+_s - g_s.
    Check ps = start("event_psi:" + id, "events", "random_points+exact");
    ps.exact = true;
    std::vector<std::size_t> c_rows;
    std::vector<int> map_row(n, -1);
    for (std::size_t r = 0; r < e.psi.size(); ++r) {
      std::vector<std::size_t> plus;
      for (std::size_t i = 0; i < n; ++i)
        if (e.psi[r].has(xp[i])) plus.push_back(i);
      if (plus.empty()) {
        c_rows.push_back(r);
      } else if (plus.size() > 1) {
        ps.fail(where + ".psi[" + std::to_string(r) + "] = " + e.psi_text[r] + " involves " +
                std::to_string(plus.size()) +
                " states after the event; each row of the map part must be x+ - g(x-) for one state.");
      } else if (map_row[plus[0]] >= 0) {
        ps.fail(where + ".psi has two rows in " + print(xp[plus[0]]) + " (rows " + std::to_string(map_row[plus[0]]) +
                " and " + std::to_string(r) + "); the map part has one row x+ - g(x-) per state.");
      } else {
        map_row[plus[0]] = static_cast<int>(r);
      }
    }
    std::vector<ex> g(n), c;
    for (const auto r : c_rows) c.push_back(e.psi[r]);
    for (std::size_t s = 0; s < n && ps.pass; ++s) {
      if (map_row[s] < 0) {
        ps.fail(where + ".psi has no row " + print(xp[s]) + " - g_" + states_[s] + "(x-) for state " + states_[s] +
                ": the map part of psi must give every state after the event.");
        break;
      }
      const ex& row = e.psi[static_cast<std::size_t>(map_row[s])];
      g[s] = tree_size(row, kExactBudget) > kExactBudget ? ex(xp[s] - row) : (xp[s] - row).expand();
      if (!zero_at_points(d(row, xp[s]) - 1) || g[s].has(xp[s])) {
        ps.fail(where + ".psi[" + std::to_string(map_row[s]) +
                "] = " + e.psi_text[static_cast<std::size_t>(map_row[s])] + " must be " + print(xp[s]) +
                " - g(x-) with coefficient 1 on " + print(xp[s]) + " (its multiplier is then -lambda_" + states_[s] +
                "(t+)).");
        break;
      }
      const Compiled cg = compile(g[s]), cm = compile(e.map[s]);
      double worst = 0;
      for (const auto& p : points_) worst = std::max(worst, rel_diff(cg(p), cm(p)));
      ps.max_rel = std::max(ps.max_rel, worst);
      if (worst > kTol && !exact_equal(g[s], e.map[s])) {
        ps.fail(where + ".state_map[" + states_[s] + "] = " + e.map_text[s] + " is not the map of psi[" +
                std::to_string(map_row[s]) + "] = " + e.psi_text[static_cast<std::size_t>(map_row[s])] +
                ", which gives " + print(xp[s]) + " = " + short_print(g[s]) + " (relative difference " + num(worst) +
                ").");
      } else if (worst > kTol || tree_size(g[s], kExactBudget) > kExactBudget) {
        ps.exact = ps.exact && worst <= kTol;
      }
    }
    for (std::size_t j = 0; j < c.size() && ps.pass; ++j)
      for (std::size_t i = 0; i < n; ++i)
        if (e.psi[c_rows[j]].has(lm[i]) || e.psi[c_rows[j]].has(lp[i]))
          ps.fail(where + ".psi[" + std::to_string(c_rows[j]) + "] = " + e.psi_text[c_rows[j]] +
                  " involves a costate; psi constrains states, time and parameters only.");
    ps.exact = ps.exact && ps.pass;
    checks_.push_back(ps);
    if (!ps.pass) return;

    // 2. Multipliers: nu_<id>_j for the rows of c, -lambda(t+)_s for the row x+_s - g_s.
    Check pm = start("event_multipliers:" + id, "events", "structural");
    pm.exact = true;
    std::vector<ex> nu;
    if (e.multiplier_text.size() != e.psi.size()) {
      pm.fail(where + ".multipliers has " + std::to_string(e.multiplier_text.size()) + " entries for " +
              std::to_string(e.psi.size()) + " rows of psi: give one multiplier per row.");
    } else {
      std::set<std::string> seen;
      for (std::size_t j = 0; j < c.size(); ++j) {
        const std::string& m = e.multiplier_text[c_rows[j]];
        const bool fresh = is_identifier(m) && kinds_[static_cast<std::size_t>(slot(m))] == Kind::Free &&
                           std::find(e.free_params.begin(), e.free_params.end(), m) == e.free_params.end() &&
                           std::find(e.time_vars.begin(), e.time_vars.end(), m) == e.time_vars.end();
        if (!fresh || !seen.insert(m).second)
          pm.fail(where + ".multipliers[" + std::to_string(c_rows[j]) + "] = '" + m +
                  "' must be a new symbol (e.g. nu_" + id + "_" + std::to_string(j + 1) +
                  "), the multiplier of psi row " + e.psi_text[c_rows[j]] + ".");
        else
          nu.push_back(sym(m));
      }
      for (std::size_t s = 0; s < n && pm.pass; ++s) {
        const std::string& m = e.multiplier_text[static_cast<std::size_t>(map_row[s])];
        bool ok = false;
        try {
          ok = (table_.parse(m, where + ".multipliers") + lp[s]).expand().is_zero();
        } catch (const std::exception&) {
        }
        if (!ok)
          pm.fail(where + ".multipliers[" + std::to_string(map_row[s]) + "] = '" + m + "' must be -" + print(lp[s]) +
                  ": the multiplier of the row " + print(xp[s]) + " - g is -lambda_" + states_[s] +
                  "(t+) (lambda(t+) = -dPhi/dx+).");
      }
    }
    checks_.push_back(pm);
    if (!pm.pass) return;

    // 3. Each row of c is a shooting equation (Rule 0).
    for (std::size_t j = 0; j < c.size(); ++j) {
      const std::string name = "psi_" + id + "_" + std::to_string(j + 1);
      Check k = start("event_constraint:" + id + "_" + std::to_string(j + 1), "events", "random_points+exact");
      if (!matching_equation(name, c[j], k, {}))
        k.fail("missing interior constraint " + e.psi_text[c_rows[j]] + " = 0 (" + where + ".psi[" +
               std::to_string(c_rows[j]) + "] at " + id + "); add it to shooting.equations.");
      checks_.push_back(k);
      if (const json* bound = equation_field(name, "inequality")) check_bound(name, *bound, nu[j]);
    }

    // 4. Costate jumps: lambda(t-)_s = nu^T dc/dx-_s + lambda(t+)^T dg/dx-_s. A state the map
    //    carries (dg_s/dx- = unit row s) gets lambda(t+)_s explicitly, any other a shooting variable.
    std::vector<bool> carried(n, true);
    std::vector<std::vector<ex>> dg(n, std::vector<ex>(n));  // dg[k][s] = dg_k/dx-_s
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t s = 0; s < n; ++s) {
        dg[k][s] = d(g[k], xm[s]);
        if (carried[k] && !zero_at_points(dg[k][s] - (k == s ? 1 : 0))) carried[k] = false;
      }
    std::vector<ex> rows(n), explicit_lp(n);
    GiNaC::exmap resolve;  // lambda(t+) of carried states -> their explicit value
    for (std::size_t s = 0; s < n; ++s) {
      ex row = lm[s];
      for (std::size_t j = 0; j < c.size(); ++j) row -= nu[j] * d(c[j], xm[s]);
      for (std::size_t k = 0; k < n; ++k)
        if (!carried[k]) row -= lp[k] * dg[k][s];
      rows[s] = row;
      if (carried[s]) {
        explicit_lp[s] = row;
        resolve[lp[s]] = row;
      }
    }
    std::vector<ex> basis_rows = nu;
    for (std::size_t k = 0; k < n; ++k)
      if (!carried[k]) basis_rows.push_back(lp[k]);
    for (std::size_t s = 0; s < n; ++s) basis_rows.push_back(lm[s]);
    for (std::size_t s = 0; s < n; ++s) {
      const std::string cid = "costate_jump:" + id + "_" + states_[s];
      const CostateEntry& entry = e.costate_map[s];
      const std::string label = where + ".costate_map[" + costates_[s] + "]";
      const std::string jump_rule =
          print(lm[s]) + " = nu^T dc/d" + print(xm[s]) + " + lambda(t+)^T dg/d" + print(xm[s]);
      if (!entry.given) {
        Check k = start(cid, "events", "structural");
        k.fail(label + " is missing: give lambda_" + states_[s] + " just after " + id + " (" + jump_rule + ").");
        checks_.push_back(k);
        continue;
      }
      if (carried[s]) {
        if (entry.is_variable) {
          Check k = start(cid, "events", "structural");
          k.fail(label + " makes lambda_" + states_[s] + "(t+) a shooting variable, but the map carries " + states_[s] +
                 " (dg_" + states_[s] + "/dx- is the unit row), so its jump row gives it explicitly: expected " +
                 print(lp[s]) + " = " + short_print(explicit_lp[s]) + " (" + jump_rule + ").");
          checks_.push_back(k);
          continue;
        }
        Check k = equality(cid, "events", label, "lambda_" + states_[s] + "(t+) from " + jump_rule,
                           {explicit_lp[s], compile(explicit_lp[s]), {}}, json(entry.text), false);
        if (!k.pass) {
          const Linear lc = linear_compare(explicit_lp[s], entry.expr, basis_rows, lm[s], true);
          std::string why = lc.text();
          if (!lc.flipped.empty() &&
              std::any_of(nu.begin(), nu.end(), [&](const ex& v) { return lc.has(lc.flipped, print(v)); }))
            why += " (lambda(t+) = lambda(t-) - nu^T dc/dx-: the jump subtracts the multipliers)";
          else if (!lc.missing.empty() &&
                   std::any_of(nu.begin(), nu.end(), [&](const ex& v) { return lc.has(lc.missing, print(v)); }))
            why += " (psi constrains " + states_[s] + " at " + id + ", so its costate jumps by -nu^T dc/dx-)";
          else {
            bool in_c = false;
            for (const auto& cj : c) in_c = in_c || cj.has(xm[s]);
            why += " (the map carries " + states_[s] + " over, " + print(xp[s]) + " = " + short_print(g[s]) +
                   " with dg/d" + print(xm[s]) + " = 1, " +
                   (in_c ? std::string("so lambda_" + states_[s] + " jumps by -nu^T dc/dx- only")
                         : std::string("and no row of c involves it, so lambda_" + states_[s] +
                                       " does not jump: " + print(lp[s]) + " = " + print(lm[s]))) +
                   ")";
          }
          k.feedback = label + " = " + entry.text + " is not the costate jump at " + id + ": expected " + print(lp[s]) +
                       " = " + short_print(explicit_lp[s]) + " (" + jump_rule + ")" + (why.empty() ? "" : "; " + why) +
                       ".";
        }
        checks_.push_back(k);
        continue;
      }
      // Not carried: lambda(t+)_s is a shooting variable and the row an equation.
      Check k = start(cid, "events", "random_points+exact");
      const std::string row_text = short_print(rows[s]);
      if (!entry.is_variable) {
        k.fail(label + " = " + entry.text + " treats lambda_" + states_[s] + " as given across " + id +
               ", but the map " + print(xp[s]) + " = " + short_print(g[s]) + " does not carry " + states_[s] +
               " over (dg/dx- is not the unit row): lambda_" + states_[s] + "(t+) is unknown; make it the shooting " +
               "variable " + print(lp[s]) + " (\"variable\") and add the jump row " + row_text +
               " = 0 as equation jump_" + id + "_" + states_[s] + ".");
        checks_.push_back(k);
        continue;
      }
      if (entry.variable != print(lp[s])) {
        k.fail(label + " names the variable '" + entry.variable + "'; lambda_" + states_[s] + " just after " + id +
               " is the symbol " + print(lp[s]) + ".");
        checks_.push_back(k);
        continue;
      }
      const std::string ename = "jump_" + id + "_" + states_[s];
      if (!matching_equation(ename, rows[s], k, resolve)) {
        const Equation* meant = named_equation(ename);
        if (meant) {
          const Linear lc = linear_compare(rows[s], meant->e.subs(resolve), basis_rows, lm[s]);
          k.fail("shooting equation '" + ename + "' (" + (meant->text.size() > 300 ? "..." : meant->text) +
                 " = 0) is not the costate jump row " + jump_rule + ", i.e. " + row_text + " = 0" +
                 (lc.ok() ? "" : ": " + lc.text()) + ".");
        } else {
          k.fail("missing costate jump row " + row_text + " = 0 at " + id + " (" + jump_rule + ", row " + states_[s] +
                 "; lambda_" + states_[s] + "(t+) is the shooting variable " + print(lp[s]) +
                 "); add it to shooting.equations as " + ename + ".");
        }
      }
      checks_.push_back(k);
    }

    // 5. Free epoch: H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0, d/dt through the moving parameters.
    std::vector<std::string> problems;
    std::set<std::string> labels;
    for (const auto& name : parameters_) {
      const auto it = sources_.find(name);
      if (it == sources_.end() || it->second.rfind("ephemeris_rate:", 0) == 0) continue;
      bool used = false;
      for (const auto& r : e.psi) used = used || r.has(sym(name));
      if (used) labels.insert(it->second.substr(it->second.rfind(':') + 1));
    }
    std::map<std::string, ex> rates;
    for (const auto& l : labels)
      for (const auto& [name, rate] : rates_at(l, problems)) rates[name] = rate;
    {
      Check k = start("event_time:" + id, "events", "random_points+exact");
      if (e.Hm.empty() || e.Hp.empty())
        problems.push_back("event_values must declare H just before and just after " + id + " (kind hamiltonian, at " +
                           id + "_m and " + id + "_p)");
      if (!problems.empty()) {
        k.max_rel = 2;
        k.fail("cannot form the free-epoch condition of " + id + ": " + join(problems, "; ") + ".");
      } else {
        const std::string epoch = "t_" + id;
        ex dphi = 0;
        for (std::size_t j = 0; j < c.size(); ++j) dphi += nu[j] * time_derivative(c[j], epoch, rates);
        for (std::size_t s = 0; s < n; ++s)
          dphi += (carried[s] ? explicit_lp[s] : lp[s]) * time_derivative(g[s], epoch, rates);
        const ex Hm = sym(e.Hm), Hp = sym(e.Hp);
        const ex expected = Hm - Hp + dphi;
        const std::string ename = "time_" + id;
        const std::string want =
            "H(t-) - H(t+) + nu^T dc/dt + lambda(t+)^T dg/dt = 0, i.e. " + short_print(expected) + " = 0";
        if (!matching_equation(ename, expected, k, resolve)) {
          const Equation* meant = named_equation(ename);
          if (!meant)
            for (const auto& eq : equations_)
              if (eq.ok && !meant && (eq.e.has(Hm) || eq.e.has(Hp))) meant = &eq;
          if (!meant) {
            k.fail("missing free-epoch condition of " + id + " " + want + "; add it to shooting.equations as " + ename +
                   ".");
          } else {
            std::vector<ex> basis{Hm, Hp};
            basis.insert(basis.end(), nu.begin(), nu.end());
            for (std::size_t s = 0; s < n; ++s)
              if (!carried[s]) basis.push_back(lp[s]);
            const ex given = meant->e.subs(resolve);
            const Linear lc = linear_compare(expected, given, basis, nu.empty() ? ex(0) : nu[0]);
            std::vector<std::string> why;
            const std::string hm = print(Hm), hp = print(Hp);
            if (!given.has(Hm) && !given.has(Hp))
              why.push_back("the jump of the Hamiltonian H(t-) - H(t+) = " + hm + " - " + hp + " is missing");
            else if (lc.has(lc.flipped, hm) && lc.has(lc.flipped, hp))
              why.push_back("the jump of the Hamiltonian has the wrong sign: it must be H(t-) - H(t+) = " + hm + " - " +
                            hp);
            bool rate_missing = false;
            for (const auto& name : lc.missing) rate_missing = rate_missing || (name != hm && name != hp);
            if (rate_missing && !dphi.is_zero())
              why.push_back("nu^T dpsi/dt is missing (" + short_print(dphi) + "): the target moves with the epoch " +
                            "(parameters " +
                            join(
                                [&] {
                                  std::vector<std::string> v;
                                  for (const auto& [name, rate] : rates) v.push_back(name + "' = " + print(rate));
                                  return v;
                                }(),
                                ", ") +
                            ")");
            if (why.empty() && !lc.ok()) why.push_back(lc.text());
            k.fail("shooting equation '" + meant->name + "' (" + (meant->text.size() > 300 ? "..." : meant->text) +
                   " = 0) is not the free-epoch condition of " + id + " " + want +
                   (why.empty() ? "" : ": " + join(why, "; ")) + ".");
          }
        }
      }
      checks_.push_back(k);
    }

    // 6. Stationarity in the free parameters of psi (Category C): nu^T dc/dq + lambda(t+)^T dg/dq = 0.
    std::vector<std::string> params;
    for (const auto& q : e.free_params)
      if (std::find(params.begin(), params.end(), q) == params.end()) params.push_back(q);
    for (const auto& q : params) {
      Check k = start("event_stationarity:" + id + "_" + q, "events", "random_points+exact");
      ex expected = 0;
      for (std::size_t j = 0; j < c.size(); ++j) expected += nu[j] * d(c[j], sym(q));
      for (std::size_t s = 0; s < n; ++s) expected += (carried[s] ? explicit_lp[s] : lp[s]) * d(g[s], sym(q));
      const std::string ename = "stationarity_" + id + "_" + q;
      const std::string want = "dPhi/d" + q + " = nu^T dc/d" + q + " + lambda(t+)^T dg/d" + q + " = 0";
      if (!matching_equation(ename, expected, k, resolve)) {
        const Equation* meant = named_equation(ename);
        if (meant) {
          std::vector<ex> basis = nu;
          for (std::size_t s = 0; s < n; ++s)
            if (!carried[s]) basis.push_back(lp[s]);
          const Linear lc = linear_compare(expected, meant->e.subs(resolve), basis);
          k.fail("shooting equation '" + ename + "' is not the stationarity condition " + want + " of the free " +
                 "parameter " + q + " of psi at " + id + (lc.ok() ? "" : ": " + lc.text()) + ".");
        } else {
          k.fail("missing stationarity condition " + want + " (" + q + " is a free parameter of psi at " + id + ": " +
                 short_print(expected) + " = 0); add it to shooting.equations as " + ename + ".");
        }
      }
      checks_.push_back(k);
    }

    // 7. The event's unknowns are shooting variables (Rule 0): its nu's, its epoch's fraction,
    //    lambda(t+) of the states the map does not carry, and the free parameters of psi.
    {
      Check k = start("event_unknowns:" + id, "counts", "structural");
      k.exact = true;
      const std::set<std::string> vars(variables_.begin(), variables_.end());
      std::vector<std::string> missing;
      for (const auto& v : nu)
        if (!vars.count(print(v))) missing.push_back(print(v) + " (multiplier of c)");
      for (const auto& v : e.time_vars)
        if (!vars.count(v)) missing.push_back(v + " (the epoch of " + id + ")");
      for (std::size_t s = 0; s < n; ++s)
        if (!carried[s] && !vars.count(print(lp[s])))
          missing.push_back(print(lp[s]) + " (lambda_" + states_[s] + " after " + id + ", not carried by the map)");
      for (const auto& q : params)
        if (!vars.count(q)) missing.push_back(q + " (free parameter of psi)");
      if (!missing.empty()) k.fail("shooting.variables lacks " + join(missing, ", ") + " for the event " + id + ".");
      bool free_epoch = false;
      for (const auto& name : symbolic::free_symbols(e.time_expr)) free_epoch = free_epoch || vars.count(name);
      if (!free_epoch)
        k.fail(where + ".time.expression = " + e.time_text + " depends on no shooting variable: the epoch of " + id +
               " is free and must be an unknown of the shooting (Rule 0).");
      else if (e.time_vars.size() == 1 && e.window.size() == 2) {
        const ex lo = e.time_expr.subs(sym(e.time_vars[0]) == 0).evalf(),
                 hi = e.time_expr.subs(sym(e.time_vars[0]) == 1).evalf();
        if (!GiNaC::is_a<numeric>(lo) || !GiNaC::is_a<numeric>(hi) ||
            rel_diff(GiNaC::ex_to<numeric>(lo).to_double(), e.window[0]) > 1e-9 ||
            rel_diff(GiNaC::ex_to<numeric>(hi).to_double(), e.window[1]) > 1e-9)
          k.fail(where + ".time.expression = " + e.time_text + " does not run over the window [" + num(e.window[0]) +
                 ", " + num(e.window[1]) + "] as " + e.time_vars[0] + " goes from 0 to 1.");
      }
      checks_.push_back(k);
    }
  }

  // Sliding departure: -H(t0) + nu0^T dpsi0/dt0 + H(tf) + dPhi/dtf = 0 (tf = t0 + tof moves with
  // t0), nu0 from lambda(t0) = -nu0^T dpsi0/dx(t0), nu_f from lambda(tf) = lambda0 dphi/dx + nu_f^T dpsi_f/dx.
  void check_departure() {
    if (!free_t0_) return;
    {
      Check c = start("t0_expression", "counts", "structural");
      c.exact = true;
      const std::set<std::string> vars(variables_.begin(), variables_.end());
      if (!t0_error_.empty()) {
        c.fail(t0_error_ + ".");
      } else {
        std::vector<std::string> missing;
        bool used = false;
        for (const auto& name : symbolic::free_symbols(t0_expr_)) {
          used = used || vars.count(name);
          if (std::find(t0_vars_.begin(), t0_vars_.end(), name) != t0_vars_.end() && !vars.count(name))
            missing.push_back(name);
        }
        const json& times = d_["times"];
        if (!missing.empty() || !used) {
          c.fail("times.t0_expression depends on no shooting variable" +
                 (missing.empty() ? std::string() : " (" + join(missing, ", ") + " is not one)") +
                 ": a sliding departure adds one shooting variable, t0_frac (Rule 0).");
        } else if (times.contains("tf") && times["tf"].is_number()) {
          const double tof = times["tf"].get<double>() - times.value("t0", 0.0);
          const Compiled gap = compile(t0_tf_expr_ - t0_expr_);
          for (const auto& p : points_)
            if (rel_diff(gap(p), tof) > 1e-9) {
              c.fail("times.tf_expression - times.t0_expression must be the fixed time of flight " + num(tof) +
                     " (tf = t0 + tof moves with t0), got " + num(gap(p)) + ".");
              break;
            }
        }
      }
      checks_.push_back(c);
    }
    Check c = start("transversality_t0", "transversality", "random_points+exact");
    std::vector<std::string> problems;
    const std::map<std::string, ex> r0 = rates_at("t0", problems), rf = rates_at("tf", problems);
    std::string H0, Hf;
    for (const auto& v : events_)
      if (v.hamiltonian && v.at == "t0")
        H0 = v.name;
      else if (v.hamiltonian && v.at == "tf")
        Hf = v.name;
    if (H0.empty() || Hf.empty())
      problems.push_back("event_values must declare the Hamiltonian at t0 and at tf (kind hamiltonian, at t0 / tf)");
    GiNaC::exmap to_t0, to_tf;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      to_t0[sym(states_[i])] = sym(states_[i] + "_t0");
      to_t0[sym(costates_[i])] = sym(costates_[i] + "_t0");
      to_tf[sym(states_[i])] = sym(states_[i] + "_tf");
      to_tf[sym(costates_[i])] = sym(costates_[i] + "_tf");
    }
    ex depart, coupling, expected;
    try {
      if (!problems.empty()) throw std::invalid_argument(join(problems, "; "));
      std::vector<ex> psi0, d0, psif, df;
      for (const auto& k : constraints_)
        for (const auto& e : k.psi) {
          const auto& rates = k.at == "t0" ? r0 : rf;
          const std::string epoch = k.at;
          (k.at == "t0" ? psi0 : psif).push_back(e);
          (k.at == "t0" ? d0 : df).push_back(time_derivative(e, epoch, rates));
        }
      const ex lambda0 = sym(multiplier_);
      depart = -sym(H0) + nu_dot(psi0, d0, [&](std::size_t i) { return -sym(costates_[i]); }).subs(to_t0);
      coupling = sym(Hf) + nu_dot(psif, df, [&](std::size_t i) {
                             return sym(costates_[i]) - lambda0 * phi_.diff(GiNaC::ex_to<symbol>(sym(states_[i])));
                           }).subs(to_tf);
      if (slots_.count("tf")) coupling += lambda0 * phi_.diff(GiNaC::ex_to<symbol>(sym("tf"))).subs(to_tf);
      depart = GiNaC::normal(depart).expand();
      coupling = GiNaC::normal(coupling).expand();
      expected = depart + coupling;
    } catch (const std::exception& e) {
      c.max_rel = 2;
      c.fail("cannot form the sliding-departure condition -H(t0) + dPhi/dt0 + H(tf) + dPhi/dtf = 0: " +
             std::string(e.what()) + ".");
      checks_.push_back(c);
      return;
    }
    const std::string want = "-H(t0) + nu0^T dpsi0/dt0 + H(tf) + nu_f^T dpsi_f/dtf = 0, i.e. " + print(expected) +
                             " = 0 (t0 slides and tf = t0 + tof moves with it)";
    if (!matching_equation("transversality_t0", expected, c, {})) {
      const Equation* meant = named_equation("transversality_t0");
      if (!meant)
        for (const auto& eq : equations_)
          if (eq.ok && !meant && eq.e.has(sym(H0))) meant = &eq;
      if (!meant) {
        c.fail("missing sliding-departure condition " + want + "; add it to shooting.equations as transversality_t0.");
      } else {
        std::vector<std::string> why;
        bool motion = false, tf_side = meant->e.has(sym(Hf));
        for (const auto& [name, rate] : r0)
          for (const auto& s : symbolic::free_symbols(rate)) motion = motion || meant->e.has(sym(s));
        for (const auto& l : costates_) tf_side = tf_side || meant->e.has(sym(l + "_tf"));
        const ex motion_part = (depart + sym(H0)).expand();
        if (!motion && !motion_part.is_zero())
          why.push_back("the departure body's motion is missing (nu0^T dpsi0/dt0 = " + print(motion_part) +
                        ": the departure state moves with t0)");
        if (!tf_side)
          why.push_back("the coupling with tf is missing (H(tf) + dPhi/dtf = " + print(coupling) +
                        ": tf = t0 + tof moves with t0)");
        if (why.empty()) {
          std::vector<ex> basis{sym(H0), sym(Hf)};
          for (const auto& l : costates_) {
            basis.push_back(sym(l + "_t0"));
            basis.push_back(sym(l + "_tf"));
          }
          const Linear lc = linear_compare(expected, meant->e, basis);
          if (!lc.ok()) why.push_back(lc.text());
        }
        c.fail("shooting equation '" + meant->name + "' (" + meant->text + " = 0) is not the sliding-departure " +
               "condition " + want + (why.empty() ? "" : ": " + join(why, "; ")) + ".");
      }
    }
    checks_.push_back(c);
  }

  void check_shooting_shape() {
    {
      Check c = start("count", "counts", "structural");
      c.exact = true;
      std::set<std::string> seen, dup;
      for (const auto& v : variables_)
        if (!seen.insert(v).second) dup.insert(v);
      if (variables_.size() != equations_.size())
        c.fail("shooting has " + std::to_string(variables_.size()) + " variables but " +
               std::to_string(equations_.size()) + " equations: the shooting system must be square.");
      else if (!dup.empty())
        c.fail("shooting.variables lists " + join({dup.begin(), dup.end()}, ", ") + " more than once.");
      checks_.push_back(c);
    }
    {
      Check c = start("shooting_variables", "counts", "structural");
      c.exact = true;
      const std::set<std::string> vars(variables_.begin(), variables_.end());
      std::vector<std::string> missing;
      if (!vars.count(multiplier_)) missing.push_back(multiplier_ + " (the cost multiplier, G1)");
      for (std::size_t i = 0; i < states_.size(); ++i)
        if (fixed_at_t0_.count(states_[i]) && !vars.count(costates_[i] + "_t0"))
          missing.push_back(costates_[i] + "_t0 (" + states_[i] + "(t0) is fixed, so its costate at t0 is unknown)");
      std::vector<std::string> unknown;
      for (const auto& v : variables_)
        if (!slots_.count(v)) unknown.push_back("'" + v + "'");
      if (!missing.empty()) c.fail("shooting.variables lacks " + join(missing, ", ") + ".");
      if (!unknown.empty())
        c.fail("shooting.variables has " + join(unknown, ", ") + ", which are not symbols of this derivation.");
      checks_.push_back(c);
    }
    {
      // Every symbol of an equation must be known when the shooting function evaluates it.
      Check c = start("equation_symbols", "counts", "structural");
      c.exact = true;
      std::set<std::string> allowed(variables_.begin(), variables_.end());
      allowed.insert(parameters_.begin(), parameters_.end());
      allowed.insert(eps_);
      for (const auto& v : events_) allowed.insert(v.name);
      // Around an interior event the shooting knows the states and costates just before and after
      // it (it propagates arc by arc) and its epoch.
      for (const auto& e : interior_) {
        if (!e.error.empty()) continue;
        allowed.insert("t_" + e.id);
        for (std::size_t i = 0; i < states_.size(); ++i)
          for (const auto& name : {states_[i], costates_[i]}) {
            allowed.insert(before(name, e.id));
            allowed.insert(after(name, e.id));
          }
      }
      for (std::size_t i = 0; i < states_.size(); ++i)
        for (const char* event : {"_t0", "_tf"}) {
          allowed.insert(states_[i] + event);
          if (std::string(event) == "_tf") allowed.insert(costates_[i] + event);
        }
      std::vector<std::string> problems;
      for (const auto& eq : equations_) {
        if (!eq.ok) {
          problems.push_back(eq.error);
          continue;
        }
        std::vector<std::string> bad;
        for (const auto& name : symbolic::free_symbols(eq.e))
          if (!allowed.count(name)) bad.push_back(name);
        if (!bad.empty())
          problems.push_back(
              "shooting equation '" + eq.name + "' uses " + join(bad, ", ") +
              ", not known at the shooting boundaries (use <state>_tf, <costate>_tf, <state>_t0, shooting "
              "variables and parameters)");
      }
      if (!problems.empty()) c.fail(join(problems, "; ") + ".");
      checks_.push_back(c);
    }
  }

  void check_normalization() {
    Check c = start("normalization", "counts", "zero_set+exact");
    std::vector<std::string> sphere{multiplier_};
    for (const auto& v : variables_)
      for (const auto& l : costates_)
        if (v == l + "_t0") sphere.push_back(v);
    ex norm2 = 0;
    for (const auto& v : sphere) norm2 += GiNaC::pow(sym(v), 2);
    const ex expected = GiNaC::sqrt(norm2) - 1;
    const std::string want = "missing normalization equation " + print(expected) + " = 0 (G1: " + multiplier_ +
                             " must be inside the sphere normalization with the costates at t0)";
    std::vector<std::size_t> idx;
    for (const auto& v : sphere) idx.push_back(static_cast<std::size_t>(slot(v)));
    // Zero on the unit sphere of (multiplier, costates at t0), nonzero off it.
    auto test = [&](const Compiled& g, double& on_err) {
      on_err = 0;
      bool off_ok = true;
      for (const auto& p : points_) {
        double n = 0;
        for (auto i : idx) n += p[i] * p[i];
        n = std::sqrt(n);
        if (!(n > 0)) continue;
        for (double radius : {1.0, 0.5, 1.7}) {
          Point q = p;
          for (auto i : idx) q[i] = p[i] * radius / n;
          const double v = g(q);
          if (radius == 1.0)
            on_err = std::max(on_err, rel_diff(v, 0));
          else if (!std::isfinite(v) || std::fabs(v) < 1e-6)
            off_ok = false;
        }
      }
      return on_err <= kTol && off_ok;
    };
    const Equation* named = nullptr;
    double best = 2;
    for (const auto& eq : equations_) {
      if (eq.name == "normalization") named = &eq;
      if (!eq.ok) continue;
      double err = 0;
      // An equation free of the sphere's symbols cannot vanish on it and only on it.
      if (std::none_of(sphere.begin(), sphere.end(), [&](const std::string& v) { return eq.symbols.count(v) > 0; }))
        continue;
      if (test(eq.c, err)) {
        c.max_rel = err;
        c.exact = exact_equal(eq.e, expected) || exact_equal(eq.e, norm2 - 1);
        checks_.push_back(c);
        return;
      }
      best = std::min(best, err);
    }
    c.max_rel = best;
    if (named && named->ok) {
      std::vector<std::string> left_out;
      for (const auto& v : sphere)
        if (!named->e.has(sym(v))) left_out.push_back(v);
      c.fail("shooting equation 'normalization' (" + named->text + " = 0) is not equivalent to " + print(expected) +
             " = 0" + (left_out.empty() ? "" : ": it leaves out " + join(left_out, ", ")) + " (G1: " + multiplier_ +
             " must be inside the sphere normalization with the costates at t0).");
    } else {
      c.fail(want + ".");
    }
    checks_.push_back(c);
  }

  // G4: a state with identically zero dynamics that appears nowhere else is not a state.
  void check_state_usage() {
    Check c = start("state_usage", "counts", "structural");
    c.exact = true;
    std::vector<std::string> unused, constant;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const ex x = sym(states_[i]);
      if (!f_[i].expand().is_zero()) continue;
      bool used = L_.has(x) || phi_.has(x);
      for (const auto& fj : f_) used = used || fj.has(x);
      for (const auto& k : constraints_)
        if (k.at == "tf")
          for (const auto& psi : k.psi) used = used || psi.has(x);
      if (!used)
        unused.push_back(states_[i]);
      else if (fixed_at_t0_.count(states_[i]))
        constant.push_back(states_[i]);
    }
    if (!unused.empty())
      c.fail("state(s) " + join(unused, ", ") +
             " have identically zero dynamics and appear in no other dynamics, cost or final "
             "constraint: they are not states of this problem; remove them (G4; e.g. a sail has no mass state).");
    if (!constant.empty())
      c.fail("state(s) " + join(constant, ", ") +
             " have identically zero dynamics and a fixed initial value: they are constants, not states; make them "
             "parameters and remove their costates and shooting variables (G4; e.g. a sail has no mass state).");
    checks_.push_back(c);
  }

  json report() const {
    json doc = io::artifact_header("verify", "helios-verify", "builtin");
    const json problem = d_.contains("problem") && d_["problem"].is_object() ? d_["problem"] : json::object();
    doc["problem"] = {{"id", problem.value("id", "")}};
    doc["derivation_producer"] = d_.contains("producer") ? d_["producer"] : json::object();
    doc["settings"] = {{"points", opt_.points}, {"seed", opt_.seed}, {"rel_tolerance", kTol}};
    int passed = 0, failed = 0;
    json checks = json::array();
    std::vector<std::string> feedback;
    for (const auto& c : checks_) {
      checks.push_back(c.to_json());
      if (c.pass) {
        ++passed;
      } else {
        ++failed;
        feedback.push_back(c.feedback);
      }
    }
    doc["verdict"] = failed == 0 ? "pass" : "fail";
    doc["checks"] = checks;
    doc["summary"] = {{"passed", passed}, {"failed", failed}, {"total", passed + failed}};
    doc["feedback"] = join(feedback, " ");
    return doc;
  }
};

}  // namespace

json verify_derivation(const json& derivation, const VerifyOptions& options) {
  return Verifier(derivation, options).run();
}

}  // namespace helios::verify

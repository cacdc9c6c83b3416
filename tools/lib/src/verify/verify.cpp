#include "helios/verify/verify.hpp"

#include <ginac/ginac.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::verify {
namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;
using io::json;
using symbolic::to_text;
using Point = std::vector<double>;

constexpr double kTol = 1e-9;          // |a - b| <= kTol (1 + max(|a|, |b|)) at every point
constexpr int kRandomDirections = 48;  // random unit vectors tried against a* at each point
constexpr int kThrottleGrid = 40;      // intervals of the grid of u in [0, 1]

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

std::string print(const ex& e) {
  try {
    return to_text(e);
  } catch (const std::exception&) {
    std::ostringstream out;
    out << e;
    return out.str();
  }
}

// ---------------------------------------------------------------------------------------------
// A GiNaC expression compiled to a small tree over symbol slots, evaluated in doubles (GiNaC's
// subs + evalf per point would cost ~100x more).

class Compiled {
 public:
  Compiled() = default;
  Compiled(const ex& e, const std::map<std::string, int>& slots) { root_ = build(e, slots); }
  double operator()(const Point& x) const { return root_ < 0 ? std::nan("") : eval(root_, x); }

 private:
  enum class Op { Const, Var, Add, Mul, Pow, PowEx, Fn1, Fn2 };
  struct Node {
    Op op = Op::Const;
    double value = 0;
    int slot = 0;
    double (*f1)(double) = nullptr;
    double (*f2)(double, double) = nullptr;
    std::vector<int> args;
  };
  std::vector<Node> nodes_;
  int root_ = -1;

  int push(Node n) {
    nodes_.push_back(std::move(n));
    return static_cast<int>(nodes_.size()) - 1;
  }

  static double (*unary(const std::string& name))(double) {
    static const std::map<std::string, double (*)(double)> table = {
        {"exp", +[](double x) { return std::exp(x); }},   {"log", +[](double x) { return std::log(x); }},
        {"sin", +[](double x) { return std::sin(x); }},   {"cos", +[](double x) { return std::cos(x); }},
        {"tan", +[](double x) { return std::tan(x); }},   {"asin", +[](double x) { return std::asin(x); }},
        {"acos", +[](double x) { return std::acos(x); }}, {"atan", +[](double x) { return std::atan(x); }},
        {"sinh", +[](double x) { return std::sinh(x); }}, {"cosh", +[](double x) { return std::cosh(x); }},
        {"tanh", +[](double x) { return std::tanh(x); }}, {"abs", +[](double x) { return std::fabs(x); }}};
    const auto it = table.find(name);
    return it == table.end() ? nullptr : it->second;
  }

  int build(const ex& e, const std::map<std::string, int>& slots) {
    Node n;
    if (GiNaC::is_a<numeric>(e) || GiNaC::is_a<GiNaC::constant>(e)) {
      const ex v = GiNaC::evalf(e);
      if (!GiNaC::is_a<numeric>(v) || !GiNaC::ex_to<numeric>(v).is_real())
        throw std::invalid_argument("constant " + print(e) + " is not a real number");
      n.value = GiNaC::ex_to<numeric>(v).to_double();
      return push(n);
    }
    if (GiNaC::is_a<symbol>(e)) {
      const std::string name = GiNaC::ex_to<symbol>(e).get_name();
      const auto it = slots.find(name);
      if (it == slots.end()) throw std::invalid_argument("unknown symbol " + name);
      n.op = Op::Var;
      n.slot = it->second;
      return push(n);
    }
    if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
      // GiNaC's operand order follows hash values that vary between runs; a fixed order keeps
      // the rounding, and so every reported number, reproducible.
      n.op = GiNaC::is_a<GiNaC::add>(e) ? Op::Add : Op::Mul;
      std::vector<std::pair<std::string, ex>> ops;
      for (const auto& op : e) ops.emplace_back(print(op), op);
      std::sort(ops.begin(), ops.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& op : ops) n.args.push_back(build(op.second, slots));
      return push(n);
    }
    if (GiNaC::is_a<GiNaC::power>(e)) {
      n.args.push_back(build(e.op(0), slots));
      if (GiNaC::is_a<numeric>(e.op(1)) && GiNaC::ex_to<numeric>(e.op(1)).is_real()) {
        n.op = Op::Pow;
        n.value = GiNaC::ex_to<numeric>(e.op(1)).to_double();
      } else {
        n.op = Op::PowEx;
        n.args.push_back(build(e.op(1), slots));
      }
      return push(n);
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if (e.nops() == 1 && unary(name)) {
        n.op = Op::Fn1;
        n.f1 = unary(name);
      } else if (e.nops() == 2 && name == "atan2") {
        n.op = Op::Fn2;
        n.f2 = +[](double y, double x) { return std::atan2(y, x); };
      } else {
        throw std::invalid_argument("function " + name + " is not supported by the verifier");
      }
      for (const auto& op : e) n.args.push_back(build(op, slots));
      return push(n);
    }
    throw std::invalid_argument("cannot evaluate " + print(e));
  }

  double eval(int i, const Point& x) const {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    switch (n.op) {
      case Op::Const:
        return n.value;
      case Op::Var:
        return x[static_cast<std::size_t>(n.slot)];
      case Op::Add: {
        double s = 0;
        for (int a : n.args) s += eval(a, x);
        return s;
      }
      case Op::Mul: {
        double p = 1;
        for (int a : n.args) p *= eval(a, x);
        return p;
      }
      case Op::Pow:
        return std::pow(eval(n.args[0], x), n.value);
      case Op::PowEx:
        return std::pow(eval(n.args[0], x), eval(n.args[1], x));
      case Op::Fn1:
        return n.f1(eval(n.args[0], x));
      case Op::Fn2:
        return n.f2(eval(n.args[0], x), eval(n.args[1], x));
    }
    return std::nan("");
  }
};

// ---------------------------------------------------------------------------------------------
// Exact comparison: expand + normal, and for expressions with square roots the substitution
// B^(k/2) -> w^k followed by reduction of the numerator modulo w^2 - B (so that, e.g.,
// S^(-3/2) - 3 x^2 S^(-5/2) and (S - 3 x^2) S^(-5/2) compare equal). False means "not shown".

struct HalfPowers : GiNaC::map_function {
  std::vector<std::pair<ex, symbol>> roots;
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<numeric>(e.op(1))) {
      const numeric k = GiNaC::ex_to<numeric>(e.op(1));
      if (k.is_rational() && !k.is_integer() && k.denom() == 2)
        return GiNaC::pow(root((*this)(e.op(0)).expand()), k * 2);
    }
    return e.map(*this);
  }
  symbol root(const ex& base) {
    for (const auto& [b, w] : roots)
      if ((b - base).expand().is_zero()) return w;
    roots.emplace_back(base, symbol("helios_root_" + std::to_string(roots.size())));
    return roots.back().second;
  }
};

bool exact_equal(const ex& a, const ex& b) {
  try {
    if (symbolic::symbolically_equal(a, b)) return true;
    HalfPowers half;
    const ex diff = (a - b).expand();
    if (GiNaC::is_a<GiNaC::add>(diff) && diff.nops() > 400) return false;  // keep normal() affordable
    const ex d = half(diff);
    if (half.roots.empty()) return false;
    ex n = GiNaC::numer(GiNaC::normal(d)).expand();
    for (auto it = half.roots.rbegin(); it != half.roots.rend(); ++it)
      n = GiNaC::rem(n, GiNaC::pow(it->second, 2) - it->first, it->second, false).expand();
    return n.is_zero() || GiNaC::normal(n).is_zero();
  } catch (const std::exception&) {
    return false;
  }
}

// True if `a` is a constant nonzero multiple of `b`, shown exactly.
bool exact_proportional(const ex& a, const ex& b) {
  try {
    if (exact_equal(a, b) || exact_equal(a, -b)) return true;
    const ex r = GiNaC::normal(a / b);
    return GiNaC::is_a<numeric>(r) && !r.is_zero();
  } catch (const std::exception&) {
    return false;
  }
}

// A tidier form for feedback: in an expanded sum, the terms sharing a factor B^(k/2) whose
// cofactors add up to a multiple q*B become q*B^(k/2+1) (so that sum(l_i^2)*S^(-1/2) with
// S = sum(l_i^2) prints as sqrt(S)). Falls back to `e` on any trouble.
ex tidy(const ex& e) {
  try {
    const ex x = e.expand();
    if (!GiNaC::is_a<GiNaC::add>(x)) return x;
    std::vector<std::pair<ex, ex>> groups;  // (B^(k/2), sum of cofactors)
    ex out = 0;
    for (const auto& t : x) {
      ex factor;
      const auto is_half = [](const ex& f) {
        return GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<numeric>(f.op(1)) &&
               GiNaC::ex_to<numeric>(f.op(1)).is_rational() && GiNaC::ex_to<numeric>(f.op(1)).denom() == 2;
      };
      if (is_half(t)) factor = t;
      if (GiNaC::is_a<GiNaC::mul>(t))
        for (const auto& f : t)
          if (is_half(f)) factor = f;
      if (factor.is_zero()) {
        out += t;
        continue;
      }
      auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first.is_equal(factor); });
      if (it == groups.end()) it = groups.insert(groups.end(), {factor, 0});
      it->second += t / factor;
    }
    for (const auto& [factor, cofactor] : groups) {
      const ex r = GiNaC::normal(cofactor / factor.op(0));
      const ex den = GiNaC::denom(r);
      bool sum_in_denominator = false;
      for (GiNaC::const_preorder_iterator i = den.preorder_begin(); i != den.preorder_end(); ++i)
        sum_in_denominator = sum_in_denominator || GiNaC::is_a<GiNaC::add>(*i);
      out +=
          sum_in_denominator ? (cofactor * factor).expand() : r.expand() * GiNaC::pow(factor.op(0), factor.op(1) + 1);
    }
    return out;
  } catch (const std::exception&) {
    return e;
  }
}

std::vector<ex> terms_of(const ex& e) {
  std::vector<ex> out;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const auto& t : e) out.push_back(t);
  } else if (!e.is_zero()) {
    out.push_back(e);
  }
  return out;
}

// Term by term comparison of two expanded expressions: flipped signs, missing and extra terms.
// Empty when the forms are too different for the comparison to mean anything.
std::string term_diagnosis(const ex& expected, const ex& given) {
  const std::vector<ex> E = terms_of(tidy(expected)), G = terms_of(tidy(given));
  if (E.empty() || G.empty() || E.size() > 64 || G.size() > 64) return "";
  std::vector<bool> used(G.size(), false);
  std::vector<std::string> flipped, missing, extra;
  std::size_t matched = 0;
  for (const auto& e : E) {
    bool found = false;
    for (std::size_t j = 0; j < G.size() && !found; ++j)
      if (!used[j] && (e - G[j]).expand().is_zero()) used[j] = found = true;
    if (found) {
      ++matched;
      continue;
    }
    for (std::size_t j = 0; j < G.size() && !found; ++j)
      if (!used[j] && (e + G[j]).expand().is_zero()) {
        used[j] = found = true;
        flipped.push_back(print(e));
      }
    if (!found) missing.push_back(print(e));
  }
  for (std::size_t j = 0; j < G.size(); ++j)
    if (!used[j]) extra.push_back(print(G[j]));
  if (matched + flipped.size() == 0) return "";
  for (auto* list : {&flipped, &missing, &extra}) std::sort(list->begin(), list->end());
  if (!flipped.empty() && flipped.size() == E.size() && extra.empty())
    return "the sign of the whole expression is flipped";
  std::vector<std::string> parts;
  if (!flipped.empty()) parts.push_back("the sign of " + join(flipped, ", ") + " is flipped");
  if (!missing.empty()) parts.push_back("it lacks the term(s) " + join(missing, ", "));
  if (!extra.empty()) parts.push_back("it has the unexpected term(s) " + join(extra, ", "));
  return join(parts, "; ");
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
  Parameter,
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
            {"max_rel_error", std::isfinite(max_rel) ? max_rel : 2.0},
            {"feedback", pass ? "" : feedback}};
  }
};

struct Constraint {
  std::string id, at;
  std::vector<ex> psi;  // in the state symbols
};

struct Equation {
  std::string name, text, error;
  bool ok = false;
  ex e;
  Compiled c;
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
    check_throttle();
    read_shooting();
    check_endpoints();
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

  std::vector<std::string> states_, costates_, directions_, parameters_;
  std::string throttle_, multiplier_, eps_;
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
      } else {
        throw input_error("derivation: control " + name + " has unknown kind '" + kind + "'");
      }
    }
    for (const auto& p : parameters) {
      const std::string name = io::require_string(p, "name", "derivation parameters");
      parameters_.push_back(name);
      declare(name, Kind::Parameter, io::require_number(p, "value", "derivation parameter " + name));
    }
    declare(multiplier_, Kind::Multiplier);
    declare(eps_, Kind::Homotopy);
    if (d.contains("constraints") && d["constraints"].is_array())
      for (const auto& c : d["constraints"])
        if (c.contains("multipliers") && c["multipliers"].is_array())
          for (const auto& m : c["multipliers"])
            if (m.is_string() && !slots_.count(m.get<std::string>())) declare(m.get<std::string>(), Kind::Free);

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
        constraints_.push_back(k);
      }
    }

    H_ = sym(multiplier_) * L_;
    for (std::size_t i = 0; i < states_.size(); ++i) H_ += sym(costates_[i]) * f_[i];
    Hc_ = compile(H_);
    for (const auto& a : directions_) {
      grad_a_.push_back(H_.diff(GiNaC::ex_to<symbol>(sym(a))));
      grad_ac_.push_back(compile(grad_a_.back()));
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
            p[i] = 0;
            break;
          case Kind::Parameter:
            p[i] = values_[i];
            break;
          case Kind::Free:
            p[i] = uniform(-1, 1);
            break;
        }
      }
      if (!directions_.empty()) p = set_direction(p, random_unit(directions_.size()));
      bool finite = true;
      for (const auto& c : statement) finite = finite && std::isfinite(c(p));
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
      Check c = equality(id, category, field + "[" + name + "]", expected_name, {expected, compile(expected), {}},
                         entry->contains("rhs") ? (*entry)["rhs"] : json(), true);
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
        e.ok = true;
      } catch (const std::exception& x) {
        e.error = x.what();
      }
      equations_.push_back(e);
    }
  }

  // The mismatch of `g` with k * `e` for the best constant k != 0 (k from the point of largest |e|).
  double proportional_mismatch(const Compiled& e, const Compiled& g) const {
    double best = 0, k = std::nan("");
    std::vector<double> ev, gv;
    for (const auto& p : points_) {
      ev.push_back(e(p));
      gv.push_back(g(p));
      if (std::isfinite(ev.back()) && std::fabs(ev.back()) > best) {
        best = std::fabs(ev.back());
        k = gv.back() / ev.back();
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
      const double m = proportional_mismatch(ec, eq.c);
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
  }
  std::set<std::string> fixed_at_t0_;

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
    std::vector<std::string> unused;
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const ex x = sym(states_[i]);
      if (!f_[i].expand().is_zero()) continue;
      bool used = L_.has(x) || phi_.has(x);
      for (const auto& fj : f_) used = used || fj.has(x);
      for (const auto& k : constraints_)
        if (k.at == "tf")
          for (const auto& psi : k.psi) used = used || psi.has(x);
      if (!used) unused.push_back(states_[i]);
    }
    if (!unused.empty())
      c.fail("state(s) " + join(unused, ", ") +
             " have identically zero dynamics and appear in no other dynamics, cost or final "
             "constraint: they are not states of this problem; remove them (G4).");
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

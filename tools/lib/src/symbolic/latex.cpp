#include "helios/symbolic/latex.hpp"

#include "helios/derivation/names.hpp"
#include "helios/pmp/catalogue.hpp"
#include "helios/symbolic/expr.hpp"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>
#include <sstream>

namespace helios::symbolic {

namespace names = derivation::names;  // the grammar of a derivation's names

namespace {

using GiNaC::ex;

const std::map<std::string, std::string>& greek() {
  static const std::map<std::string, std::string> letters = {
      {"alpha", "\\alpha"}, {"beta", "\\beta"},      {"gamma", "\\gamma"},
      {"delta", "\\delta"}, {"eps", "\\varepsilon"}, {"epsilon", "\\varepsilon"},
      {"zeta", "\\zeta"},   {"eta", "\\eta"},        {"theta", "\\theta"},
      {"kappa", "\\kappa"}, {"lambda", "\\lambda"},  {"mu", "\\mu"},
      {"nu", "\\nu"},       {"xi", "\\xi"},          {"pi", "\\pi"},
      {"rho", "\\rho"},     {"sigma", "\\sigma"},    {"tau", "\\tau"},
      {"phi", "\\phi"},     {"chi", "\\chi"},        {"psi", "\\psi"},
      {"omega", "\\omega"}, {"Gamma", "\\Gamma"},    {"Delta", "\\Delta"},
      {"Theta", "\\Theta"}, {"Lambda", "\\Lambda"},  {"Phi", "\\Phi"},
      {"Psi", "\\Psi"},     {"Omega", "\\Omega"}};
  return letters;
}

std::vector<std::string> split(const std::string& name) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(name);
  while (std::getline(in, part, '_')) parts.push_back(part);
  return parts;
}

bool is_axis(char c) {
  return c == 'x' || c == 'y' || c == 'z';
}

// A vector component: one letter and its axis (rx, vx, nx).
bool is_component(const std::string& part) {
  return part.size() == 2 && std::isalpha(static_cast<unsigned char>(part[0])) && is_axis(part[1]);
}

bool is_number(const std::string& part) {
  return !part.empty() &&
         std::all_of(part.begin(), part.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

std::string upright(const std::string& word) {
  return "\\mathrm{" + latex_text(word) + "}";
}

// One word as a symbol with its own subscript, if any: rx r_x, lambda0 \lambda_0, Tmax T_{\max}.
struct Atom {
  std::string base;
  std::vector<std::string> sub;
};

Atom atom(const std::string& word) {
  const auto& g = greek();
  if (auto it = g.find(word); it != g.end()) return {it->second, {}};
  if (is_component(word)) return {word.substr(0, 1), {word.substr(1)}};
  if (word.size() == 1) return {word, {}};
  if (word == "tf") return {"t", {"f"}};
  // A term's parameter the catalogue typesets (Tmax T_{\max}, a constant mass's m, a bus power P_bus).
  if (const pmp::TermParameter* q = pmp::find_typeset_parameter(word)) {
    if (q->symbol_subscript.empty()) return {q->symbol_base, {}};
    return {q->symbol_base, {q->symbol_subscript}};
  }
  std::size_t digits = word.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(word[digits - 1]))) --digits;
  if (digits > 0 && digits < word.size()) {
    Atom a = atom(word.substr(0, digits));
    a.sub.push_back(word.substr(digits));
    return a;
  }
  return {upright(word), {}};
}

bool is_atom_word(const std::string& word) {
  return greek().count(word) || is_component(word) || word.size() == 1 || word == "tf" ||
         pmp::find_typeset_parameter(word);
}

std::string joined(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

std::string render(const Atom& a, const std::vector<std::string>& sup, const std::string& time) {
  std::string out = a.base;
  if (!a.sub.empty()) out += "_{" + joined(a.sub, ",") + "}";
  if (!sup.empty()) out += "^{" + joined(sup, "") + "}";
  return out + time;
}

ex sum_of_squares(const std::vector<ex>& components) {
  ex sum = 0;
  for (const auto& c : components) sum += GiNaC::pow(c, 2);
  return sum;
}

std::string name_of(const ex& symbol) {
  return GiNaC::ex_to<GiNaC::symbol>(symbol).get_name();
}

std::size_t term_count(const ex& e) {
  return GiNaC::is_a<GiNaC::add>(e) ? e.nops() : 1;
}

// Replaces every symbol named in `by_name` (by its name) wherever it stands.
struct RenameSymbols : GiNaC::map_function {
  const std::map<std::string, GiNaC::symbol>& by_name;
  explicit RenameSymbols(const std::map<std::string, GiNaC::symbol>& m) : by_name(m) {}
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto it = by_name.find(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
      return it == by_name.end() ? e : ex(it->second);
    }
    return e.map(*this);
  }
};

// An intermediate's partial derivative in a state (names::partial: dP_in_drx), its two names matched.
const std::regex& partial_name() {
  static const std::regex partial(R"(d([A-Za-z][A-Za-z0-9_]*)_d([A-Za-z][A-Za-z0-9]*))");
  return partial;
}

}  // namespace

std::string latex_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '_':
      case '&':
      case '%':
      case '$':
      case '#':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string latex_symbol(const std::string& name) {
  if (std::smatch m; std::regex_match(name, m, partial_name()))
    return "\\partial_{" + latex_symbol(m[2].str()) + "} " + latex_symbol(m[1].str());
  std::vector<std::string> parts = split(name);
  if (parts.empty() || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    return upright(name);
  std::string time;
  if (parts.size() > 1 && (parts.back() == names::kT0 || parts.back() == names::kTf)) {
    time = parts.back() == names::kT0 ? "(t_0)" : "(t_f)";
    parts.pop_back();
  }
  Atom core;
  std::vector<std::string> rest;
  if (parts[0] == names::kCostate && parts.size() > 1) {  // a costate: lambda with the state as its subscript
    core = {"\\lambda", {render(atom(parts[1]), {}, "")}};
    rest.assign(parts.begin() + 2, parts.end());
  } else {
    // The symbol is the first part that is one (a body's state mars_vx is v_x^{mars}).
    std::size_t at = 0;
    while (at < parts.size() && !is_atom_word(parts[at])) ++at;
    if (at == parts.size()) at = 0;
    core = atom(parts[at]);
    for (std::size_t i = 0; i < parts.size(); ++i)
      if (i != at) rest.push_back(parts[i]);
  }
  std::string sign;
  if (rest.size() >= 2 && (rest.back() == names::kBefore || rest.back() == names::kAfter)) {  // before / after an event
    sign = rest.back() == names::kBefore ? "-" : "+";
    rest.pop_back();
  }
  std::vector<std::string> sup;
  for (const auto& p : rest) {
    if (is_number(p))
      core.sub.push_back(p);
    else
      sup.push_back((sup.empty() ? "" : ",") + (is_atom_word(p) ? render(atom(p), {}, "") : upright(p)));
  }
  if (!sign.empty()) sup.push_back(sign);
  return render(core, sup, time);
}

std::string latex_intermediate(const std::string& name) {
  const std::vector<std::string> parts = split(name);
  if (parts.size() < 2 || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    return latex_symbol(name);
  Atom core = atom(parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i)
    core.sub.push_back(is_atom_word(parts[i]) ? render(atom(parts[i]), {}, "") : upright(parts[i]));
  return render(core, {}, "");
}

Typesetter::Typesetter(const std::vector<std::string>& names, const std::set<std::string>& intermediates) {
  const auto typeset = [&](const std::string& name) {
    if (intermediates.count(name)) return latex_intermediate(name);
    if (std::smatch m; std::regex_match(name, m, partial_name()) && intermediates.count(m[1].str()))
      return "\\partial_{" + latex_symbol(m[2].str()) + "} " + latex_intermediate(m[1].str());
    return latex_symbol(name);
  };
  std::set<std::string> taken;
  for (const auto& name : names) {
    std::string tex = typeset(name);
    if (!taken.insert(tex).second) {
      tex = upright(name);
      taken.insert(tex);
    }
    latex_of_[name] = tex;
    printable_.emplace(name, GiNaC::symbol(name, tex));
  }
}

std::string Typesetter::symbol(const std::string& name) const {
  auto it = latex_of_.find(name);
  return it == latex_of_.end() ? latex_symbol(name) : it->second;
}

namespace {

// A LaTeX printer whose output depends only on the expression: GiNaC's own LaTeX printer follows
// its internal term order, which follows hash values and so memory addresses (two runs of the same
// tool printed S10's Hamiltonian with its terms in different orders). Terms and factors are sorted
// by their LaTeX; a sum raised to an integer power is printed with its first term positive.
struct Latex {
  std::string text;
  int precedence;  // kSum, kProduct, kPower or kAtom (of expr.cpp's printer)
};
enum LatexPrecedence { kSum = 1, kProduct = 2, kPower = 3, kAtom = 4 };

Latex latex_of(const ex& e);

std::string parenthesized(const Latex& l, int needed) {
  return l.precedence < needed ? "\\left(" + l.text + "\\right)" : l.text;
}

std::string sort_key(const std::string& text) {
  return text[0] == '-' ? text.substr(1) + "~" : text;
}

Latex latex_numeric(const GiNaC::numeric& n) {
  std::ostringstream out;
  if (n.is_integer()) {
    out << n;
  } else if (n.is_rational()) {
    out << (n.is_negative() ? "-" : "") << "\\frac{" << GiNaC::abs(n.numer()) << "}{" << n.denom() << "}";
  } else {
    out.precision(17);
    out << n.to_double();
  }
  const std::string t = out.str();
  return {t, t[0] == '-' ? kSum : (n.is_integer() ? kAtom : kProduct)};
}

// The terms of a sum printed, in the order they are printed in (by their text, the sign aside).
std::vector<std::string> sorted_terms(const ex& sum) {
  std::vector<std::string> terms;
  for (const auto& t : sum) terms.push_back(latex_of(t).text);
  std::sort(terms.begin(), terms.end(),
            [](const std::string& a, const std::string& b) { return sort_key(a) < sort_key(b); });
  return terms;
}

// A sum's printed terms joined with their signs.
std::string joined_terms(const std::vector<std::string>& terms) {
  std::string out;
  for (const auto& t : terms) out += out.empty() ? t : (t[0] == '-' ? " - " + t.substr(1) : " + " + t);
  return out;
}

// `base` (printed as `b`) as the base of a power.
std::string latex_base(const ex& base, const Latex& b) {
  if (GiNaC::is_a<GiNaC::symbol>(base) && b.text.find('^') != std::string::npos) return "{" + b.text + "}";
  if (GiNaC::is_a<GiNaC::function>(base)) return "\\left(" + b.text + "\\right)";
  return parenthesized(b, kAtom);
}

// base^k for k > 0, `base` printed as `b`.
std::string latex_power(const ex& base, const Latex& b, const GiNaC::numeric& k) {
  if (k == 1) return parenthesized(b, kProduct);
  if (k == GiNaC::numeric(1, 2)) return "\\sqrt{" + b.text + "}";
  std::ostringstream exponent;
  if (k.is_integer())
    exponent << k;
  else
    exponent << k.numer() << "/" << k.denom();
  return latex_base(base, b) + "^{" + exponent.str() + "}";
}

bool is_upright(const std::string& factor) {
  return factor.rfind("\\mathrm", 0) == 0 || factor.rfind("{\\mathrm", 0) == 0;
}

Latex latex_product(const GiNaC::exvector& factors) {
  GiNaC::numeric coefficient = 1;
  bool negative = false, lone_sum = false;
  std::string lone_sum_text;
  std::vector<std::string> numerator, denominator;
  for (const auto& f : factors) {
    if (GiNaC::is_a<GiNaC::numeric>(f)) {
      coefficient *= GiNaC::ex_to<GiNaC::numeric>(f);
      continue;
    }
    ex base = f;
    GiNaC::numeric k = 1;
    if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::numeric>(f.op(1))) {
      base = f.op(0);
      k = GiNaC::ex_to<GiNaC::numeric>(f.op(1));
    } else if (GiNaC::is_a<GiNaC::power>(f)) {
      numerator.push_back(latex_base(f.op(0), latex_of(f.op(0))) + "^{" + latex_of(f.op(1)).text + "}");
      continue;
    }
    Latex printed = latex_of(base);
    if (GiNaC::is_a<GiNaC::add>(base) && k.is_integer()) {
      // A sum raised to an integer power is printed with its first term positive.
      if (printed.text[0] == '-') {
        base = (-base).expand();
        printed = latex_of(base);
        if (k.is_odd()) negative = !negative;
      }
      if (k == 1) {
        lone_sum = true;
        lone_sum_text = printed.text;
      }
    }
    (k.is_negative() ? denominator : numerator).push_back(latex_power(base, printed, GiNaC::abs(k)));
  }
  if (coefficient.is_negative()) {
    negative = !negative;
    coefficient = -coefficient;
  }
  std::sort(numerator.begin(), numerator.end());
  std::sort(denominator.begin(), denominator.end());
  // Upright words side by side would read as one (ac rref^2): a thin space between them.
  const auto joined_factors = [](const std::vector<std::string>& factors) {
    std::string out, previous;
    for (const auto& f : factors) {
      out += out.empty() ? "" : (is_upright(f) || is_upright(previous) ? "\\, " : " ");
      out += f;
      previous = f;
    }
    return out;
  };
  std::string out;
  if (coefficient.is_rational()) {
    std::ostringstream num, den;
    num << coefficient.numer();
    den << coefficient.denom();
    std::string top = joined_factors(numerator), bottom = joined_factors(denominator);
    if (coefficient.numer() != 1 || top.empty()) top = num.str() + (top.empty() ? "" : " " + top);
    if (coefficient.denom() != 1) bottom = den.str() + (bottom.empty() ? "" : " " + bottom);
    // A lone sum over a denominator needs no parentheses: the fraction bar groups it.
    if (!bottom.empty() && numerator.size() == 1 && coefficient.numer() == 1 && lone_sum) top = lone_sum_text;
    out = bottom.empty() ? top : "\\frac{" + top + "}{" + bottom + "}";
  } else {
    const std::string top = joined_factors(numerator), bottom = joined_factors(denominator);
    out = latex_numeric(coefficient).text + (top.empty() ? "" : " " + top);
    if (!bottom.empty()) out = "\\frac{" + out + "}{" + bottom + "}";
  }
  return {(negative ? "-" : "") + out, negative ? kSum : kProduct};
}

const std::map<std::string, std::string>& latex_functions() {
  static const std::map<std::string, std::string> names = {{"sin", "\\sin"},
                                                           {"cos", "\\cos"},
                                                           {"tan", "\\tan"},
                                                           {"asin", "\\arcsin"},
                                                           {"acos", "\\arccos"},
                                                           {"atan", "\\arctan"},
                                                           {"exp", "\\exp"},
                                                           {"log", "\\ln"},
                                                           {"sinh", "\\sinh"},
                                                           {"cosh", "\\cosh"},
                                                           {"tanh", "\\tanh"},
                                                           {"abs", "\\operatorname{abs}"},
                                                           {"atan2", "\\operatorname{atan2}"}};
  return names;
}

Latex latex_of(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return latex_numeric(GiNaC::ex_to<GiNaC::numeric>(e));
  if (GiNaC::is_a<GiNaC::symbol>(e)) return {GiNaC::ex_to<GiNaC::symbol>(e).get_TeX_name(), kAtom};
  if (GiNaC::is_a<GiNaC::add>(e)) return {joined_terms(sorted_terms(e)), kSum};
  if (GiNaC::is_a<GiNaC::mul>(e)) return latex_product(GiNaC::exvector(e.begin(), e.end()));
  if (GiNaC::is_a<GiNaC::power>(e)) return latex_product({e});
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    auto it = latex_functions().find(name);
    std::string args;
    for (const auto& a : e) args += (args.empty() ? "" : ", ") + latex_of(a).text;
    return {(it == latex_functions().end() ? "\\operatorname{" + latex_text(name) + "}" : it->second) + "\\left(" +
                args + "\\right)",
            kAtom};
  }
  std::ostringstream raw;
  raw << e;
  throw std::invalid_argument("cannot typeset expression " + raw.str());
}

}  // namespace

std::string Typesetter::print(const ex& e) {
  return latex_of(e).text;
}

ex Typesetter::printable(const ex& e) const {
  RenameSymbols rename(printable_);
  return rename(e);
}

std::string Typesetter::norm_name(const std::vector<ex>& components) const {
  // rx, ry, rz -> r; l_vx, l_vy, l_vz -> l_v; vx_mars_m, ... -> v_mars_m: the axis dropped.
  std::string stripped;
  std::set<char> axes;
  for (const auto& c : components) {
    const std::string name = GiNaC::ex_to<GiNaC::symbol>(c).get_name();
    std::vector<std::string> parts = split(name);
    auto it = std::find_if(parts.begin(), parts.end(), [](const std::string& p) { return is_component(p); });
    if (it == parts.end() || !axes.insert(it->back()).second) return "";
    *it = it->substr(0, 1);
    const std::string s = joined(parts, "_");
    if (!stripped.empty() && s != stripped) return "";
    stripped = s;
  }
  if (printable_.count(stripped)) return "";  // a symbol of that name exists
  const std::string tex = latex_symbol(stripped);
  for (const auto& [name, other] : latex_of_)
    if (other == tex) return "";
  for (const auto& n : norms_)
    if (n.symbol.get_name() == tex) return "";
  return tex;
}

const Typesetter::Norm* Typesetter::norm_of(const ex& base) {
  if (!GiNaC::is_a<GiNaC::add>(base) || base.nops() < 2) return nullptr;
  for (const auto& n : norms_)
    if (n.squared.is_equal(base)) return &n;
  // Squares s^2 (coefficient 1) and cross terms -2*s*t of two symbols.
  std::vector<ex> squares;
  std::vector<std::pair<ex, ex>> crosses;
  GiNaC::exvector terms(base.begin(), base.end());
  for (const auto& term : terms) {
    if (GiNaC::is_a<GiNaC::power>(term) && GiNaC::is_a<GiNaC::symbol>(term.op(0)) && term.op(1).is_equal(2)) {
      squares.push_back(term.op(0));
      continue;
    }
    if (GiNaC::is_a<GiNaC::mul>(term) && term.nops() == 3) {
      std::vector<ex> syms;
      ex coefficient = 1;
      for (const auto& f : term) {
        if (GiNaC::is_a<GiNaC::symbol>(f))
          syms.push_back(f);
        else if (GiNaC::is_a<GiNaC::numeric>(f))
          coefficient = f;
      }
      if (syms.size() == 2 && coefficient.is_equal(-2)) {
        if (name_of(syms[1]) < name_of(syms[0])) std::swap(syms[0], syms[1]);
        crosses.emplace_back(syms[0], syms[1]);
        continue;
      }
    }
    return nullptr;
  }
  const auto has_square = [&](const ex& s) {
    return std::any_of(squares.begin(), squares.end(), [&](const ex& q) { return q.is_equal(s); });
  };
  std::vector<ex> paired;
  const auto is_paired = [&](const ex& s) {
    return std::any_of(paired.begin(), paired.end(), [&](const ex& q) { return q.is_equal(s); });
  };
  std::vector<ex> components;
  std::sort(crosses.begin(), crosses.end(),
            [](const auto& x, const auto& y) { return name_of(x.first) < name_of(y.first); });
  for (const auto& cross : crosses) {
    // Named copies, not structured bindings: C++17 lambdas cannot capture bindings (clang refuses).
    ex a = cross.first, b = cross.second;
    if (!has_square(a) || !has_square(b) || is_paired(a) || is_paired(b)) return nullptr;
    paired.push_back(a);
    paired.push_back(b);
    // The state at an event minus the body's: the name with the event's sign comes first.
    const auto at_event = [](const ex& s) {
      return names::is_before_or_after(GiNaC::ex_to<GiNaC::symbol>(s).get_name());
    };
    if (at_event(b) && !at_event(a)) std::swap(a, b);
    auto it = std::find_if(differences_.begin(), differences_.end(),
                           [&](const Difference& d) { return d.minuend.is_equal(a) && d.subtrahend.is_equal(b); });
    if (it == differences_.end()) {
      const std::string index = std::to_string(differences_.size() + 1);
      differences_.push_back({GiNaC::symbol("delta_" + index, "\\Delta_{" + index + "}"), a, b});
      it = differences_.end() - 1;
    }
    components.push_back(it->symbol);
  }
  for (const auto& s : squares)
    if (!is_paired(s)) components.push_back(s);
  if (components.size() < 2) return nullptr;
  std::sort(components.begin(), components.end(), [](const ex& a, const ex& b) { return name_of(a) < name_of(b); });
  std::string tex = norm_name(components);
  if (tex.empty()) tex = "\\rho_{" + std::to_string(norms_.size() + 1) + "}";
  norms_.push_back({GiNaC::symbol("norm_" + std::to_string(norms_.size() + 1), tex), components, base});
  return &norms_.back();
}

ex Typesetter::name_power_bases(const ex& e) {
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::add>(e.op(0)))
    if (const Norm* n = norm_of(e.op(0))) return GiNaC::pow(n->symbol, 2 * e.op(1));
  if (e.nops() == 0) return e;
  struct Recurse : GiNaC::map_function {
    Typesetter& t;
    explicit Recurse(Typesetter& owner) : t(owner) {}
    ex operator()(const ex& o) override { return t.name_power_bases(o); }
  } recurse(*this);
  return e.map(recurse);
}

namespace {

// Every sum raised to a power in e (the candidates for a norm).
void collect_power_bases(const ex& e, std::map<std::string, ex>& bases) {
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::add>(e.op(0))) bases.emplace(to_text(e.op(0)), e.op(0));
  for (const auto& o : e) collect_power_bases(o, bases);
}

}  // namespace

void Typesetter::learn(const ex& e) {
  learn_printable(printable(e));
}

void Typesetter::learn_printable(const ex& e) {
  // In the order of their text, so that the names do not follow GiNaC's term order.
  std::map<std::string, ex> bases;
  collect_power_bases(e, bases);
  for (const auto& [text, base] : bases) norm_of(base);
}

ex Typesetter::substitute_differences(const ex& e) const {
  GiNaC::exmap by_difference;
  for (const auto& d : differences_)
    if (e.has(d.minuend) && e.has(d.subtrahend)) by_difference[d.minuend] = d.symbol + d.subtrahend;
  if (by_difference.empty()) return e;
  return e.subs(by_difference).expand();
}

ex Typesetter::substitute_expanded_norms(const ex& e) const {
  ex best = e;
  std::size_t best_length = print(e).size();
  // The norms of more components first: |v|^2 before its x-y part.
  std::vector<const Norm*> order;
  for (const auto& n : norms_) order.push_back(&n);
  std::stable_sort(order.begin(), order.end(),
                   [](const Norm* a, const Norm* b) { return a->components.size() > b->components.size(); });
  for (const Norm* norm : order) {
    const Norm& n = *norm;
    if (!std::all_of(n.components.begin(), n.components.end(), [&](const ex& c) { return best.has(c); })) continue;
    ex rest = GiNaC::pow(n.symbol, 2);
    for (std::size_t i = 1; i < n.components.size(); ++i) rest -= GiNaC::pow(n.components[i], 2);
    const ex candidate = best.subs(GiNaC::pow(n.components[0], 2) == rest, GiNaC::subs_options::algebraic).expand();
    const std::size_t length = print(candidate).size();
    if (length < best_length) {
      best = candidate;
      best_length = length;
    }
  }
  return best;
}

namespace {

// The shortest LaTeX among `e` with its common factors collected and `e` factored (factoring only
// a polynomial of few terms: its cost grows fast with their number).
// A product with each factor (or power's base) expanded: factor() returns an irreducible factor
// collected in the variable it chose as its main one, which follows GiNaC's term order too.
ex with_expanded_factors(const ex& product) {
  const auto expanded = [](const ex& f) {
    return GiNaC::is_a<GiNaC::power>(f) ? GiNaC::pow(f.op(0).expand(), f.op(1)) : f.expand();
  };
  if (!GiNaC::is_a<GiNaC::mul>(product)) return expanded(product);
  ex out = 1;
  for (const auto& f : product) out *= expanded(f);
  return out;
}

ex shortest_form(const ex& coefficient) {
  // From the expanded form: GiNaC's collect leaves a coefficient partly grouped, and
  // collect_common_factors then groups it further, both in GiNaC's term order, which follows
  // memory addresses (S05's costate rows came out grouped differently from run to run).
  const ex e = coefficient.expand();
  std::vector<ex> forms = {e};
  try {
    forms.push_back(GiNaC::collect_common_factors(e));
  } catch (const std::exception&) {
    // Not a form GiNaC groups (a non-integer power inside): the others stand.
  }
  if (term_count(e) <= 24) {
    try {
      forms.push_back(with_expanded_factors(GiNaC::factor(e)));
    } catch (const std::exception&) {
      // Not a form GiNaC factors: the others stand.
    }
  }
  ex best = e;
  std::size_t best_length = std::string::npos;
  for (const auto& f : forms) {
    const std::size_t length = Typesetter::print(f).size();
    if (length < best_length) {
      best = f;
      best_length = length;
    }
  }
  return best;
}

}  // namespace

ex Typesetter::collected(const ex& e) const {
  if (!GiNaC::is_a<GiNaC::add>(e)) return shortest_form(e);
  GiNaC::lst by;
  for (const auto& n : norms_)
    if (e.has(n.symbol)) by.append(n.symbol);
  if (by.nops() == 0) return shortest_form(e);
  // Terms grouped by the powers of the norms they carry, each group's coefficient made short.
  const ex grouped = GiNaC::collect(e, by, true);
  if (!GiNaC::is_a<GiNaC::add>(grouped)) return shortest_form(grouped);
  ex out = 0;
  for (const auto& term : grouped) {
    ex norms = 1, coefficient = 1;
    const ex factors = GiNaC::is_a<GiNaC::mul>(term) ? term : ex(GiNaC::lst{term});
    for (const auto& f : factors) {
      const ex base = GiNaC::is_a<GiNaC::power>(f) ? f.op(0) : f;
      if (std::any_of(by.begin(), by.end(), [&](const ex& n) { return base.is_equal(n); }))
        norms *= f;
      else
        coefficient *= f;
    }
    out += shortest_form(coefficient) * norms;
  }
  return out;
}

ex Typesetter::compact(const ex& stored) {
  const ex p = printable(stored);
  learn_printable(p);  // new quantities named in the order of their text, not of GiNaC's terms
  ex best = name_power_bases(p);
  std::size_t best_length = print(best).size();
  const auto keep_if_shorter = [&](const ex& candidate) {
    const std::size_t length = print(candidate).size();
    if (length < best_length) {
      best = candidate;
      best_length = length;
    }
  };
  // A form GiNaC cannot take (collect's degrees of a power with a non-integer exponent inside a
  // sum, as a solar-electric engine's smooth cap has) leaves the others standing.
  const auto try_form = [&](const auto& form) {
    try {
      keep_if_shorter(form());
    } catch (const std::exception&) {
    }
  };
  try_form([&] { return substitute_differences(best); });
  try_form([&] { return substitute_expanded_norms(best); });
  try_form([&] { return collected(best); });
  for (const auto& n : norms_)
    if (best.has(n.symbol)) used_.insert(n.symbol.get_name());
  for (const auto& d : differences_)
    if (best.has(d.symbol)) used_.insert(d.symbol.get_name());
  return best;
}

std::vector<NamedQuantity> Typesetter::definitions() const {
  // A used norm of named differences uses them too.
  std::set<std::string> used = used_;
  for (const auto& n : norms_)
    if (used.count(n.symbol.get_name()))
      for (const auto& c : n.components) used.insert(GiNaC::ex_to<GiNaC::symbol>(c).get_name());
  std::vector<NamedQuantity> out;
  for (const auto& d : differences_)
    if (used.count(d.symbol.get_name()))
      out.push_back({print(d.symbol), print(d.minuend) + " - " + print(d.subtrahend)});
  for (const auto& n : norms_) {
    if (!used.count(n.symbol.get_name())) continue;
    out.push_back({print(n.symbol), print(GiNaC::sqrt(sum_of_squares(n.components)))});
  }
  return out;
}

std::vector<std::string> Typesetter::latex_lines(const ex& e, std::size_t width) {
  const ex c = compact(e);
  if (!GiNaC::is_a<GiNaC::add>(c)) return {print(c)};
  const std::vector<std::string> terms = sorted_terms(c);
  const std::string whole = joined_terms(terms);
  if (whole.size() <= width) return {whole};
  std::vector<std::string> lines;
  std::string line;
  for (std::string t : terms) {
    const bool negative = !t.empty() && t[0] == '-';
    if (negative) t.erase(0, 1);
    const std::string piece = line.empty() && lines.empty() ? (negative ? "-" : "") + t : (negative ? "- " : "+ ") + t;
    if (!line.empty() && line.size() + piece.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + piece;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

ex Typesetter::expanded_back(const ex& compact_form, const GiNaC::symtab& table) const {
  GiNaC::exmap back;
  for (const auto& n : norms_) {
    back[n.symbol] = GiNaC::sqrt(sum_of_squares(n.components));
  }
  ex e = compact_form.subs(back);
  back.clear();
  for (const auto& d : differences_) back[d.symbol] = d.minuend - d.subtrahend;
  e = e.subs(back);
  back.clear();
  for (const auto& [name, printable] : printable_)
    if (auto it = table.find(name); it != table.end()) back[printable] = it->second;
  return e.subs(back);
}

}  // namespace helios::symbolic

#include "helios/symbolic/expr.hpp"

#include "helios/symbolic/compare.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <typeinfo>

#include <sys/personality.h>
#include <unistd.h>

namespace helios::symbolic {

const GiNaC::symbol& SymbolTable::get(const std::string& name) {
  auto it = table_.find(name);
  if (it == table_.end()) it = table_.emplace(name, GiNaC::symbol(name)).first;
  return GiNaC::ex_to<GiNaC::symbol>(it->second);
}

GiNaC::ex SymbolTable::parse(const std::string& text, const std::string& where) const {
  // The message goes into JSON artifacts, which must be UTF-8: the text (valid UTF-8, as it came
  // from JSON) is cut at a character's start, and GiNaC's reason, which quotes a lone byte of a
  // multi-byte character it does not know, has every byte outside ASCII shown as '?'.
  const auto shown = [](const std::string& t) {
    std::size_t cut = std::min<std::size_t>(t.size(), 200);
    while (cut > 0 && cut < t.size() && (static_cast<unsigned char>(t[cut]) & 0xC0) == 0x80) --cut;
    return cut < t.size() ? t.substr(0, cut) + "..." : t;
  };
  const auto fail = [&](std::string why) {
    for (char& c : why)
      if (static_cast<unsigned char>(c) >= 0x80) c = '?';
    return std::invalid_argument(where + ": cannot parse expression '" + shown(text) + "': " + why);
  };
  if (text.size() > kMaxExpressionChars)
    throw fail("it is " + std::to_string(text.size()) + " characters; the limit is " +
               std::to_string(kMaxExpressionChars));
  int depth = 0;
  for (const char c : text)
    if (c == '(' && ++depth > kMaxExpressionDepth)
      throw fail("parentheses nested deeper than " + std::to_string(kMaxExpressionDepth) + " levels");
    else if (c == ')')
      --depth;
  GiNaC::parser reader(table_, true);
  GiNaC::ex e;
  try {
    e = reader(text);
  } catch (const std::exception& error) {
    // GiNaC's message continues with the parser's source location on further lines.
    const std::string why = error.what();
    throw fail(why.substr(0, why.find('\n')));
  }
  double terms = expanded_terms(e);
  for (const auto& name : free_symbols(e))
    terms = std::max(terms, expanded_terms(e.diff(GiNaC::ex_to<GiNaC::symbol>(table_.at(name)))));
  const auto too_much = [&](double n, const std::string& how, double limit) {
    std::ostringstream why;
    why.precision(2);
    why << where << ": expression '" << shown(text) << "'" << how << " would expand to about " << n
        << " terms; the limit of the symbolic work is " << limit << " terms";
    return std::invalid_argument(why.str());
  };
  if (terms > kMaxExpandedTerms) throw too_much(terms, " (or a first derivative of it)", kMaxExpandedTerms);
  if (substitutions_.empty()) return e;
  // An intermediate named in it stands for its whole expression: the work of the expression so
  // made (each intermediate may be a power of the one before), bounded in nodes first.
  const GiNaC::ex substituted = e.subs(substitutions_);
  if (substituted.is_equal(e)) return e;
  if (tree_size(substituted, kMaxSubstitutedNodes) > kMaxSubstitutedNodes)
    throw std::invalid_argument(where + ": expression '" + shown(text) +
                                "' with its intermediates substituted has more than " +
                                std::to_string(kMaxSubstitutedNodes) + " nodes");
  if (const double n = expanded_terms(substituted); n > kMaxSubstitutedTerms)
    throw too_much(n, " with its intermediates substituted", kMaxSubstitutedTerms);
  return substituted;
}

namespace {

// C(n + k - 1, k) in floating point: the monomials of degree k in n variables.
double monomials(double n, double k) {
  return std::exp(std::lgamma(n + k) - std::lgamma(k + 1) - std::lgamma(n));
}

// The terms of e's expansion; `worst` collects the largest expansion nested in a function or a
// power that expand() leaves as one factor.
double expanded_terms(const GiNaC::ex& e, double& worst) {
  double terms = 1;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    terms = 0;
    for (const auto& op : e) terms += expanded_terms(op, worst);
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    for (const auto& op : e) terms *= expanded_terms(op, worst);
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    const double base = expanded_terms(e.op(0), worst);
    const GiNaC::ex& k = e.op(1);
    if (GiNaC::is_a<GiNaC::numeric>(k) && GiNaC::ex_to<GiNaC::numeric>(k).is_pos_integer())
      terms = base > 1 ? monomials(base, GiNaC::ex_to<GiNaC::numeric>(k).to_double()) : 1;
    else
      worst = std::max(worst, std::max(base, expanded_terms(k, worst)));
  } else {
    for (const auto& op : e) worst = std::max(worst, expanded_terms(op, worst));
  }
  return terms;
}

}  // namespace

double expanded_terms(const GiNaC::ex& e) {
  double worst = 0;
  return std::max(expanded_terms(e, worst), worst);
}

namespace {

// A printer whose output depends only on the expression, not on GiNaC's internal term order
// (which follows hash values and so memory addresses): terms and factors are sorted by their
// printed text. Three dialects: GiNaC's own syntax (parsed back by GiNaC::parser), C++ on doubles
// (std::pow, std::sin, ...), and C++ for any scalar type (the functions unqualified, so that
// argument-dependent lookup finds the overloads of a type such as the runtime's dual numbers).
enum class Dialect { Text, Cpp, CppGeneric };
enum Precedence { kSum = 1, kProduct = 2, kPower = 3, kAtom = 4 };

struct Printed {
  std::string text;
  int precedence;
};

std::string wrap(const Printed& p, int needed) {
  return p.precedence < needed ? "(" + p.text + ")" : p.text;
}

Printed print(const GiNaC::ex& e, Dialect d);

Printed print_numeric(const GiNaC::numeric& n, Dialect d) {
  std::ostringstream out;
  if (d != Dialect::Text) {
    if (n.is_integer()) {
      out << n << ".0";
    } else if (n.is_rational()) {
      out << n.numer() << ".0/" << n.denom() << ".0";
    } else {
      out.precision(17);
      out << n.to_double();
    }
  } else {
    out << n;
  }
  const std::string t = out.str();
  const bool atomic = n.is_integer() && n.is_nonneg_integer();
  return {t, atomic ? kAtom : (t[0] == '-' ? kSum : kProduct)};
}

Printed print_power(const GiNaC::ex& base, const GiNaC::ex& exponent, Dialect d) {
  const Printed b = print(base, d);
  if (GiNaC::is_a<GiNaC::numeric>(exponent)) {
    const GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(exponent);
    if (k == GiNaC::numeric(1, 2)) return {"sqrt(" + b.text + ")", kAtom};
    // In C++, an integer or half-integer power up to 9/2 is products and one sqrt: pow costs tens
    // of multiplications, and the gravity terms' r^-5/2 and r^-7/2 sit in every right-hand side.
    const GiNaC::numeric twice = 2 * GiNaC::abs(k);
    if (d != Dialect::Text && twice.is_integer() && twice <= 9 && k != 1) {
      const std::string bb = wrap(b, kAtom);
      const int whole = twice.to_int() / 2;  // abs(k) rounded down
      std::vector<std::string> factors(static_cast<std::size_t>(whole), bb);
      if (!GiNaC::abs(k).is_integer()) factors.push_back("sqrt(" + b.text + ")");
      std::string product;
      for (const auto& f : factors) product += (product.empty() ? "" : "*") + f;
      if (k.is_positive()) return {product, kProduct};
      return {"1.0/" + (factors.size() == 1 ? product : "(" + product + ")"), kProduct};
    }
  }
  if (d != Dialect::Text)
    return {std::string(d == Dialect::Cpp ? "std::" : "") + "pow(" + b.text + ", " + print(exponent, d).text + ")",
            kAtom};
  const Printed x = print(exponent, d);
  return {wrap(b, kAtom) + "^" + wrap(x, kAtom), kPower};
}

Printed print(const GiNaC::ex& e, Dialect d) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return print_numeric(GiNaC::ex_to<GiNaC::numeric>(e), d);
  if (GiNaC::is_a<GiNaC::symbol>(e)) return {GiNaC::ex_to<GiNaC::symbol>(e).get_name(), kAtom};
  if (GiNaC::is_a<GiNaC::add>(e)) {
    std::vector<std::string> terms;
    for (const auto& op : e) terms.push_back(print(op, d).text);
    std::sort(terms.begin(), terms.end());
    std::string out;
    for (const auto& t : terms) out += out.empty() || t[0] == '-' ? t : "+" + t;
    return {out, kSum};
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    std::vector<std::string> factors;
    std::string sign;
    GiNaC::numeric coefficient = 1;
    for (const auto& op : e) {
      if (GiNaC::is_a<GiNaC::numeric>(op))
        coefficient *= GiNaC::ex_to<GiNaC::numeric>(op);
      else
        factors.push_back(wrap(print(op, d), kProduct));
    }
    std::sort(factors.begin(), factors.end());
    if (coefficient.is_negative()) {
      sign = "-";
      coefficient = -coefficient;
    }
    if (coefficient != 1) factors.insert(factors.begin(), wrap(print_numeric(coefficient, d), kPower));
    std::string out;
    for (const auto& f : factors) out += (out.empty() ? "" : "*") + f;
    return {sign + out, sign.empty() ? kProduct : kSum};
  }
  if (GiNaC::is_a<GiNaC::power>(e)) return print_power(e.op(0), e.op(1), d);
  if (GiNaC::is_a<GiNaC::function>(e)) {
    std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (d == Dialect::Cpp) name = "std::" + name;
    std::string args;
    for (const auto& op : e) args += (args.empty() ? "" : ", ") + print(op, d).text;
    return {name + "(" + args + ")", kAtom};
  }
  std::ostringstream raw;
  raw << e;
  throw std::invalid_argument("cannot print expression " + raw.str());
}

}  // namespace

void fix_expression_order(char** argv) {
  const int current = personality(0xffffffff);
  if (current == -1 || (current & ADDR_NO_RANDOMIZE) != 0) return;
  if (personality(static_cast<unsigned long>(current) | ADDR_NO_RANDOMIZE) == -1) return;
  execv("/proc/self/exe", argv);
  personality(static_cast<unsigned long>(current));  // exec failed: carry on as before
}

std::vector<std::string> identifiers(const std::string& text) {
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

bool is_identifier(const std::string& s) {
  return !s.empty() && (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_') &&
         std::all_of(s.begin(), s.end(),
                     [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
}

// NOTE: printing the expanded form makes the text independent of how GiNaC normalized the
// signs of sums inside products, which depends on its term order.
std::string to_text(const GiNaC::ex& e) {
  return print(e.expand(), Dialect::Text).text;
}

std::string to_csrc(const GiNaC::ex& e, CppScalar scalar) {
  return print(e.expand(), scalar == CppScalar::Double ? Dialect::Cpp : Dialect::CppGeneric).text;
}

double evaluate(const GiNaC::ex& e, const SymbolTable& table, const Values& values) {
  GiNaC::exmap m;
  for (const auto& [name, value] : values) {
    if (table.has(name)) m[table.symtab().at(name)] = value;
  }
  const GiNaC::ex v = GiNaC::evalf(e.subs(m));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) {
    const auto missing = free_symbols(v);
    throw std::invalid_argument("no value for symbol " + (missing.empty() ? to_text(v) : missing.front()));
  }
  const GiNaC::numeric n = GiNaC::ex_to<GiNaC::numeric>(v);
  if (!n.is_real()) throw std::domain_error("expression " + to_text(e) + " is not real at the given point");
  const double d = n.to_double();
  if (!std::isfinite(d)) throw std::domain_error("expression " + to_text(e) + " is not finite at the given point");
  return d;
}

std::vector<std::string> free_symbols(const GiNaC::ex& e) {
  std::set<std::string> names;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) names.insert(GiNaC::ex_to<GiNaC::symbol>(*it).get_name());
  return {names.begin(), names.end()};
}

bool symbolically_equal(const GiNaC::ex& a, const GiNaC::ex& b) {
  const GiNaC::ex d = (a - b).expand();
  if (d.is_zero()) return true;
  return GiNaC::normal(d).is_zero();
}

}  // namespace helios::symbolic

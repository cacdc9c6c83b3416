#include "helios/symbolic/compare.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "helios/symbolic/expr.hpp"

namespace helios::symbolic {
namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;

// The substitution B^(k/2) -> w^k, one new symbol w per distinct base B.
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

std::vector<ex> terms_of(const ex& e) {
  std::vector<ex> out;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const auto& t : e) out.push_back(t);
  } else if (!e.is_zero()) {
    out.push_back(e);
  }
  return out;
}

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

}  // namespace

std::string print(const ex& e) {
  try {
    return to_text(e);
  } catch (const std::exception&) {
    std::ostringstream out;
    out << e;
    return out.str();
  }
}

std::size_t tree_size(const ex& e, std::size_t limit) {
  std::size_t n = 0;
  for (auto i = e.preorder_begin(); i != e.preorder_end() && n <= limit; ++i) ++n;
  return n;
}

bool exact_equal(const ex& a, const ex& b) {
  if (tree_size(a, kExactBudget) + tree_size(b, kExactBudget) > kExactBudget) return false;
  try {
    if (symbolically_equal(a, b)) return true;
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

bool exact_proportional(const ex& a, const ex& b) {
  if (tree_size(a, kExactBudget) + tree_size(b, kExactBudget) > kExactBudget) return false;
  try {
    if (exact_equal(a, b) || exact_equal(a, -b)) return true;
    const ex r = GiNaC::normal(a / b);
    return GiNaC::is_a<numeric>(r) && !r.is_zero();
  } catch (const std::exception&) {
    return false;
  }
}

ex tidy(const ex& e) {
  // Beyond a few exact budgets the grouping's normal() runs for minutes (a fitted thruster's rows
  // with its intermediates substituted): the feedback then shows the expression as it is.
  if (tree_size(e, kTidyBudget) > kTidyBudget) return e;
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

}  // namespace helios::symbolic

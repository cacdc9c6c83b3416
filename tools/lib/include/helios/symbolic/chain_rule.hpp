#pragma once
// Named intermediate quantities q_1, ..., q_k of an expression (the derivation's intermediates),
// each a function of other symbols and the earlier ones, and the derivative of an expression that
// holds them, by the chain rule through them: without substituting them, which would expand the
// powers of a fit of the power into thousands of terms. (A reader that checks a claim by its own
// arithmetic substitutes them instead: SymbolTable::substitute_on_parse.)
#include <ginac/ginac.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace helios::symbolic {

class ChainRule {
 public:
  // q = expression; `expression` may hold the intermediates added before, not q or later ones.
  void add(const GiNaC::symbol& q, const GiNaC::ex& expression);
  // From here on diff() writes q's own partial derivative in x (at fixed earlier intermediates) as
  // the symbol `named` (itself an intermediate of that value), not as its expression: the writer
  // of a derivation keeps an input power's gradient by name in every costate equation.
  void name_partial(const GiNaC::symbol& q, const GiNaC::symbol& x, const GiNaC::symbol& named);
  bool empty() const { return order_.empty(); }
  // de/dx = the partial derivative plus sum_q de/dq dq/dx, dq/dx by the same rule (remembered).
  // x is any symbol but an intermediate.
  GiNaC::ex diff(const GiNaC::ex& e, const GiNaC::symbol& x) const;
  // The intermediates in order: name and expression (in the symbols and the earlier ones).
  const std::vector<std::pair<GiNaC::symbol, GiNaC::ex>>& order() const { return order_; }

 private:
  // dq_i/dx through the intermediates, remembered.
  const GiNaC::ex& total(std::size_t i, const GiNaC::symbol& x) const;

  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> order_;
  std::map<std::pair<std::size_t, std::string>, GiNaC::ex> named_;  // (q's index, x) -> its partial's symbol
  mutable std::map<std::pair<std::size_t, std::string>, GiNaC::ex> derivatives_;  // (q's index, x) -> dq/dx
};

}  // namespace helios::symbolic

#include "helios/symbolic/chain_rule.hpp"

#include <stdexcept>

namespace helios::symbolic {

void ChainRule::add(const GiNaC::symbol& q, const GiNaC::ex& expression) {
  if (expression.has(q))
    throw std::invalid_argument("the intermediate " + q.get_name() + " is defined in terms of itself");
  for (const auto& [earlier, unused] : order_)
    if (earlier.is_equal(q)) throw std::invalid_argument("the intermediate " + q.get_name() + " is defined twice");
  order_.emplace_back(q, expression);
}

void ChainRule::name_partial(const GiNaC::symbol& q, const GiNaC::symbol& x, const GiNaC::symbol& named) {
  for (std::size_t i = 0; i < order_.size(); ++i)
    if (order_[i].first.is_equal(q)) {
      named_[{i, x.get_name()}] = named;
      derivatives_.clear();
      return;
    }
  throw std::invalid_argument("no intermediate " + q.get_name() + " to name the partial derivative of");
}

const GiNaC::ex& ChainRule::total(std::size_t i, const GiNaC::symbol& x) const {
  const auto key = std::make_pair(i, x.get_name());
  if (const auto it = derivatives_.find(key); it != derivatives_.end()) return it->second;
  const GiNaC::ex& expression = order_[i].second;
  const auto named = named_.find(key);
  GiNaC::ex d = named != named_.end() ? named->second : expression.diff(x);
  for (std::size_t j = 0; j < i; ++j)
    if (expression.has(order_[j].first)) {
      const GiNaC::ex& dj = total(j, x);
      if (!dj.is_zero()) d += expression.diff(order_[j].first) * dj;
    }
  return derivatives_.emplace(key, d).first->second;
}

GiNaC::ex ChainRule::diff(const GiNaC::ex& e, const GiNaC::symbol& x) const {
  GiNaC::ex d = e.diff(x);
  for (std::size_t i = 0; i < order_.size(); ++i) {
    if (!e.has(order_[i].first)) continue;
    const GiNaC::ex& di = total(i, x);
    if (!di.is_zero()) d += e.diff(order_[i].first) * di;
  }
  return d;
}

}  // namespace helios::symbolic

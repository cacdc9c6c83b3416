// The fuel cost: the mass flow Tmax u / c with the quadratic homotopy term, L = Tmax/c (u - eps
// u (1 - u)): eps = 1 is an energy-like problem, eps = 0 the bang-bang fuel-optimal one
// (Bertrand & Epenoy; Jiang, Baoyin & Li 2012).
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class FuelCost : public CostTerm {
 public:
  std::string name() const override { return "fuel"; }
  std::vector<std::string> parameters() const override { return {"Tmax", "c"}; }
  ex running_cost(Problem& p) const override {
    auto& S = p.symbols;
    const ex TM = S.get("Tmax"), C = S.get("c"), u = S.get("u"), eps = S.get("eps");
    return TM / C * (u - eps * u * (1 - u));
  }
};

}  // namespace

std::unique_ptr<CostTerm> fuel_cost() {
  return std::make_unique<FuelCost>();
}

}  // namespace helios::pmp::terms

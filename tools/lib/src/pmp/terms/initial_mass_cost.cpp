// The initial-mass cost: with m(tf) fixed, m0 is the fuel m0 - m(tf) up to a constant, so the
// fuel's running cost (with its homotopy term) minimizes the initial mass.
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class InitialMassCost : public CostTerm {
 public:
  std::string name() const override { return "initial_mass"; }
  std::vector<std::string> parameters() const override { return fuel_->parameters(); }
  ex running_cost(Problem& p) const override { return fuel_->running_cost(p); }

 private:
  std::unique_ptr<CostTerm> fuel_ = fuel_cost();
};

}  // namespace

std::unique_ptr<CostTerm> initial_mass_cost() {
  return std::make_unique<InitialMassCost>();
}

}  // namespace helios::pmp::terms

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

namespace helios::pmp::catalogue {

std::vector<TermEntry> initial_mass_cost() {
  TermEntry e;
  e.name = "initial_mass";
  e.kind = "cost";
  e.order = 120;
  e.summary = "the initial mass with the final mass given, the fuel's L = Tmax/c (u - eps u (1 - u))";
  e.parameters = {{"Tmax", "maximum thrust", "mass*length/time^2", "thrust_scale"},
                  {"c", "exhaust velocity Isp*g0", "length/time", "exhaust_velocity"}};
  e.required = 2;
  return {e};
}

}  // namespace helios::pmp::catalogue

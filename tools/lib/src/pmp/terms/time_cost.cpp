// The time cost: L = 1, the time of flight.
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class TimeCost : public CostTerm {
 public:
  std::string name() const override { return "time"; }
  std::vector<std::string> parameters() const override { return {}; }
  ex running_cost(Problem&) const override { return 1; }
};

}  // namespace

std::unique_ptr<CostTerm> time_cost() {
  return std::make_unique<TimeCost>();
}

}  // namespace helios::pmp::terms

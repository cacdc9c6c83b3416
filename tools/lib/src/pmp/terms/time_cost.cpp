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

namespace helios::pmp::catalogue {

std::vector<TermEntry> time_cost() {
  TermEntry e;
  e.name = "time";
  e.kind = "cost";
  e.order = 110;
  e.summary = "the time of flight, L = 1";
  return {e};
}

}  // namespace helios::pmp::catalogue

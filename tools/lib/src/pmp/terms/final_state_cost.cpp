// Objectives on the final state (Mayer terms), with no running cost: the final radius,
// phi = -|r(tf)|, and the final orbital energy, phi = -(|v(tf)|^2/2 - mu/|r(tf)|), both maximized
// (phi is minimized). The final time is fixed: with it free neither has a maximum.
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class FinalStateCost : public CostTerm {
 public:
  explicit FinalStateCost(bool energy) : energy_(energy) {}
  std::string name() const override { return energy_ ? "final_energy" : "final_radius"; }
  std::vector<std::string> parameters() const override {
    return energy_ ? std::vector<std::string>{"mu"} : std::vector<std::string>{};
  }
  ex running_cost(Problem&) const override { return 0; }
  ex endpoint_cost(Problem& p) const override {
    auto& S = p.symbols;
    const ex rx = S.get("rx"), ry = S.get("ry"), rz = S.get("rz"), vx = S.get("vx"), vy = S.get("vy"), vz = S.get("vz");
    const ex r = GiNaC::sqrt(rx * rx + ry * ry + rz * rz);
    if (!energy_) return -r;
    return -((vx * vx + vy * vy + vz * vz) / 2 - S.get("mu") / r);
  }

 private:
  bool energy_;
};

}  // namespace

std::unique_ptr<CostTerm> final_radius_cost() {
  return std::make_unique<FinalStateCost>(false);
}
std::unique_ptr<CostTerm> final_energy_cost() {
  return std::make_unique<FinalStateCost>(true);
}

}  // namespace helios::pmp::terms

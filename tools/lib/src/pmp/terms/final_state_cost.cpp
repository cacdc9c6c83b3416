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

namespace helios::pmp::catalogue {

std::vector<TermEntry> final_state_cost() {
  TermEntry radius;
  radius.name = "final_radius";
  radius.kind = "cost";
  radius.order = 130;
  radius.summary =
      "the final radius maximized, a Mayer term: running_cost 0, endpoint_cost -sqrt(rx^2+ry^2+rz^2), whose gradient "
      "enters lambda(tf) = lambda0 dphi/dx + nu^T dpsi/dx";
  TermEntry energy = radius;
  energy.name = "final_energy";
  energy.summary =
      "the final orbital energy maximized, a Mayer term: running_cost 0, endpoint_cost -((vx^2+vy^2+vz^2)/2 - "
      "mu/sqrt(rx^2+ry^2+rz^2))";
  energy.parameters = {{"mu", "gravitational parameter of the central body", "length^3/time^2"}};
  energy.required = 1;
  return {radius, energy};
}

}  // namespace helios::pmp::catalogue

// The fuel cost: the engine's mass flow at full throttle F (Tmax/c, a solar-electric engine's
// T(r)/c, as its term records it) with the quadratic homotopy term,
// L = F (u - eps u (1 - u)): eps = 1 is an energy-like problem, eps = 0 the bang-bang fuel-optimal
// one (Bertrand & Epenoy; Jiang, Baoyin & Li 2012). An engine of constant mass has the same L1 cost
// (Tmax/c: the propellant it would burn); without an exhaust velocity its cost is the delta-v,
// L = Tmax/mass (u - eps u (1 - u)) (delta_v).
#include <algorithm>

#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class FuelCost : public CostTerm {
 public:
  explicit FuelCost(bool delta_v) : delta_v_(delta_v) {}
  std::string name() const override { return delta_v_ ? "delta_v" : "fuel"; }
  std::vector<std::string> parameters() const override { return parameters_; }
  ex running_cost(Problem& p) const override {
    auto& S = p.symbols;
    const ex u = S.get("u"), eps = S.get("eps");
    if (!delta_v_) {
      parameters_ = p.flow_parameters;
      return p.max_mass_flow * (u - eps * u * (1 - u));
    }
    // The acceleration, whose integral is the delta-v: the thrust's parameters and the mass.
    parameters_ = p.thrust_parameters;
    parameters_.push_back("mass");
    return p.max_thrust / S.get("mass") * (u - eps * u * (1 - u));
  }

 private:
  bool delta_v_;
  mutable std::vector<std::string> parameters_;
};

}  // namespace

std::unique_ptr<CostTerm> fuel_cost() {
  return std::make_unique<FuelCost>(false);
}

std::unique_ptr<CostTerm> delta_v_cost() {
  return std::make_unique<FuelCost>(true);
}

}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> fuel_cost() {
  TermEntry fuel;
  fuel.name = "fuel";
  fuel.kind = "cost";
  fuel.order = 100;
  fuel.summary =
      "the propellant, L = Tmax/c (u - eps u (1 - u)); with a solar-electric engine the engine's parameters, L = "
      "T(r)/c (u - eps u (1 - u))";
  fuel.parameters = {{"Tmax", "maximum thrust", "mass*length/time^2", "thrust_scale"},
                     {"c", "exhaust velocity Isp*g0", "length/time", "exhaust_velocity"}};
  fuel.required = 2;
  TermEntry delta_v = fuel;
  delta_v.name = "delta_v";
  delta_v.summary = "the delta-v of an engine of constant mass without an Isp, L = Tmax/mass (u - eps u (1 - u))";
  delta_v.parameters[1] = {"mass", "the constant mass: 1, the mass unit", "mass"};
  return {fuel, delta_v};
}

}  // namespace helios::pmp::catalogue

// The fuel cost: the mass flow T u / c (T the engine's full thrust: Tmax, or a solar-electric
// engine's T(r)), for a constant engine the mass flow Tmax u / c with the quadratic homotopy term, L = Tmax/c (u - eps
// u (1 - u)): eps = 1 is an energy-like problem, eps = 0 the bang-bang fuel-optimal one
// (Bertrand & Epenoy; Jiang, Baoyin & Li 2012). An engine of constant mass has the same L1 cost
// (Tmax/c: the propellant it would burn); without an exhaust velocity its cost is the delta-v,
// L = Tmax/mass (u - eps u (1 - u)) (delta_v).
#include <algorithm>

#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class FuelCost : public CostTerm {
 public:
  // `per`: the parameter the thrust is divided by (c: the propellant's mass flow, mass: the
  // acceleration, whose integral is the delta-v).
  explicit FuelCost(std::string per) : per_(std::move(per)) {}
  std::string name() const override { return per_ == "c" ? "fuel" : "delta_v"; }
  // The engine's thrust parameters (Tmax, or a solar-electric engine's, which list c already) and per.
  std::vector<std::string> parameters(const Problem& p) const {
    std::vector<std::string> out = p.thrust_parameters;
    if (std::find(out.begin(), out.end(), per_) == out.end()) out.push_back(per_);
    return out;
  }
  std::vector<std::string> parameters() const override { return parameters_; }
  ex running_cost(Problem& p) const override {
    auto& S = p.symbols;
    parameters_ = parameters(p);
    const ex TM = p.max_thrust, C = S.get(per_), u = S.get("u"), eps = S.get("eps");
    return TM / C * (u - eps * u * (1 - u));
  }

 private:
  std::string per_;
  mutable std::vector<std::string> parameters_ = {"Tmax", per_};
};

}  // namespace

std::unique_ptr<CostTerm> fuel_cost() {
  return std::make_unique<FuelCost>("c");
}

std::unique_ptr<CostTerm> delta_v_cost() {
  return std::make_unique<FuelCost>("mass");
}

}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> fuel_cost() {
  TermEntry fuel;
  fuel.name = "fuel";
  fuel.kind = "cost";
  fuel.order = 100;
  fuel.summary =
      "the propellant, L = Tmax/c (u - eps u (1 - u)); with a solar-electric engine its parameters, L = T(r)/c (u - "
      "eps u (1 - u))";
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

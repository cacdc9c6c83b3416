// Two-body gravity of the central body: a = -mu r/|r|^3, the gradient of the potential mu/|r|.
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class TwoBody : public ForceTerm {
 public:
  TwoBody(const json& central, const Units& U)
      : mu_(normalized_mu(central.at("mu_km3_s2").get<double>(), U)), unit_(mu_unit(U)) {}
  std::string name() const override { return "two_body"; }
  std::vector<Named> parameters() const override {
    return {{"mu", "gravitational parameter of the central body", unit_, mu_}};
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    const ex mu = p.symbols.get("mu");
    const ex r3 = GiNaC::pow(x.r[0] * x.r[0] + x.r[1] * x.r[1] + x.r[2] * x.r[2], GiNaC::numeric(3, 2));
    return {-mu * x.r[0] / r3, -mu * x.r[1] / r3, -mu * x.r[2] / r3};
  }

 private:
  double mu_;
  std::string unit_;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  return std::make_unique<TwoBody>(s.spec.at("central_body"), s.problem.units);
}

}  // namespace

TermListing listing(const std::string& name, const std::string& kind, const std::vector<std::string>& parameters,
                    const json& details) {
  return {name, kind, parameters, details};
}

}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> two_body() {
  TermEntry e;
  e.name = "two_body";
  e.kind = "force";
  e.summary = "the central body's gravity, -mu r/|r|^3";
  e.parameters = {{"mu", "gravitational parameter of the central body", "length^3/time^2"}};
  e.required = 1;
  e.field = e.axially_symmetric = true;
  e.order = 10;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

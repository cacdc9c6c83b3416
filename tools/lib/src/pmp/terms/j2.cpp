// The J2 zonal term of the central body (z along its pole), the gradient of the potential
// -J2 mu R^2 / (2 r^3) (3 z^2/r^2 - 1):
// a_J2 = -3/2 J2 mu R^2 / r^5 [x (1 - 5 z^2/r^2), y (1 - 5 z^2/r^2), z (3 - 5 z^2/r^2)].
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class J2 : public ForceTerm {
 public:
  J2(const json& central, const Units& U)
      : j2_(central.at("j2").get<double>()),
        radius_(central.at("radius_km").get<double>() / U.length_km),
        length_(U.length_name) {}
  std::string name() const override { return "j2"; }
  std::vector<Named> parameters() const override {
    return {{"J2", "J2 zonal coefficient of the central body", "1", j2_},
            {"Req", "equatorial radius of the central body", length_, radius_}};
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    const auto& r = x.r;
    const ex mu = p.symbols.get("mu"), j2 = p.symbols.get("J2"), R = p.symbols.get("Req");
    const ex r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const ex k = -GiNaC::numeric(3, 2) * j2 * mu * R * R / GiNaC::pow(r2, GiNaC::numeric(5, 2));
    const ex zz = 5 * r[2] * r[2] / r2;
    return {k * r[0] * (1 - zz), k * r[1] * (1 - zz), k * r[2] * (3 - zz)};
  }

 private:
  double j2_, radius_;
  std::string length_;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  return std::make_unique<J2>(s.spec.at("central_body"), s.problem.units);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> j2() {
  TermEntry e;
  e.name = "j2";
  e.kind = "force";
  e.summary = "the central body's J2 zonal term (needs two_body), the gradient of -J2 mu Req^2/(2 r^3) (3 z^2/r^2 - 1)";
  e.parameters = {{"J2", "J2 zonal coefficient of the central body", "1"},
                  {"Req", "equatorial radius of the central body", "length"}};
  e.required = 2;
  e.field = e.axially_symmetric = true;
  e.spec_kind = "j2";
  e.spec_schema = {{"additionalProperties", false}, {"properties", {{"kind", {{"const", "j2"}}}}}};
  e.order = 20;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

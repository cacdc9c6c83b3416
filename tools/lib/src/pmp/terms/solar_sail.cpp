// An ideal flat solar sail: a = ac (rref/r)^2 (n.rhat)^2 n, n the unit normal pointing away from
// the Sun (n.r >= 0), ac the characteristic acceleration at the distance rref.
#include "helios/astro/constants.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class SolarSail : public ForceTerm {
 public:
  SolarSail(const json& sc, const Units& U)
      : ac_(sc.at("sail_characteristic_acceleration_mm_s2").get<double>() * 1e-6 * U.time_s * U.time_s / U.length_km),
        rref_(sc.at("sail_reference_distance_AU").get<double>() * helios::astro::AU_KM / U.length_km),
        accel_unit_(acceleration_unit(U)),
        length_(U.length_name) {}
  std::string name() const override { return "solar_sail"; }
  std::vector<Control> controls() const override {
    return {{"nx", "sail normal x (unit vector, n.r >= 0)", "sail_normal"},
            {"ny", "sail normal y (unit vector, n.r >= 0)", "sail_normal"},
            {"nz", "sail normal z (unit vector, n.r >= 0)", "sail_normal"}};
  }
  std::vector<Named> parameters() const override {
    return {{"ac", "characteristic acceleration of the sail", accel_unit_, ac_},
            {"rref", "distance at which the characteristic acceleration holds", length_, rref_}};
  }
  // Records the sail's model (k, rhat) for the control law.
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    const auto& r = x.r;
    const ex rn = GiNaC::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const std::vector<ex> n = {S.get("nx"), S.get("ny"), S.get("nz")};
    const ex cos_cone = (n[0] * r[0] + n[1] * r[1] + n[2] * r[2]) / rn;
    const ex k = S.get("ac") * GiNaC::pow(S.get("rref") / rn, 2);
    p.sail = {k, {r[0] / rn, r[1] / rn, r[2] / rn}, {"vx", "vy", "vz"}};
    return {k * GiNaC::pow(cos_cone, 2) * n[0], k * GiNaC::pow(cos_cone, 2) * n[1], k * GiNaC::pow(cos_cone, 2) * n[2]};
  }

 private:
  double ac_, rref_;
  std::string accel_unit_, length_;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  if (s.problem.propulsion != "solar_sail") return nullptr;
  return std::make_unique<SolarSail>(s.spec.at("spacecraft"), s.problem.units);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> solar_sail() {
  TermEntry e;
  e.name = "solar_sail";
  e.kind = "force";
  e.summary = "an ideal flat sail, ac (rref/r)^2 (n.rhat)^2 n with the unit normal n (controls nx, ny, nz; n.r >= 0)";
  e.parameters = {{"ac", "characteristic acceleration of the sail", "length/time^2"},
                  {"rref", "distance at which the characteristic acceleration holds", "length"}};
  e.required = 2;
  e.engine = true;
  e.order = 30;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

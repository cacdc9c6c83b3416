// Atmospheric drag in an exponential atmosphere that turns with the central body:
//   a = -1/2 rho(r) Cd A / m |v_rel| v_rel,  rho(r) = rho0 exp(-(|r| - r0)/H),  v_rel = v - w z x r,
// rho0 the density at the reference radius r0 (the body's radius plus the reference altitude), H the
// scale height, w the atmosphere's rotation rate about the body's z axis (0: an atmosphere at rest
// in the frame) and Cd A the drag coefficient times the reference area. Its coefficients enter as
// one parameter, Bd = Cd A rho0 (in the normalized units a mass per length), and r0, H, w. It is
// not part of the natural field (a coasting target has its own area), turns with the body (axially
// symmetric) and needs the spacecraft's mass: an engine's or the constant mass; a sail has none.
#include <cmath>
#include <stdexcept>

#include "term.hpp"

namespace helios::pmp::terms {
namespace {

// The rotation rates [rad/s] of the bodies whose atmosphere turns with them by default (sidereal).
double known_rotation_rad_s(const std::string& body) {
  if (body == "Earth") return 7.2921159e-5;
  if (body == "Mars") return 7.088218e-5;
  return NAN;
}

class Drag : public ForceTerm {
 public:
  Drag(const json& q, const json& central, const Problem& p, std::string mass_unit)
      : L_(p.units.length_name), T_(p.units.time_name), mass_unit_(std::move(mass_unit)) {
    const Units& U = p.units;
    const std::string where = "field /dynamics/perturbations (drag)";
    if (U.length_name == "AU")
      throw std::invalid_argument(where + ": drag needs a planet with an atmosphere as the central body, not the Sun");
    if (p.propulsion == "solar_sail")
      throw std::invalid_argument(where + ": drag needs the spacecraft's mass, and a sail's is not stated");
    const std::string body = central.at("name").get<std::string>();
    double rotation = q.value("atmosphere_rotation_rad_s", known_rotation_rad_s(body));
    if (std::isnan(rotation))
      throw std::invalid_argument(where + "/atmosphere_rotation_rad_s is missing: the rotation of " + body +
                                  " is not known (state the atmosphere's rotation rate, or that it is at rest)");
    const double length_m = U.length_km * 1e3;
    // Cd A rho0 [kg/m] in mass units per length unit.
    coefficient_ = q.at("drag_coefficient").get<double>() * q.at("area_m2").get<double>() *
                   q.at("density_kg_m3").get<double>() * length_m / U.mass_kg;
    reference_ = (U.length_km + q.at("reference_altitude_km").get<double>()) / U.length_km;
    scale_ = q.at("scale_height_km").get<double>() / U.length_km;
    rotation_ = rotation * U.time_s;
    if (!(coefficient_ > 0) || !(scale_ > 0) || !std::isfinite(coefficient_ * reference_ * rotation_))
      throw std::domain_error(where + ": a coefficient is 0 or not finite in normalized units");
  }
  std::string name() const override { return "drag"; }
  std::vector<Named> parameters() const override {
    return {
        {"Bd", "drag coefficient times area times the density at r0 (Cd A rho0)", mass_unit_ + "/" + L_, coefficient_},
        {"r0", "reference radius of the atmosphere (the body's radius plus the reference altitude)", L_, reference_},
        {"H", "scale height of the atmosphere", L_, scale_},
        {"w", "rotation rate of the atmosphere about the z axis", "1/" + T_, rotation_}};
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    const ex w = S.get("w");
    const std::vector<ex> rel = {x.v[0] + w * x.r[1], x.v[1] - w * x.r[0], x.v[2]};
    const ex speed = GiNaC::sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
    const ex r = GiNaC::sqrt(x.r[0] * x.r[0] + x.r[1] * x.r[1] + x.r[2] * x.r[2]);
    const ex k = -S.get("Bd") / 2 * GiNaC::exp(-(r - S.get("r0")) / S.get("H")) * speed / x.mass;
    return {k * rel[0], k * rel[1], k * rel[2]};
  }

 private:
  std::string L_, T_, mass_unit_;
  double coefficient_ = 0, reference_ = 0, scale_ = 0, rotation_ = 0;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  return std::make_unique<Drag>(*s.perturbation, s.spec.at("central_body"), s.problem, s.mass_unit);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> drag() {
  TermEntry e;
  e.name = "drag";
  e.kind = "force";
  e.summary =
      "atmospheric drag in an exponential atmosphere turning with the body, -Bd/2 exp(-(|r| - r0)/H) |v_rel| v_rel/m "
      "with v_rel = (vx + w ry, vy - w rx, vz) (m the mass state, or 1 for a constant mass)";
  e.parameters = {
      TermParameter("Bd", "drag coefficient times area times the density at r0", "mass/length").typeset("B", "d"),
      {"r0", "reference radius of the atmosphere", "length"},
      {"H", "scale height", "length"},
      {"w", "rotation rate of the atmosphere about z", "1/time"}};
  e.required = 4;
  e.axially_symmetric = true;
  e.spec_kind = "drag";
  const io::json positive = {{"type", "number"}, {"exclusiveMinimum", 0}};
  e.spec_schema = {
      {"description",
       "atmospheric drag, -1/2 rho Cd A/m |v_rel| v_rel, in an exponential atmosphere rho = density_kg_m3 exp(-(h - "
       "reference_altitude_km)/scale_height_km) turning about the central body's z axis at atmosphere_rotation_rad_s "
       "(absent: the body's own rotation, known for the Earth and Mars; 0: at rest)"},
      {"required",
       {"kind", "drag_coefficient", "area_m2", "density_kg_m3", "reference_altitude_km", "scale_height_km"}},
      {"additionalProperties", false},
      {"properties",
       {{"kind", {{"const", "drag"}}},
        {"drag_coefficient", positive},
        {"area_m2", positive},
        {"density_kg_m3", positive},
        {"reference_altitude_km", {{"type", "number"}, {"minimum", 0}}},
        {"scale_height_km", positive},
        {"atmosphere_rotation_rad_s", {{"type", "number"}}}}}};
  e.order = 60;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

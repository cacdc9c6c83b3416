// A user-written acceleration of the spec (its components in the variables x, y, z, r [km],
// vx, vy, vz [km/s], m [kg], t [s], in mm/s^2, m/s^2 or km/s^2), in normalized units. The
// derivation lists its normalized components: a verifier has no other way to know them.
#include "helios/spec/parse.hpp"
#include "helios/spec/units.hpp"
#include "helios/symbolic/expr.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class UserAcceleration : public ForceTerm {
 public:
  explicit UserAcceleration(const json& pert) : pert_(pert) {}
  std::string name() const override { return "user_acceleration"; }
  std::vector<Named> parameters() const override { return {}; }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override;
  json details(const Problem&) const override {
    std::vector<std::string> text;
    for (const auto& a : components_) text.push_back(symbolic::to_text(a));
    return {{"label", pert_.at("name")}, {"acceleration", text}};
  }

 private:
  json pert_;
  mutable std::vector<ex> components_;
};

std::vector<ex> UserAcceleration::acceleration(Problem& p, const Frame& x) const {
  symbolic::SymbolTable vars;
  for (const char* v : spec::kAccelerationVariables) vars.get(v);
  const Units& U = p.units;
  auto& S = p.symbols;
  const auto& r = x.r;
  GiNaC::exmap to_model = {
      {vars.get("x"), r[0] * U.length_km},
      {vars.get("y"), r[1] * U.length_km},
      {vars.get("z"), r[2] * U.length_km},
      {vars.get("r"), GiNaC::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * U.length_km},
      {vars.get("vx"), x.v[0] * U.speed_km_s()},
      {vars.get("vy"), x.v[1] * U.speed_km_s()},
      {vars.get("vz"), x.v[2] * U.speed_km_s()},
      {vars.get("m"), x.mass * U.mass_kg},
      {vars.get("t"), S.get("t") * U.time_s},
  };
  // The spec unit of accelerations is mm/s^2 = 1e-6 km/s^2.
  const double to_km_s2 = spec::to_spec_unit(spec::Dimension::Acceleration, pert_.at("unit")) * 1e-6;
  const double scale = to_km_s2 * U.time_s * U.time_s / U.length_km;
  components_.clear();
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string where =
        "field /dynamics/perturbations (" + pert_.at("name").get<std::string>() + ")/components/" + std::to_string(i);
    components_.push_back(vars.parse(pert_.at("components")[i].get<std::string>(), where).subs(to_model) * scale);
  }
  return components_;
}

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  return std::make_unique<UserAcceleration>(*s.perturbation);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> user_acceleration() {
  TermEntry e;
  e.name = "user_acceleration";
  e.kind = "force";
  e.summary =
      "an acceleration the spec writes out, listed with its \"label\" and its three components in normalized units "
      "(\"acceleration\")";
  e.details = {"label", "acceleration"};
  e.spec_kind = "acceleration";
  e.spec_schema = {
      {"description",
       "user-written acceleration: components in variables x, y, z, r [km], vx, vy, vz [km/s], m [kg], t [s since t0]"},
      {"required", {"kind", "name", "components", "unit"}},
      {"additionalProperties", false},
      {"properties",
       {{"kind", {{"const", "acceleration"}}},
        {"name", {{"type", "string"}, {"pattern", "^[A-Za-z][A-Za-z0-9_]*$"}}},
        {"components",
         {{"type", "array"}, {"items", {{"type", "string"}, {"minLength", 1}}}, {"minItems", 3}, {"maxItems", 3}}},
        {"unit", {{"enum", {"mm/s^2", "m/s^2", "km/s^2"}}}}}}};
  e.order = 40;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

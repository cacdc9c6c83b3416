// A third body perturbing the spacecraft as a point mass mu3, direct and indirect parts (the
// central body is accelerated by it too):
//   a = mu3 ((r3 - r)/|r3 - r|^3 - r3/|r3|^3).
// The model of its motion: a circular orbit about the central body of radius a3, inclination i3,
// ascending node W3 and argument of latitude u0 at the time origin (t = 0), with the mean motion
// n3 = sqrt((mu + mu3)/a3^3):
//   r3(t) = a3 [cos W3 cos u - sin W3 sin u cos i3, sin W3 cos u + cos W3 sin u cos i3, sin u sin i3],
//   u = u0 + n3 t.
// Its position is a function of t the symbolic engine differentiates and the generator prints.
// Its parameters carry the body's name: mu_<name>, a_<name>, i_<name>, W_<name>, u0_<name>, n_<name>.
#include <cmath>
#include <stdexcept>

#include "term.hpp"

namespace helios::pmp::terms {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

class ThirdBody : public ForceTerm {
 public:
  ThirdBody(const json& pert, const json& central, const Units& U);
  std::string name() const override { return "third_body"; }
  std::vector<Named> parameters() const override;
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override;
  json details(const Problem&) const override { return {{"body", body_}}; }

 private:
  std::string body_, L_, T_;
  double mu_, a_, inc_, node_, phase_, n_;
  std::string sym(const std::string& stem) const { return stem + "_" + body_; }
};

ThirdBody::ThirdBody(const json& pert, const json& central, const Units& U)
    : body_(pert.at("name").get<std::string>()),
      L_(U.length_name),
      T_(U.time_name),
      mu_(normalized_mu(pert.at("mu_km3_s2").get<double>(), U)),
      a_(pert.at("orbit_radius_km").get<double>() / U.length_km),
      inc_(pert.value("inclination_deg", 0.0) * kDeg),
      node_(pert.value("raan_deg", 0.0) * kDeg),
      phase_(pert.value("phase_deg", 0.0) * kDeg) {
  const double mu_central = normalized_mu(central.at("mu_km3_s2").get<double>(), U);
  n_ = std::sqrt((mu_central + mu_) / (a_ * a_ * a_));
  if (!(mu_ > 0) || !(a_ > 0) || !std::isfinite(n_) || !(n_ > 0))
    throw std::domain_error("field /dynamics/perturbations (" + body_ +
                            "): its mu or orbit radius is 0 or not finite in normalized units");
}

std::vector<Named> ThirdBody::parameters() const {
  const std::string of = " of the third body " + body_;
  return {{sym("mu"), "gravitational parameter" + of, L_ + "^3/" + T_ + "^2", mu_},
          {sym("a"), "radius of the circular orbit" + of, L_, a_},
          {sym("i"), "inclination of the orbit (rad)" + of, "1", inc_},
          {sym("W"), "ascending node of the orbit (rad)" + of, "1", node_},
          {sym("u0"), "argument of latitude at t = 0 (rad)" + of, "1", phase_},
          {sym("n"), "mean motion sqrt((mu + mu3)/a^3)" + of, "1/" + T_, n_}};
}

std::vector<ex> ThirdBody::acceleration(Problem& p, const Frame& x) const {
  auto& S = p.symbols;
  const ex mu3 = S.get(sym("mu")), a = S.get(sym("a")), inc = S.get(sym("i")), W = S.get(sym("W"));
  const ex u = S.get(sym("u0")) + S.get(sym("n")) * S.get("t");
  const std::vector<ex> r3 = {a * (cos(W) * cos(u) - sin(W) * sin(u) * cos(inc)),
                              a * (sin(W) * cos(u) + cos(W) * sin(u) * cos(inc)), a * sin(u) * sin(inc)};
  const std::vector<ex> d = {r3[0] - x.r[0], r3[1] - x.r[1], r3[2] - x.r[2]};
  const ex d3 = GiNaC::pow(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], GiNaC::numeric(3, 2));
  const ex a3 = GiNaC::pow(a, 3);
  return {mu3 * (d[0] / d3 - r3[0] / a3), mu3 * (d[1] / d3 - r3[1] / a3), mu3 * (d[2] / d3 - r3[2] / a3)};
}

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  return std::make_unique<ThirdBody>(*s.perturbation, s.spec.at("central_body"), s.problem.units);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> third_body() {
  TermEntry e;
  e.name = "third_body";
  e.kind = "force";
  e.summary =
      "a point mass B on a circular orbit about the central body, direct and indirect parts, mu_B ((r3 - r)/|r3 - "
      "r|^3 - r3/|r3|^3) with r3 = a_B Rz(W_B) Rx(i_B) (cos u, sin u, 0), u = u0_B + n_B t; listed with \"body\": "
      "\"B\"";
  e.parameters = {{"mu_B", "gravitational parameter of the third body", "length^3/time^2"},
                  {"a_B", "radius of its circular orbit", "length"},
                  {"i_B", "inclination of the orbit", "rad"},
                  {"W_B", "ascending node of the orbit", "rad"},
                  {"u0_B", "argument of latitude at t = 0", "rad"},
                  {"n_B", "mean motion sqrt((mu + mu_B)/a_B^3)", "1/time"}};
  e.required = 6;
  e.details = {"body"};
  e.field = true;
  e.spec_kind = "third_body";
  const io::json positive = {{"type", "number"}, {"exclusiveMinimum", 0}}, number = {{"type", "number"}};
  e.spec_schema = {
      {"description",
       "a point mass on a circular orbit about the central body (radius, inclination, node, argument of latitude at "
       "t0; angles default to 0), perturbing the spacecraft directly and through the central body"},
      {"required", {"kind", "name", "mu_km3_s2", "orbit_radius_km"}},
      {"additionalProperties", false},
      {"properties",
       {{"kind", {{"const", "third_body"}}},
        {"name", {{"type", "string"}, {"pattern", "^[A-Za-z][A-Za-z0-9]*$"}}},
        {"mu_km3_s2", positive},
        {"orbit_radius_km", positive},
        {"inclination_deg", number},
        {"raan_deg", number},
        {"phase_deg", number}}}};
  e.order = 50;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

// A solar-electric engine about the Sun: the arrays give P0 at 1 AU and P0/r^2 at r AU (the
// length unit is the AU), the bus takes Pbus of it, and the engine takes the rest up to its
// maximum input power Pmax; at a constant efficiency eta and exhaust velocity c = g0 Isp its
// thrust is T(r) = 2 eta P_in(r) / c and its mass flow T(r) u / c:
//   a = T(r) u a_hat / m,  dm/dt = -T(r) u / c,  P_in = min(max(P0/r^2 - Pbus, 0), Pmax).
// The cap is a smooth saturation, P_in = (Pa + Pmax - sqrt((Pa - Pmax)^2 + Pw^2)) / 2 with the
// width Pw = 1% of Pmax (kSmoothWidth): the input power is C-infinity in r, so the costate rates
// (which carry dT/dr) and the shooting function stay smooth for hybrj and the eps homotopy; it is
// Pw/2 below the hard minimum where Pa = Pmax and within Pw^2 / (4 |Pa - Pmax|) of it elsewhere.
// Without a maximum input power the engine takes all the arrays give (no cap). Where a bus takes
// its share, the arrays give less than it beyond r = sqrt(P0/Pbus) AU and the engine gets nothing:
// Pa is floored at zero smoothly, s_f(Pa) = (Pa + sqrt(Pa^2 + Pf^2)) / 2 with Pf = 1% of Pbus
// (kSmoothWidth), within Pf^2 / (4 |Pa|) of max(Pa, 0) (a relative 1e-7 at Mars for S15's 20 kW
// arrays and 0.5 kW bus), and with a cap the two soft parts are summed, not nested:
//   P_in = s_f(Pa) - s_w(Pa - Pmax) + s_w(-Pmax)
//        = (sqrt(Pa^2 + Pf^2) + sqrt(Pmax^2 + Pw^2) - sqrt((Pa - Pmax)^2 + Pw^2)) / 2,
// s_w the soft positive part of width Pw. It is positive for every Pa (s_w rises with a slope below
// 1, so the cap's part never takes more than the floor's gives), tends to Pmax + s_w(-Pmax) (0.25 W
// above Pmax for a 10 kW cap) and keeps the thrust and the mass flow from turning negative. The
// cap of the floored power (s_w of s_f) would be the same physics, but the derivation's expansion
// of its square grows the program tenfold and loses the power to cancellation near the Sun.
// The thrust depends on the position, so H's r-derivatives (the costate rates), the switching
// function and the throttle law carry T(r) and dT/dr: the derivation finds them from H, nothing
// here is written for them. The input power is the derivation's intermediate P_in: the costate
// rates hold its gradient by name (dP_in_drx, ...), not its expansion (S15's program 859 KB with
// it expanded).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "helios/astro/constants.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class SolarElectric : public SolarArrayEngine {
 public:
  SolarElectric(const json& sc, const Units& U, std::string mass_unit) : SolarArrayEngine(sc, U, std::move(mass_unit)) {
    if (sc.contains("thrust_N"))
      throw std::invalid_argument(
          "field /spacecraft/thrust_N: a solar-electric engine's thrust follows from its power; drop thrust_N");
    if (!sc.contains("isp_s"))
      throw std::invalid_argument("field /spacecraft/isp_s is missing (a solar-electric engine needs it)");
    eta_ = sc.at("engine_efficiency").get<double>();
    // The cap: the maximum input power, or the power at which the engine gives its maximum thrust
    // (T c / (2 eta)), the lower of the two where both are stated.
    cap_ = sc.contains("max_engine_power_W") || sc.contains("max_thrust_N");
    double pmax_W = sc.value("max_engine_power_W", INFINITY);
    if (sc.contains("max_thrust_N"))
      pmax_W = std::min(pmax_W, sc.at("max_thrust_N").get<double>() * sc.at("isp_s").get<double>() *
                                    helios::astro::G0_M_S2 / (2 * eta_));
    if (cap_) pmax_ = pmax_W / power_unit_W_;
    exhaust_ = sc.at("isp_s").get<double>() * helios::astro::G0_M_S2 * 1e-3 / U.speed_km_s();
    if (!(eta_ > 0 && eta_ <= 1))
      throw std::invalid_argument("field /spacecraft/engine_efficiency: " + std::to_string(eta_) + " is not in (0, 1]");
    if (!(exhaust_ > 0) || (cap_ && !(pmax_ > 0)))
      throw std::domain_error(
          "field /spacecraft: a power or the exhaust velocity is 0 in normalized units: the spacecraft's magnitudes "
          "are beyond the range of double precision");
  }
  std::string name() const override { return "solar_electric_thrust"; }
  // P0, Pbus, eta, c, and with a cap Pmax and the cap's width Pw.
  std::vector<Named> parameters() const override {
    const std::string power = power_unit();
    std::vector<Named> out = {{"P0", "solar array power at 1 AU", power, p0_, "", "thrust_scale"},
                              {"Pbus", "bus power taken from the arrays", power, bus_, "", "thrust_scale"},
                              {"eta", "engine efficiency (jet power / input power)", "1", eta_},
                              {"c", "exhaust velocity Isp*g0", L_ + "/" + T_, exhaust_, "", "exhaust_velocity"}};
    if (cap_) {
      out.push_back({"Pmax", "maximum engine input power", power, pmax_, "", "thrust_scale"});
      out.push_back(
          {"Pw", "width of the smooth power cap (1% of Pmax)", power, kSmoothWidth * pmax_, "", "thrust_scale"});
    }
    return out;
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    p.intermediates = {{"P_in", "the engine's input power at the spacecraft's distance", power_unit(),
                        solar_input_power(S, x, bus_ > 0, cap_)}};
    const ex thrust = 2 * S.get("eta") * S.get("P_in") / S.get("c");
    return thrust_acceleration(p, x, thrust, thrust / S.get("c"));
  }

 private:
  double pmax_ = 0, eta_ = 0, exhaust_ = 0;
  bool cap_ = false;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  const json& sc = s.spec.at("spacecraft");
  if (s.problem.propulsion == "solar_sail" || !sc.contains("array_power_1AU_W") || fitted_engine(sc)) return nullptr;
  return std::make_unique<SolarElectric>(sc, s.problem.units, s.mass_unit);
}

}  // namespace

SolarArrayEngine::SolarArrayEngine(const json& sc, const Units& U, std::string mass_unit)
    : mass_unit_(std::move(mass_unit)), L_(U.length_name), T_(U.time_name) {
  if (U.length_name != "AU")
    throw std::invalid_argument(
        "field /spacecraft/array_power_1AU_W: a solar-electric engine needs the Sun as the central body (its "
        "power falls as 1/r^2 with r in AU)");
  if (sc.value("mass_model", "variable") == "constant" || sc.value("full_throttle", false))
    throw std::invalid_argument(
        "field /spacecraft: a solar-electric engine of constant mass or at full throttle throughout is not "
        "supported");
  // Power in the normalized units: mass * length^2 / time^3.
  power_unit_W_ = U.mass_kg * std::pow(U.length_km * 1e3, 2) / std::pow(U.time_s, 3);
  p0_ = sc.at("array_power_1AU_W").get<double>() / power_unit_W_;
  bus_ = sc.value("bus_power_W", 0.0) / power_unit_W_;
  if (!(bus_ < p0_))
    throw std::invalid_argument("field /spacecraft/bus_power_W: the bus takes all the arrays give at 1 AU");
  if (!(p0_ > 0))
    throw std::domain_error(
        "field /spacecraft: a power is 0 in normalized units: the spacecraft's magnitudes are beyond the range of "
        "double precision");
}

std::vector<Control> SolarArrayEngine::controls() const {
  return {{"u", "throttle T/T(r) in [0, 1] (T(r) the thrust the power at r allows)", "throttle"},
          {"ax", "thrust direction x (unit vector)", "direction"},
          {"ay", "thrust direction y (unit vector)", "direction"},
          {"az", "thrust direction z (unit vector)", "direction"}};
}

std::vector<ex> SolarArrayEngine::thrust_acceleration(Problem& p, const Frame& x, const ex& thrust,
                                                      const ex& flow) const {
  auto& S = p.symbols;
  p.max_thrust = thrust;
  p.max_mass_flow = flow;
  p.thrust_parameters.clear();
  for (const auto& q : parameters()) p.thrust_parameters.push_back(q.name);
  p.flow_parameters = p.thrust_parameters;
  const ex u = S.get("u");
  return {thrust * u * S.get("ax") / x.mass, thrust * u * S.get("ay") / x.mass, thrust * u * S.get("az") / x.mass};
}

ex solar_input_power(symbolic::SymbolTable& S, const Frame& x, bool bus, bool cap) {
  const ex r2 = x.r[0] * x.r[0] + x.r[1] * x.r[1] + x.r[2] * x.r[2];
  const ex available = S.get("P0") / r2 - S.get("Pbus");
  if (bus) {  // floored at zero (the soft positive part of width Pf), and capped as above
    const ex Pf = kSmoothWidth * S.get("Pbus"), floor_root = GiNaC::sqrt(GiNaC::pow(available, 2) + Pf * Pf);
    if (!cap) return (available + floor_root) / 2;
    const ex Pmax = S.get("Pmax"), Pw = S.get("Pw");
    return (floor_root + GiNaC::sqrt(Pmax * Pmax + Pw * Pw) - GiNaC::sqrt(GiNaC::pow(available - Pmax, 2) + Pw * Pw)) /
           2;
  }
  if (!cap) return available;
  const ex Pmax = S.get("Pmax"), Pw = S.get("Pw");
  return (available + Pmax - GiNaC::sqrt(GiNaC::pow(available - Pmax, 2) + Pw * Pw)) / 2;
}

}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> solar_electric() {
  const std::string power = "mass*length^2/time^3";
  TermEntry e;
  e.name = "solar_electric_thrust";
  e.kind = "force";
  e.summary =
      "a solar-electric engine, T(r) u a/m with the mass flow -T(r) u/c, T(r) = 2 eta P_in/c, Pa = "
      "P0/(rx^2+ry^2+rz^2) - Pbus, Pf = Pbus/100, Pw = Pmax/100: P_in = Pa without a bus or a cap, (Pa + Pmax - "
      "sqrt((Pa - Pmax)^2 + Pw^2))/2 with a cap alone, (Pa + sqrt(Pa^2 + Pf^2))/2 with a bus alone, (sqrt(Pa^2 + "
      "Pf^2) + sqrt(Pmax^2 + Pw^2) - sqrt((Pa - Pmax)^2 + Pw^2))/2 with both; its fuel cost lists the same "
      "parameters, L = T(r)/c (u - eps u (1 - u))";
  e.parameters = {
      {"P0", "solar array power at 1 AU", power, "thrust_scale"},
      TermParameter("Pbus", "bus power taken from the arrays", power, "thrust_scale").typeset("P", "\\mathrm{bus}"),
      {"eta", "engine efficiency (jet power / input power)", "1"},
      {"c", "exhaust velocity Isp*g0", "length/time", "exhaust_velocity"},
      TermParameter("Pmax", "maximum engine input power", power, "thrust_scale").typeset("P", "\\max"),
      TermParameter("Pw", "width of the smooth power cap (Pmax/100)", power, "thrust_scale").typeset("P", "w")};
  e.required = 4;
  e.engine = e.varying_flow = true;
  e.order = 30;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

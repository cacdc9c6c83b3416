// A thruster of maximum thrust Tmax and exhaust velocity c: a = Tmax u a_hat / m with the
// throttle u in [0, 1] and the unit direction a_hat, and the mass flow dm/dt = -Tmax u / c. An
// engine at full throttle throughout (full_thrust) has u = 1: its direction is its only control.
// An engine of constant mass (the spec's mass_model "constant": constant_mass_thrust) has no mass
// state: m is a parameter (1, the mass unit), and c, where a specific impulse is given, only
// prices the propellant of the minimum-fuel cost (fuel_cost.cpp).
#include <stdexcept>

#include "helios/astro/constants.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class Thrust : public ForceTerm {
 public:
  Thrust(const json& sc, const Units& U, std::string mass_unit)
      : full_(sc.value("full_throttle", false)),
        constant_mass_(sc.value("mass_model", "variable") == "constant"),
        thrust_(sc.at("thrust_N").get<double>() / U.force_N()),
        exhaust_(sc.contains("isp_s") ? sc.at("isp_s").get<double>() * helios::astro::G0_M_S2 * 1e-3 / U.speed_km_s()
                                      : 0.0),
        mass_unit_(std::move(mass_unit)),
        L_(U.length_name),
        T_(U.time_name) {
    if (!constant_mass_ && !sc.contains("isp_s"))
      throw std::invalid_argument("field /spacecraft/isp_s is missing (an engine whose mass varies needs it)");
    // The schema asks for positive values; a zero here is an underflow in normalized units.
    if (!(thrust_ > 0) || (sc.contains("isp_s") && !(exhaust_ > 0)))
      throw std::domain_error("field /spacecraft: the " +
                              std::string(thrust_ > 0 ? "exhaust velocity" : "maximum thrust") +
                              " is 0 in normalized units: the spacecraft's magnitudes (thrust, Isp, mass) are beyond "
                              "the range of double precision");
  }
  std::string name() const override {
    return std::string(constant_mass_ ? "constant_mass_" : "") + (full_ ? "full_thrust" : "thrust");
  }
  std::vector<Named> states() const override {
    if (constant_mass_) return {};
    return {{"m", "mass", mass_unit_}};
  }
  std::vector<Control> controls() const override {
    std::vector<Control> out = {{"ax", "thrust direction x (unit vector)", "direction"},
                                {"ay", "thrust direction y (unit vector)", "direction"},
                                {"az", "thrust direction z (unit vector)", "direction"}};
    if (!full_) out.insert(out.begin(), {"u", "throttle T/Tmax in [0, 1]", "throttle"});
    return out;
  }
  // Tmax and c; with a constant mass Tmax, the mass and c where a specific impulse is given.
  std::vector<Named> parameters() const override {
    const Named tmax = {"Tmax", "maximum thrust", mass_unit_ + "*" + L_ + "/" + T_ + "^2", thrust_, "", "thrust_scale"};
    const Named c = {"c", "exhaust velocity Isp*g0", L_ + "/" + T_, exhaust_, "", "exhaust_velocity"};
    if (!constant_mass_) return {tmax, c};
    std::vector<Named> out = {tmax, {"mass", "constant mass of the spacecraft", mass_unit_, 1.0}};
    if (exhaust_ > 0) out.push_back(c);
    return out;
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    const ex u = throttle(p), TM = S.get("Tmax"), m = constant_mass_ ? ex(S.get("mass")) : x.mass;
    p.max_thrust = TM;
    p.thrust_parameters = {"Tmax"};
    if (exhaust_ > 0) {
      p.max_mass_flow = TM / S.get("c");
      p.flow_parameters = {"Tmax", "c"};
    }
    return {TM * u * S.get("ax") / m, TM * u * S.get("ay") / m, TM * u * S.get("az") / m};
  }
  ex mass_rate(Problem& p) const override {
    if (constant_mass_) return 0;
    return -p.max_mass_flow * throttle(p);
  }

 private:
  ex throttle(Problem& p) const { return full_ ? ex(1) : ex(p.symbols.get("u")); }

  bool full_, constant_mass_;
  double thrust_, exhaust_;
  std::string mass_unit_, L_, T_;
};

// The engine of a spacecraft that is neither a sail nor solar-electric.
std::unique_ptr<ForceTerm> build(const TermSource& s) {
  const json& sc = s.spec.at("spacecraft");
  if (s.problem.propulsion == "solar_sail" || sc.contains("array_power_1AU_W")) return nullptr;
  return std::make_unique<Thrust>(sc, s.problem.units, s.mass_unit);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> thrust() {
  const TermParameter tmax = TermParameter("Tmax", "maximum thrust", "mass*length/time^2", "thrust_scale")
                                 .typeset("T", "\\max"),
                      c = {"c", "exhaust velocity Isp*g0", "length/time", "exhaust_velocity"},
                      mass = TermParameter("mass", "the constant mass: 1, the mass unit", "mass").typeset("m", "");
  TermEntry e;
  e.kind = "force";
  e.engine = true;
  e.order = 30;
  e.name = "thrust";
  e.summary = "a thruster, Tmax u a/m (throttle u in [0, 1], unit direction a) with the mass flow -Tmax u/c";
  e.parameters = {tmax, c};
  e.required = 2;
  e.build = terms::build;
  TermEntry full = e;
  full.name = "full_thrust";
  full.summary =
      "an engine at full throttle throughout, Tmax a/m with the mass flow -Tmax/c (no throttle control: the direction "
      "is the only control)";
  full.build = nullptr;
  TermEntry constant = e;
  constant.name = "constant_mass_thrust";
  constant.summary =
      "an engine of constant mass (spacecraft.mass_model \"constant\"), no mass state: Tmax u a/mass with the "
      "parameter mass = 1, the mass unit; c only where an Isp is given";
  constant.parameters = {tmax, mass, c};
  constant.build = nullptr;
  TermEntry constant_full = constant;
  constant_full.name = "constant_mass_full_thrust";
  constant_full.summary = "an engine of constant mass at full throttle throughout, Tmax a/mass";
  return {e, full, constant, constant_full};
}

}  // namespace helios::pmp::catalogue

// A thruster of maximum thrust Tmax and exhaust velocity c: a = Tmax u a_hat / m with the
// throttle u in [0, 1] and the unit direction a_hat, and the mass flow dm/dt = -Tmax u / c. An
// engine at full throttle throughout (full_thrust) has u = 1: its direction is its only control.
#include <stdexcept>

#include "helios/astro/constants.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

class Thrust : public ForceTerm {
 public:
  Thrust(const json& sc, const Units& U, std::string mass_unit)
      : full_(sc.value("full_throttle", false)),
        thrust_(sc.at("thrust_N").get<double>() / U.force_N()),
        exhaust_(sc.at("isp_s").get<double>() * helios::astro::G0_M_S2 * 1e-3 / U.speed_km_s()),
        mass_unit_(std::move(mass_unit)),
        L_(U.length_name),
        T_(U.time_name) {
    // The schema asks for positive values; a zero here is an underflow in normalized units.
    if (!(thrust_ > 0) || !(exhaust_ > 0))
      throw std::domain_error("field /spacecraft: the " +
                              std::string(thrust_ > 0 ? "exhaust velocity" : "maximum thrust") +
                              " is 0 in normalized units: the spacecraft's magnitudes (thrust, Isp, mass) are beyond "
                              "the range of double precision");
  }
  std::string name() const override { return full_ ? "full_thrust" : "thrust"; }
  std::vector<Named> states() const override { return {{"m", "mass", mass_unit_}}; }
  std::vector<Control> controls() const override {
    std::vector<Control> out = {{"ax", "thrust direction x (unit vector)", "direction"},
                                {"ay", "thrust direction y (unit vector)", "direction"},
                                {"az", "thrust direction z (unit vector)", "direction"}};
    if (!full_) out.insert(out.begin(), {"u", "throttle T/Tmax in [0, 1]", "throttle"});
    return out;
  }
  std::vector<Named> parameters() const override {
    return {{"Tmax", "maximum thrust", mass_unit_ + "*" + L_ + "/" + T_ + "^2", thrust_},
            {"c", "exhaust velocity Isp*g0", L_ + "/" + T_, exhaust_}};
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    const ex u = throttle(p), TM = S.get("Tmax");
    return {TM * u * S.get("ax") / x.mass, TM * u * S.get("ay") / x.mass, TM * u * S.get("az") / x.mass};
  }
  ex mass_rate(Problem& p) const override { return -p.symbols.get("Tmax") * throttle(p) / p.symbols.get("c"); }

 private:
  ex throttle(Problem& p) const { return full_ ? ex(1) : ex(p.symbols.get("u")); }

  bool full_;
  double thrust_, exhaust_;
  std::string mass_unit_, L_, T_;
};

}  // namespace

std::unique_ptr<ForceTerm> thrust(const json& spacecraft, const Units& U, const std::string& mass_unit) {
  return std::make_unique<Thrust>(spacecraft, U, mass_unit);
}

}  // namespace helios::pmp::terms

// A solar-electric thruster given, as flown missions give NSTAR and NEXT, by fits of its thrust
// and its mass flow to its input power over the range it runs in (polynomials of degree 4 at most
// in P [kW]; thrust in mN, mass flow in mg/s): T(P) = T0 + T1 P + ... + T4 P^4,
// F(P) = F0 + F1 P + ... + F4 P^4. Its input power is solar_electric_thrust's (the arrays' P0/r^2
// less the bus, floored at zero where a bus is), capped softly at the top of the range Pmax; below
// the range's bottom Pmin, where one is stated, the engine is off, by the smooth step
// s(P) = 1/(1 + exp(-(P - Pmin)/Pn)) with Pn = 1% of Pmin (else s = 1):
//   a = T_P u a_hat / m,  dm/dt = -F_P u,  T_P = s(P_in) T(P_in),  F_P = s(P_in) F(P_in).
// Its specific impulse T/(F g0) follows the power: it has no exhaust velocity of its own. Its
// thrust-scale parameters are the coefficients (the thrust continuation multiplies them all, as
// more or fewer thrusters of the same kind would).
// P_in, T_P and F_P are the derivation's intermediates: kept by name, their powers never expand
// (a quadratic fit of the expanded power made a costate rate of 1.3 MB), and H's derivatives in r
// go through them by the chain rule.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "helios/io/json_io.hpp"
#include "term.hpp"

namespace helios::pmp::terms {
namespace {

constexpr std::size_t kCoefficients = 5;  // a fit of degree 4 at most
constexpr int kRangeSamples = 200;        // where the fits are checked to be positive

// "M^a L^b T^c" as the derivation writes a unit: the positive powers, then "/" each negative one.
std::string unit_text(const std::string& mass, const std::string& length, const std::string& time, int a, int b,
                      int c) {
  std::string num, den;
  const auto factor = [&](const std::string& name, int k) {
    if (k == 0) return;
    std::string& side = k > 0 ? num : den;
    const std::string f = name + (std::abs(k) == 1 ? "" : "^" + std::to_string(std::abs(k)));
    if (k > 0)
      side += (side.empty() ? "" : "*") + f;
    else
      side += "/" + f;
  };
  factor(mass, a);
  factor(length, b);
  factor(time, c);
  return (num.empty() ? "1" : num) + den;
}

class FittedSolarElectric : public SolarArrayEngine {
 public:
  FittedSolarElectric(const json& sc, const Units& U, std::string mass_unit)
      : SolarArrayEngine(sc, U, std::move(mass_unit)) {
    for (const char* field : {"thrust_N", "engine_efficiency", "isp_s", "max_thrust_N"})
      if (sc.contains(field))
        throw std::invalid_argument(std::string("field /spacecraft/") + field +
                                    ": the fits of the thrust and the mass flow give the engine's performance; drop " +
                                    field);
    for (const char* field : {"thrust_polynomial_mN", "mass_flow_polynomial_mg_s", "max_engine_power_W"})
      if (!sc.contains(field))
        throw std::invalid_argument(std::string("field /spacecraft/") + field +
                                    " is missing (a thruster given by fits needs both fits and the top of their "
                                    "power range, max_engine_power_W)");
    const double pmax_W = sc.at("max_engine_power_W").get<double>(), pmin_W = sc.value("min_engine_power_W", 0.0);
    pmax_ = pmax_W / power_unit_W_;
    pmin_ = pmin_W / power_unit_W_;
    if (!(pmin_W >= 0 && pmin_W < pmax_W))
      throw std::invalid_argument("field /spacecraft/min_engine_power_W: " + io::short_number(pmin_W) +
                                  " W is not below max_engine_power_W (" + io::short_number(pmax_W) + " W)");
    // A coefficient of P^k in mN/kW^k is 1e-3 (power unit/kW)^k / (force unit) of the normalized one.
    const double per_kW = power_unit_W_ / 1000;
    thrust_ = read_fit(sc, "thrust_polynomial_mN", 1e-3 / U.force_N(), per_kW, pmin_W, pmax_W);
    flow_ = read_fit(sc, "mass_flow_polynomial_mg_s", 1e-6 * U.time_s / U.mass_kg, per_kW, pmin_W, pmax_W);
    check_jet_power(sc, pmin_W, pmax_W);
    if (!(pmax_ > 0))
      throw std::domain_error(
          "field /spacecraft/max_engine_power_W: 0 in normalized units: the spacecraft's magnitudes are beyond the "
          "range of double precision");
  }
  std::string name() const override { return "solar_electric_fitted_thrust"; }
  // P0, Pbus, Pmax, Pw, T0..T4, F0..F4, and with a lowest power Pmin and its step's width Pn.
  std::vector<Named> parameters() const override {
    const std::string power = power_unit();
    std::vector<Named> out = {{"P0", "solar array power at 1 AU", power, p0_},
                              {"Pbus", "bus power taken from the arrays", power, bus_},
                              {"Pmax", "maximum engine input power (the top of the fits' range)", power, pmax_},
                              {"Pw", "width of the smooth power cap (1% of Pmax)", power, kSmoothWidth * pmax_}};
    for (std::size_t k = 0; k < kCoefficients; ++k) {
      const int j = static_cast<int>(k);
      out.push_back({"T" + std::to_string(k), "coefficient of P_in^" + std::to_string(k) + " of the fitted thrust",
                     unit_text(mass_unit_, L_, T_, 1 - j, 1 - 2 * j, 3 * j - 2), thrust_[k], "", "thrust_scale"});
    }
    for (std::size_t k = 0; k < kCoefficients; ++k) {
      const int j = static_cast<int>(k);
      out.push_back({"F" + std::to_string(k), "coefficient of P_in^" + std::to_string(k) + " of the fitted mass flow",
                     unit_text(mass_unit_, L_, T_, 1 - j, -2 * j, 3 * j - 1), flow_[k], "", "thrust_scale"});
    }
    if (pmin_ > 0) {
      out.push_back({"Pmin", "lowest engine input power (off below it)", power, pmin_});
      out.push_back({"Pn", "width of the smooth step at Pmin (1% of Pmin)", power, kSmoothWidth * pmin_});
    }
    return out;
  }
  std::vector<ex> acceleration(Problem& p, const Frame& x) const override {
    auto& S = p.symbols;
    const ex P = S.get("P_in");
    ex thrust = 0, flow = 0;
    for (std::size_t k = 0; k < kCoefficients; ++k) {
      thrust += S.get("T" + std::to_string(k)) * GiNaC::pow(P, static_cast<int>(k));
      flow += S.get("F" + std::to_string(k)) * GiNaC::pow(P, static_cast<int>(k));
    }
    if (pmin_ > 0) {
      const ex on = 1 / (1 + GiNaC::exp(-(P - S.get("Pmin")) / S.get("Pn")));
      thrust *= on;
      flow *= on;
    }
    const std::string force = unit_text(mass_unit_, L_, T_, 1, 1, -2), rate = unit_text(mass_unit_, L_, T_, 1, 0, -1);
    p.intermediates = {{"P_in", "the engine's input power at the spacecraft's distance", power_unit(),
                        solar_input_power(S, x, bus_ > 0, true)},
                       {"T_P", "the fitted thrust at the input power P_in", force, thrust},
                       {"F_P", "the fitted mass flow at the input power P_in", rate, flow}};
    return thrust_acceleration(p, x, S.get("T_P"), S.get("F_P"));
  }

 private:
  // The fit of `field` (c0..ck in the spec's units of P in kW), normalized by unit (its P^0
  // coefficient's factor) and per_kW (the power unit in kW); refused where it is negative on
  // the range the engine runs in, [Pmin, Pmax] (from 0 without a Pmin: the power falls with the
  // distance).
  static std::vector<double> read_fit(const json& sc, const char* field, double unit, double per_kW, double pmin_W,
                                      double pmax_W) {
    const std::string where = std::string("field /spacecraft/") + field;
    const json& c = sc.at(field);
    if (!c.is_array() || c.empty() || c.size() > kCoefficients)
      throw std::invalid_argument(where + ": a fit of degree 4 at most has 1 to 5 coefficients, got " + c.dump());
    std::vector<double> raw(kCoefficients, 0.0), out(kCoefficients, 0.0);
    for (std::size_t k = 0; k < c.size(); ++k) {
      raw[k] = c[k].get<double>();
      out[k] = raw[k] * unit * std::pow(per_kW, static_cast<double>(k));
    }
    for (int i = 0; i <= kRangeSamples; ++i) {
      const double P_kW = (pmin_W + (pmax_W - pmin_W) * i / kRangeSamples) / 1000;
      double v = 0;
      for (std::size_t k = kCoefficients; k-- > 0;) v = v * P_kW + raw[k];
      if (!(v >= 0))
        throw std::invalid_argument(where + ": the fit is " + io::short_number(v) + " at " + io::short_number(P_kW) +
                                    " kW, negative on the range the engine runs in (" +
                                    io::short_number(pmin_W / 1000) + " to " + io::short_number(pmax_W / 1000) + " kW" +
                                    (pmin_W > 0 ? "" : "; state its lowest input power, min_engine_power_W") + ")");
    }
    return out;
  }

  // The fit of `field` (its spec units: mN or mg/s, P in kW) at P_kW.
  static double fit_at(const json& sc, const char* field, double P_kW) {
    const json& c = sc.at(field);
    double v = 0;
    for (std::size_t k = c.size(); k-- > 0;) v = v * P_kW + c[k].get<double>();
    return v;
  }

  // The jet power T^2/(2 mdot) cannot exceed the input power where the engine surely runs (over the
  // range from a stated lowest power, else at its top): a spec written by hand meets the sentence's
  // rule here, which catches fits in the wrong units.
  static void check_jet_power(const json& sc, double pmin_W, double pmax_W) {
    for (int i = pmin_W > 0 ? 0 : kRangeSamples; i <= kRangeSamples; ++i) {
      const double P_W = pmin_W + (pmax_W - pmin_W) * i / kRangeSamples;
      const double thrust_N = fit_at(sc, "thrust_polynomial_mN", P_W / 1000) * 1e-3;
      const double flow_kg_s = fit_at(sc, "mass_flow_polynomial_mg_s", P_W / 1000) * 1e-6;
      const double jet_W = thrust_N * thrust_N / (2 * flow_kg_s);
      if (flow_kg_s > 0 && jet_W > P_W)
        throw std::invalid_argument(
            "field /spacecraft/thrust_polynomial_mN: with mass_flow_polynomial_mg_s it gives a jet power T^2/(2 mdot) "
            "of " +
            io::short_number(jet_W) + " W at an input power of " + io::short_number(P_W) + " W, " +
            io::short_number(jet_W / P_W) +
            " times what the engine takes (check the fits' units: thrust in mN, mass flow in mg/s, P in kW)");
    }
  }

  double pmax_ = 0, pmin_ = 0;
  std::vector<double> thrust_, flow_;
};

std::unique_ptr<ForceTerm> build(const TermSource& s) {
  const json& sc = s.spec.at("spacecraft");
  if (s.problem.propulsion == "solar_sail" || !fitted_engine(sc)) return nullptr;
  if (!sc.contains("array_power_1AU_W"))
    throw std::invalid_argument(
        "field /spacecraft/array_power_1AU_W is missing (a thruster given by fits of its input power is powered by "
        "solar arrays)");
  return std::make_unique<FittedSolarElectric>(sc, s.problem.units, s.mass_unit);
}

}  // namespace
}  // namespace helios::pmp::terms

namespace helios::pmp::catalogue {

std::vector<TermEntry> solar_electric_fits() {
  const std::string power = "mass*length^2/time^3";
  TermEntry e;
  e.name = "solar_electric_fitted_thrust";
  e.kind = "force";
  e.summary =
      "a solar-electric thruster given by fits to its input power, T_P u a/m with the mass flow -F_P u: the "
      "intermediates P_in (solar_electric_thrust's input power with its cap Pmax, Pw), T_P = s (T0 + T1 P_in + ... + "
      "T4 P_in^4), F_P = s (F0 + F1 P_in + ... + F4 P_in^4), s = 1/(1 + exp(-(P_in - Pmin)/Pn)) with Pn = Pmin/100 "
      "where a lowest power is listed, else 1; its fuel cost lists the same parameters, L = F_P (u - eps u (1 - u))";
  e.parameters = {{"P0", "solar array power at 1 AU", power},
                  TermParameter("Pbus", "bus power taken from the arrays", power).typeset("P", "\\mathrm{bus}"),
                  TermParameter("Pmax", "maximum engine input power", power).typeset("P", "\\max"),
                  TermParameter("Pw", "width of the smooth power cap (Pmax/100)", power).typeset("P", "w")};
  for (std::size_t k = 0; k < terms::kCoefficients; ++k)
    e.parameters.push_back(TermParameter("T" + std::to_string(k),
                                         "coefficient of P_in^" + std::to_string(k) + " of the thrust",
                                         "force/power^" + std::to_string(k), "thrust_scale")
                               .typeset("T", std::to_string(k)));
  for (std::size_t k = 0; k < terms::kCoefficients; ++k)
    e.parameters.push_back(TermParameter("F" + std::to_string(k),
                                         "coefficient of P_in^" + std::to_string(k) + " of the mass flow",
                                         "mass/time/power^" + std::to_string(k), "thrust_scale")
                               .typeset("F", std::to_string(k)));
  e.required = e.parameters.size();
  e.parameters.push_back(TermParameter("Pmin", "lowest engine input power", power).typeset("P", "\\min"));
  e.parameters.push_back(TermParameter("Pn", "width of the smooth step at Pmin (Pmin/100)", power).typeset("P", "n"));
  e.engine = e.varying_flow = true;
  e.order = 30;
  e.build = terms::build;
  return {e};
}

}  // namespace helios::pmp::catalogue

// A solar-electric thruster given, as flown missions give NSTAR and NEXT, by fits of its thrust
// and its mass flow to its input power over the range it runs in (polynomials of degree 4 at most
// in P [kW]; thrust in mN, mass flow in mg/s), or by a table of them that this term fits (least
// squares, the lowest degree that reproduces it to 1e-4): T(P) = T0 + T1 P + ... + T4 P^4,
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
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

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

// The fits in the spec's units (c0..c4 of P^k, P in kW; thrust in mN, mass flow in mg/s), the range
// the engine runs in, and the fields they came from.
struct RawFits {
  std::vector<double> thrust_mN, flow_mg_s;
  double pmin_W = 0, pmax_W = 0;
  std::string thrust_field, flow_field, note;
};

// c0 + c1 P + ... at P.
double polynomial_at(const std::vector<double>& c, double P) {
  double v = 0;
  for (std::size_t k = c.size(); k-- > 0;) v = v * P + c[k];
  return v;
}

// The lowest-degree least-squares polynomial (degree 1 to 4, below the number of points) that
// reproduces every point to kTableTolerance of its value (the table's own rounding), else the
// highest-degree one; `deviation` its largest deviation relative to the point's value, `worst`
// that point. P is scaled to [0, 1] by its largest value for the fit's conditioning. A table no
// such polynomial follows within kTableRefused is refused: its fit would not be the thruster.
constexpr double kTableTolerance = 1e-4, kTableRefused = 0.02;
std::vector<double> least_squares_fit(const std::vector<double>& P, const std::vector<double>& v, int& degree,
                                      double& deviation, std::size_t& worst) {
  const double scale = P.back(), floor = 1e-3 * *std::max_element(v.begin(), v.end());
  const int top = std::min<int>(kCoefficients - 1, static_cast<int>(P.size()) - 1);
  std::vector<double> fit;
  for (degree = 1; degree <= top; ++degree) {
    Eigen::MatrixXd V(static_cast<Eigen::Index>(P.size()), degree + 1);
    Eigen::VectorXd b(static_cast<Eigen::Index>(P.size()));
    for (std::size_t i = 0; i < P.size(); ++i) {
      for (int k = 0; k <= degree; ++k) V(static_cast<Eigen::Index>(i), k) = std::pow(P[i] / scale, k);
      b(static_cast<Eigen::Index>(i)) = v[i];
    }
    const Eigen::VectorXd c = V.colPivHouseholderQr().solve(b);
    fit.assign(kCoefficients, 0.0);
    for (int k = 0; k <= degree; ++k) fit[static_cast<std::size_t>(k)] = c(k) / std::pow(scale, k);
    deviation = 0;
    for (std::size_t i = 0; i < P.size(); ++i)
      if (const double d = std::fabs(polynomial_at(fit, P[i]) - v[i]) / std::max(v[i], floor); d > deviation) {
        deviation = d;
        worst = i;
      }
    if (deviation <= kTableTolerance) break;
  }
  degree = std::min(degree, top);
  return fit;
}

// A thruster table (spacecraft.thruster_table: rows of input_power_W, thrust_N, mass_flow_kg_s by
// increasing power) fitted as the fits sentence gives them; its range is the table's.
RawFits table_fits(const json& sc) {
  const std::string where = "field /spacecraft/thruster_table";
  const json& rows = sc.at("thruster_table");
  if (!rows.is_array() || rows.size() < 3)
    throw std::invalid_argument(where + ": a thruster table needs at least 3 rows, got " + rows.dump());
  std::vector<double> P, T, F;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string row = where + "/" + std::to_string(i);
    const json& r = rows[i];
    for (const char* key : {"input_power_W", "thrust_N", "mass_flow_kg_s"})
      if (!r.is_object() || !r.contains(key) || !r.at(key).is_number())
        throw std::invalid_argument(row + ": needs the number " + key);
    P.push_back(r.at("input_power_W").get<double>() / 1000);
    T.push_back(r.at("thrust_N").get<double>() * 1e3);
    F.push_back(r.at("mass_flow_kg_s").get<double>() * 1e6);
    if (!(P.back() > 0) || !(T.back() >= 0) || !(F.back() > 0))
      throw std::invalid_argument(row +
                                  ": the input power and the mass flow must be positive, the thrust not negative");
    if (i > 0 && !(P[i] > P[i - 1]))
      throw std::invalid_argument(row + "/input_power_W: " + io::short_number(P[i] * 1000) +
                                  " W is not above the row before's (the rows go by increasing power)");
  }
  RawFits out;
  int thrust_degree = 0, flow_degree = 0;
  double thrust_deviation = 0, flow_deviation = 0;
  std::size_t thrust_worst = 0, flow_worst = 0;
  out.thrust_mN = least_squares_fit(P, T, thrust_degree, thrust_deviation, thrust_worst);
  out.flow_mg_s = least_squares_fit(P, F, flow_degree, flow_deviation, flow_worst);
  const auto percent = [](double d) { return io::significant(d * 100, 2); };
  for (const auto& [what, deviation, worst] : {std::tuple{"thrust_N", thrust_deviation, thrust_worst},
                                               std::tuple{"mass_flow_kg_s", flow_deviation, flow_worst}})
    if (deviation > kTableRefused)
      throw std::invalid_argument(
          where + "/" + std::to_string(worst) + "/" + what +
          ": no polynomial of degree 4 or less in the power follows the table (the closest misses this row by " +
          percent(deviation) + " %): check the row, or give fits of the thruster instead");
  out.pmin_W = P.front() * 1000;
  out.pmax_W = P.back() * 1000;
  out.thrust_field = out.flow_field = "thruster_table";
  out.note = " (least squares over the thruster table's " + std::to_string(P.size()) + " rows: the thrust of degree " +
             std::to_string(thrust_degree) + ", off by at most " + percent(thrust_deviation) +
             " % at a row, the mass flow of degree " + std::to_string(flow_degree) + ", at most " +
             percent(flow_deviation) + " %)";
  return out;
}

// The fits as the spec gives them (thrust_polynomial_mN, mass_flow_polynomial_mg_s, the range's
// top max_engine_power_W and bottom min_engine_power_W).
RawFits polynomial_fits(const json& sc) {
  for (const char* field : {"thrust_polynomial_mN", "mass_flow_polynomial_mg_s", "max_engine_power_W"})
    if (!sc.contains(field))
      throw std::invalid_argument(std::string("field /spacecraft/") + field +
                                  " is missing (a thruster given by fits needs both fits and the top of their "
                                  "power range, max_engine_power_W)");
  RawFits out;
  out.thrust_field = "thrust_polynomial_mN";
  out.flow_field = "mass_flow_polynomial_mg_s";
  for (const auto& [field, c] :
       {std::pair{out.thrust_field, &out.thrust_mN}, std::pair{out.flow_field, &out.flow_mg_s}}) {
    const json& given = sc.at(field);
    if (!given.is_array() || given.empty() || given.size() > kCoefficients)
      throw std::invalid_argument("field /spacecraft/" + field +
                                  ": a fit of degree 4 at most has 1 to 5 coefficients, got " + given.dump());
    c->assign(kCoefficients, 0.0);
    for (std::size_t k = 0; k < given.size(); ++k) (*c)[k] = given[k].get<double>();
  }
  out.pmax_W = sc.at("max_engine_power_W").get<double>();
  out.pmin_W = sc.value("min_engine_power_W", 0.0);
  if (!(out.pmin_W >= 0 && out.pmin_W < out.pmax_W))
    throw std::invalid_argument("field /spacecraft/min_engine_power_W: " + io::short_number(out.pmin_W) +
                                " W is not below max_engine_power_W (" + io::short_number(out.pmax_W) + " W)");
  return out;
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
    const bool table = sc.contains("thruster_table");
    if (table)
      for (const char* field :
           {"thrust_polynomial_mN", "mass_flow_polynomial_mg_s", "min_engine_power_W", "max_engine_power_W"})
        if (sc.contains(field))
          throw std::invalid_argument(std::string("field /spacecraft/") + field +
                                      ": the thruster table gives the engine's performance and its power range; drop " +
                                      field);
    const RawFits fits = table ? table_fits(sc) : polynomial_fits(sc);
    note_ = fits.note;
    pmax_ = fits.pmax_W / power_unit_W_;
    pmin_ = fits.pmin_W / power_unit_W_;
    check_positive(fits.thrust_mN, fits.thrust_field, fits.pmin_W, fits.pmax_W);
    check_positive(fits.flow_mg_s, fits.flow_field, fits.pmin_W, fits.pmax_W);
    check_jet_power(fits);
    // A coefficient of P^k in mN/kW^k is 1e-3 (power unit/kW)^k / (force unit) of the normalized one.
    const double per_kW = power_unit_W_ / 1000;
    thrust_ = normalized(fits.thrust_mN, 1e-3 / U.force_N(), per_kW);
    flow_ = normalized(fits.flow_mg_s, 1e-6 * U.time_s / U.mass_kg, per_kW);
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
      out.push_back({"T" + std::to_string(k),
                     "coefficient of P_in^" + std::to_string(k) + " of the fitted thrust" + (k == 0 ? note_ : ""),
                     unit_text(mass_unit_, L_, T_, 1 - j, 1 - 2 * j, 3 * j - 2), thrust_[k], "", "thrust_scale"});
    }
    for (std::size_t k = 0; k < kCoefficients; ++k) {
      const int j = static_cast<int>(k);
      out.push_back({"F" + std::to_string(k),
                     "coefficient of P_in^" + std::to_string(k) + " of the fitted mass flow" + (k == 0 ? note_ : ""),
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
  // c0..c4 in the spec's units normalized: by unit (its P^0 coefficient's factor) and per_kW (the
  // power unit in kW).
  static std::vector<double> normalized(const std::vector<double>& raw, double unit, double per_kW) {
    std::vector<double> out(kCoefficients, 0.0);
    for (std::size_t k = 0; k < kCoefficients; ++k) out[k] = raw[k] * unit * std::pow(per_kW, static_cast<double>(k));
    return out;
  }

  // A fit is refused where it is negative on the range the engine runs in, [Pmin, Pmax] (from 0
  // without a Pmin: the power falls with the distance).
  static void check_positive(const std::vector<double>& raw, const std::string& field, double pmin_W, double pmax_W) {
    for (int i = 0; i <= kRangeSamples; ++i) {
      const double P_kW = (pmin_W + (pmax_W - pmin_W) * i / kRangeSamples) / 1000;
      const double v = polynomial_at(raw, P_kW);
      if (!(v >= 0))
        throw std::invalid_argument("field /spacecraft/" + field + ": the fit is " + io::short_number(v) + " at " +
                                    io::short_number(P_kW) + " kW, negative on the range the engine runs in (" +
                                    io::short_number(pmin_W / 1000) + " to " + io::short_number(pmax_W / 1000) + " kW" +
                                    (pmin_W > 0 ? "" : "; state its lowest input power, min_engine_power_W") + ")");
    }
  }

  // The jet power T^2/(2 mdot) cannot exceed the input power where the engine surely runs (over the
  // range from a stated lowest power, else at its top): a spec written by hand meets the sentence's
  // rule here, which catches fits in the wrong units.
  static void check_jet_power(const RawFits& fits) {
    for (int i = fits.pmin_W > 0 ? 0 : kRangeSamples; i <= kRangeSamples; ++i) {
      const double P_W = fits.pmin_W + (fits.pmax_W - fits.pmin_W) * i / kRangeSamples;
      const double thrust_N = polynomial_at(fits.thrust_mN, P_W / 1000) * 1e-3;
      const double flow_kg_s = polynomial_at(fits.flow_mg_s, P_W / 1000) * 1e-6;
      const double jet_W = thrust_N * thrust_N / (2 * flow_kg_s);
      if (flow_kg_s > 0 && jet_W > P_W)
        throw std::invalid_argument(
            "field /spacecraft/" + fits.thrust_field +
            (fits.thrust_field == fits.flow_field ? ": its fits give" : ": with " + fits.flow_field + " it gives") +
            " a jet power T^2/(2 mdot) of " + io::short_number(jet_W) + " W at an input power of " +
            io::short_number(P_W) + " W, " + io::short_number(jet_W / P_W) +
            " times what the engine takes (check the units: thrust in mN, mass flow in mg/s, "
            "P in kW)");
    }
  }

  double pmax_ = 0, pmin_ = 0;
  std::vector<double> thrust_, flow_;
  std::string note_;  // how a table was fitted, after the P^0 coefficients' meanings
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

#pragma once
// The dynamics and the running cost as lists of terms (internal to tools/lib/src/pmp), in the
// manner of Orekit's control/indirect adjoint terms: each force term declares the states,
// controls and parameters it needs (names, meanings, units, normalized values) and its
// contribution to f; each cost term its parameters and its contribution to the running cost L.
// Each file also describes its terms in the catalogue (helios/pmp/catalogue.hpp): the function of
// the file's name returns their entries, with the builder of each force; model.cpp builds the list
// from the spec by the catalogue and sums the contributions. A new force is one new file here, plus
// its recomputation in verify/terms/.
#include <ginac/ginac.h>

#include <memory>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/pmp/catalogue.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp::terms {

using GiNaC::ex;
using io::json;

// What a term sees of the spacecraft: position, velocity and the mass the accelerations divide
// by (1 for a sail, which has no mass state), as symbols of the problem.
struct Frame {
  std::vector<ex> r, v;
  ex mass;
};

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  // Its name in the derivation's "terms" listing (two_body, j2, thrust, ...).
  virtual std::string name() const = 0;
  // The states, controls and parameters it adds, in the order they are registered (that order
  // fixes the text of every derived expression).
  virtual std::vector<Named> states() const { return {}; }
  virtual std::vector<Control> controls() const { return {}; }
  virtual std::vector<Named> parameters() const = 0;
  // Its acceleration, added to the velocity states' rates; may record what the control law
  // needs of it in p (the sail).
  virtual std::vector<ex> acceleration(Problem& p, const Frame& x) const = 0;
  // Its contribution to the mass rate (0 unless it burns propellant).
  virtual ex mass_rate(Problem&) const { return 0; }
  // What the derivation lists beyond its name and parameters (a user acceleration's expression,
  // a third body's name).
  virtual json details(const Problem&) const { return json::object(); }
};

class CostTerm {
 public:
  virtual ~CostTerm() = default;
  virtual std::string name() const = 0;
  // The names of the (already declared) parameters it uses.
  virtual std::vector<std::string> parameters() const = 0;
  // Its contribution to the running cost L (with the homotopy parameter eps).
  virtual ex running_cost(Problem& p) const = 0;
  // Its endpoint cost phi(x(tf)) (a Mayer term; 0 for a running cost).
  virtual ex endpoint_cost(Problem&) const { return 0; }
};

using ForceList = std::vector<std::unique_ptr<ForceTerm>>;

// The cost terms (the objective picks one; their catalogue entries describe them).
std::unique_ptr<CostTerm> fuel_cost();
std::unique_ptr<CostTerm> delta_v_cost();  // an engine of constant mass without an exhaust velocity
std::unique_ptr<CostTerm> time_cost();
std::unique_ptr<CostTerm> initial_mass_cost();
std::unique_ptr<CostTerm> final_radius_cost();
std::unique_ptr<CostTerm> final_energy_cost();

// The listing of one term in the derivation: name, kind (force | cost), the parameters it uses.
TermListing listing(const std::string& name, const std::string& kind, const std::vector<std::string>& parameters,
                    const json& details = json::object());

// The unit of an acceleration and of a gravitational parameter in the units U.
inline std::string acceleration_unit(const Units& U) {
  return U.length_name + "/" + U.time_name + "^2";
}
inline std::string mu_unit(const Units& U) {
  return U.length_name + "^3/" + U.time_name + "^2";
}
// A solar-electric engine's input power at the spacecraft's distance (solar_electric.cpp): the
// arrays' P0/r^2 (r in AU) less the bus's Pbus, floored at zero where a bus is and capped at Pmax
// (a cap), each softly over its width, kSmoothWidth of Pbus and of Pmax (Pw).
constexpr double kSmoothWidth = 0.01;
ex solar_input_power(symbolic::SymbolTable& S, const Frame& x, bool bus, bool cap);
// What both solar-electric engines share (solar_electric.cpp): the spacecraft's checks (the Sun as
// the central body, a mass that changes, a throttle), the arrays' power at 1 AU and the bus in
// normalized units, the mass state, the throttle and the direction, and the acceleration and mass
// rate of a thrust and flow at full throttle, which it records on the problem with the parameters.
class SolarArrayEngine : public ForceTerm {
 public:
  std::vector<Named> states() const override { return {{"m", "mass", mass_unit_}}; }
  std::vector<Control> controls() const override;
  ex mass_rate(Problem& p) const override { return -p.max_mass_flow * p.symbols.get("u"); }

 protected:
  SolarArrayEngine(const json& spacecraft, const Units& U, std::string mass_unit);
  std::string power_unit() const { return mass_unit_ + "*" + L_ + "^2/" + T_ + "^3"; }
  // T u a / m for the full-throttle thrust and flow, both recorded on p.
  std::vector<ex> thrust_acceleration(Problem& p, const Frame& x, const ex& thrust, const ex& flow) const;

  std::string mass_unit_, L_, T_;
  double power_unit_W_ = 0, p0_ = 0, bus_ = 0;  // W per normalized power; P0 and Pbus normalized
};

// True if the spacecraft's engine is given by fits of its thrust and mass flow to its input power, or a table of them
// (solar_electric_fits.cpp) rather than by an efficiency and a specific impulse.
inline bool fitted_engine(const json& spacecraft) {
  return spacecraft.contains("thrust_polynomial_mN") || spacecraft.contains("mass_flow_polynomial_mg_s") ||
         spacecraft.contains("thruster_table");
}

// A gravitational parameter [km^3/s^2] in the units U.
inline double normalized_mu(double mu_km3_s2, const Units& U) {
  return mu_km3_s2 * U.time_s * U.time_s / (U.length_km * U.length_km * U.length_km);
}

}  // namespace helios::pmp::terms

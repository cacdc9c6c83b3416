// Sentences about the central body, the spacecraft (engine or solar sail), the perturbations of
// the dynamics and the objective.
#include "grammar.hpp"

#include "helios/astro/constants.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::spec::grammar {

void Builder::on_central(const std::smatch& m) {
  once("the central body");
  central(m[1].str(), m[2].matched ? m[2].str() : "");
}

// "gravitational parameter Q", "equatorial radius Q", "J2 coefficient N" in any order.
void Builder::central(const std::string& name, const std::string& list) {
  if (constants_body && lowercase(constants_body->first) != lowercase(name))
    throw sentence_error("the central body is " + name + ", but line " + std::to_string(constants_body->second.line) +
                         " is about " + constants_body->first + " as the central body");
  static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
  static const std::regex mu_re = re(R"((?:an? )?gravitational parameter (?:of )?)" + kQuantity);
  static const std::regex radius_re = re(R"((?:an? )?(?:equatorial )?radius (?:of )?)" + kQuantity);
  static const std::regex j2_re = re(R"((?:an? )?J2(?: coefficient)? (?:of )?()" + kNum + ")");
  central_body = {{"name", name}};
  if (!list.empty())
    for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) {
      const std::string part = *it;
      std::smatch m;
      if (std::regex_match(part, m, mu_re)) {
        set_mu(quantity(m, 1, Dimension::GravParam));
      } else if (std::regex_match(part, m, radius_re)) {
        central_body["radius_km"] = quantity(m, 1, Dimension::Length);
        radius_stated = true;
      } else if (std::regex_match(part, m, j2_re)) {
        central_body["j2"] = number(m[1].str());
      } else {
        // "mu = Q", "GM = Q": a fact in other words
        detail::SentenceFacts f;
        try {
          f = detail::read_facts(part);
        } catch (const detail::facts_error&) {
        }
        if (f.facts.size() != 1 || f.facts[0].field != detail::Field::Mu || !f.objective.empty())
          throw sentence_error("cannot read '" + part +
                               "': expected 'gravitational parameter Q', 'equatorial radius Q' or 'J2 coefficient N'");
        set_mu(f.facts[0].value[0]);
      }
    }
  if (pending_mu) central_body["mu_km3_s2"] = *pending_mu;
  if (!central_body.contains("mu_km3_s2")) {
    const auto mu = known_mu(name);
    if (!mu)
      throw sentence_error("no gravitational parameter known for '" + name +
                           "': add 'with gravitational parameter VALUE km^3/s^2'");
    central_body["mu_km3_s2"] = *mu;
  }
  if (!(central_body["mu_km3_s2"].get<double>() > 0)) throw sentence_error("gravitational parameter must be positive");
  if (!central_body.contains("radius_km"))
    if (const auto r = known_radius(name)) central_body["radius_km"] = *r;
  if (central_body.contains("radius_km") && !(central_body["radius_km"].get<double>() > 0))
    throw sentence_error("the radius must be positive");
}

void Builder::set_mu(double mu) {
  if (mu_stated) throw sentence_error("the gravitational parameter is given twice");
  mu_stated = true;
  if (central_body.is_null())
    pending_mu = mu;
  else
    central_body["mu_km3_s2"] = mu;
}

void Builder::on_has(const std::smatch& m) {
  spacecraft_clauses(m[1].str());
}

void Builder::spacecraft_clauses(const std::string& list) {
  static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
  static const std::regex clause =
      re(R"((?:an? )?(maximum thrust|specific impulse|initial mass|final mass) of )" + kQuantity);
  static const std::map<std::string, detail::Field> fields = {{"maximum thrust", detail::Field::Thrust},
                                                              {"specific impulse", detail::Field::Isp},
                                                              {"initial mass", detail::Field::InitialMass},
                                                              {"final mass", detail::Field::FinalMass}};
  // Clauses in other words ("an Isp of 2000 s", "Tmax = 0.5 N") make the sentence one of facts.
  for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) {
    const std::string part = *it;
    std::smatch m;
    if (std::regex_match(part, m, clause)) continue;
    detail::SentenceFacts f;
    try {
      f = facts_of(here.text);
    } catch (const sentence_error& e) {
      throw sentence_error("cannot read '" + part +
                           "': expected 'a maximum thrust of Q', 'a specific impulse of Q', 'an initial mass of Q' "
                           "or 'a final mass of Q' (read as facts in other words: " +
                           e.what() + ")");
    }
    return apply_facts(f);
  }
  for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) {
    const std::string part = *it;
    std::smatch m;
    if (!std::regex_match(part, m, clause))
      throw sentence_error(
          "cannot read '" + part +
          "': expected 'a maximum thrust of Q', 'a specific impulse of Q', 'an initial mass of Q' or 'a final "
          "mass of Q'");
    const detail::Field field = fields.at(lowercase(m[1].str()));
    once(field);
    ++seen["the spacecraft's engine"];
    const double value = quantity(m, 2, *detail::fact_info(field).dim);
    check_value(field, value, m[2].str() + " " + m[3].str());
    spacecraft[detail::spec_key(field)] = value;
  }
}

void Builder::on_sail(const std::smatch& m) {
  sail(quantity(m, 1, Dimension::Acceleration), quantity(m, 3, Dimension::Length) / helios::astro::AU_KM);
}

void Builder::sail(double ac_mm_s2, double ref_au) {
  once("the propulsion");
  propulsion = "solar_sail";
  if (ac_mm_s2 <= 0 || ref_au <= 0)
    throw sentence_error("the characteristic acceleration and distance must be positive");
  spacecraft["sail_characteristic_acceleration_mm_s2"] = ac_mm_s2;
  spacecraft["sail_reference_distance_AU"] = ref_au;
}

void Builder::on_j2(const std::smatch&) {
  once("the J2 perturbation");
  perturbations.push_back({{"kind", "j2"}});
}

void Builder::on_accel(const std::smatch& m) {
  once("the acceleration " + m[1].str());
  perturbations.push_back(user_acceleration(m[1].str(), m[2].str(), m[3].str()));
}

// A perturbing acceleration written as three expressions; refused here if it uses anything
// but the documented variables, so the deriver never meets an unknown symbol.
json Builder::user_acceleration(const std::string& name, const std::string& list, const std::string& unit) {
  const std::vector<std::string> items = top_level_items(list);
  if (items.size() != 3)
    throw sentence_error("the acceleration " + name + " needs three components [ax, ay, az], got " +
                         std::to_string(items.size()));
  // The components are expressions, so their unit is kept as written: one of the spec's.
  if (unit != "mm/s^2" && unit != "m/s^2" && unit != "km/s^2")
    throw sentence_error("the acceleration " + name + " is written in '" + unit +
                         "'; its components are expressions, so their unit must be mm/s^2, m/s^2 or km/s^2");
  symbolic::SymbolTable vars;
  for (const char* v : kAccelerationVariables) vars.get(v);
  for (const auto& item : items) {
    try {
      vars.parse(item, "component");
    } catch (const std::invalid_argument& e) {
      throw sentence_error(std::string(e.what()) +
                           " (variables: x, y, z, r [km], vx, vy, vz [km/s], m [kg], t [s since departure])");
    }
  }
  return {{"kind", "acceleration"}, {"name", name}, {"components", items}, {"unit", unit}};
}

void Builder::on_initial_mass(const std::smatch&) {
  once("the objective");
  objective = {{"kind", "minimum_initial_mass"}};
}

void Builder::on_fuel(const std::smatch&) {
  once("the objective");
  objective = {{"kind", "minimum_fuel"}};
}

void Builder::on_time(const std::smatch&) {
  once("the objective");
  objective = {{"kind", "minimum_time"}};
}

// "Maximize the final radius" / "... the final orbital energy": a Mayer objective on x(tf).
void Builder::on_final_state_objective(const std::smatch& m) {
  once("the objective");
  objective = {{"kind", lowercase(m[1].str()) == "radius" ? "maximum_final_radius" : "maximum_final_energy"}};
}

// "The engine thrusts at full throttle throughout": the throttle is 1, the direction the only control.
void Builder::on_full_throttle(const std::smatch&) {
  once("the engine's throttle");
  spacecraft["full_throttle"] = true;
}

}  // namespace helios::spec::grammar

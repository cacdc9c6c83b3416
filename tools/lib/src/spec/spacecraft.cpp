// The central body and its constants, and the propulsion, as the sentences of forms/ and the facts
// in other words set them.
#include "grammar.hpp"

namespace helios::spec::grammar {

void Builder::central_constant(const std::string& part) {
  static const std::regex mu_re =
      re(R"((?:an? )?(?:gravitational parameter|mu|GM|\xCE\xBC)\s*(?:of|=|:)?\s*)" + kQuantity);
  static const std::regex radius_re =
      re(R"((?:an? )?(?:(?:equatorial |mean )?radius|R|R_?E|R_?eq)\s*(?:of|=|:)?\s*)" + kQuantity);
  static const std::regex j2_re = re(R"((?:an? )?J2(?: coefficient)?\s*(?:of|=|:)?\s*()" + kNum + ")");
  std::smatch m;
  if (std::regex_match(part, m, mu_re)) return set_mu(quantity(m, 1, Dimension::GravParam));
  if (std::regex_match(part, m, radius_re)) {
    if (radius_stated) throw sentence_error("the central body's radius is given twice");
    central_body["radius_km"] = quantity(m, 1, Dimension::Length);
    radius_stated = true;
    constant_where["radius_km"] = here;
    return;
  }
  if (std::regex_match(part, m, j2_re)) {
    if (central_body.contains("j2")) throw sentence_error("the central body's J2 coefficient is given twice");
    central_body["j2"] = number(m[1].str());
    constant_where["j2"] = here;
    return;
  }
  // "GM_earth = Q": a fact in other words
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

void Builder::central(const std::string& name, const std::string& list) {
  if (constants_body && lowercase(constants_body->first) != lowercase(name))
    throw sentence_error("the central body is " + name + ", but line " + std::to_string(constants_body->second.line) +
                         " is about " + constants_body->first + " as the central body");
  static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
  central_body = {{"name", name}};
  if (!list.empty())
    for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it)
      central_constant(*it);
  if (pending_mu) central_body["mu_km3_s2"] = *pending_mu;
  if (!central_body.contains("mu_km3_s2")) {
    const auto mu = central_on_purpose ? std::nullopt : known_mu(name);
    if (!mu)
      throw sentence_error("no gravitational parameter known for '" + name +
                           "': add 'with gravitational parameter VALUE km^3/s^2'");
    central_body["mu_km3_s2"] = *mu;
  }
  if (!(central_body["mu_km3_s2"].get<double>() > 0)) throw sentence_error("gravitational parameter must be positive");
  if (!central_body.contains("radius_km") && !central_on_purpose)
    if (const auto r = known_radius(name)) central_body["radius_km"] = *r;
  if (central_body.contains("radius_km") && !(central_body["radius_km"].get<double>() > 0))
    throw sentence_error("the radius must be positive");
}

void Builder::set_mu(double mu) {
  if (mu_stated) throw sentence_error("the gravitational parameter is given twice");
  mu_stated = true;
  constant_where["mu_km3_s2"] = here;
  if (central_body.is_null())
    pending_mu = mu;
  else
    central_body["mu_km3_s2"] = mu;
}

void Builder::sail(double ac_mm_s2, double ref_au) {
  once("the propulsion");
  propulsion = "solar_sail";
  if (ac_mm_s2 <= 0 || ref_au <= 0)
    throw sentence_error("the characteristic acceleration and distance must be positive");
  spacecraft["sail_characteristic_acceleration_mm_s2"] = ac_mm_s2;
  spacecraft["sail_reference_distance_AU"] = ref_au;
}

}  // namespace helios::spec::grammar

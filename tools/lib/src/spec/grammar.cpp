// The pieces every sentence form uses: numbers with units, vectors, names and clause lists.
#include "grammar.hpp"
#include "fact_scan.hpp"

#include <cctype>
#include <cstdio>
#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {

double number(const std::string& s) {
  try {
    return std::stod(s);
  } catch (const std::out_of_range&) {
    throw sentence_error("the number " + s + " is outside the range of a double (magnitudes 2.2e-308 to 1.8e308)");
  }
}

double quantity(const std::smatch& m, std::size_t idx, Dimension d) {
  try {
    return number(m[idx].str()) * to_spec_unit(d, m[idx + 1].str());
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
}

json vector3(const std::smatch& m, std::size_t idx, Dimension d) {
  double f = 0;
  try {
    f = to_spec_unit(d, m[idx + 3].str());
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
  return json::array({number(m[idx].str()) * f, number(m[idx + 1].str()) * f, number(m[idx + 2].str()) * f});
}

std::regex re(const std::string& pattern) {
  return std::regex("^" + pattern + "$", std::regex::icase);
}

// Known gravitational parameters [km^3/s^2] for a central body named without one.
std::optional<double> known_mu(const std::string& body) {
  using namespace helios::astro;
  const std::string key = lowercase(body);
  if (key == "sun") return MU_SUN_KM3_S2;
  if (key == "earth") return MU_EARTH_KM3_S2;
  if (key == "mars") return MU_MARS_KM3_S2;
  return std::nullopt;
}

std::optional<double> known_radius(const std::string& body) {
  const std::string key = lowercase(body);
  if (key == "earth") return helios::astro::R_EARTH_KM;
  if (key == "mars") return helios::astro::R_MARS_KM;
  return std::nullopt;
}

std::optional<double> surface_radius(const std::string& body) {
  constexpr double kSunRadiusKm = 695700.0;  // IAU 2015 nominal solar radius
  if (lowercase(body) == "sun") return kSunRadiusKm;
  return known_radius(body);
}

// Splits "a, b, c" at the commas outside parentheses.
std::vector<std::string> top_level_items(const std::string& list) {
  std::vector<std::string> items(1);
  int depth = 0;
  for (char c : list) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (c == ',' && depth == 0) {
      items.emplace_back();
      continue;
    }
    items.back() += c;
  }
  for (auto& s : items) {
    s.erase(0, s.find_first_not_of(' '));
    s.erase(s.find_last_not_of(' ') + 1);
  }
  return items;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(' ') - b + 1);
}

// Factor converting `unit` into the spec unit of `d`, as a sentence error when unknown.
double unit_factor(Dimension d, const std::string& unit) {
  try {
    return to_spec_unit(d, unit);
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
}

// Splits a clause list at ';', ',', ', and' and ' and '.
std::vector<std::string> clauses_of(const std::string& list) {
  static const std::regex split(R"(\s*(?:;\s*|,\s*and\s+|,\s*|\s+and\s+)\s*)", std::regex::icase);
  std::vector<std::string> out;
  for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) out.push_back(*it);
  return out;
}

bool is_planet(const std::string& key) {
  return key == "earth" || key == "mars" || key == "venus" || key == "jupiter";
}

// A body's name as written: letters, digits and underscores, starting with a letter. It becomes a
// constraint id (in lower case) and a string inside the generated C++, so nothing else is accepted.
std::string body_name(const std::string& phrase) {
  static const std::regex the = re(R"(the (.+))");
  static const std::regex ok("[A-Za-z][A-Za-z0-9_]*");
  std::smatch m;
  const std::string name = std::regex_match(phrase, m, the) ? m[1].str() : phrase;
  if (!std::regex_match(name, ok))
    throw sentence_error("'" + phrase +
                         "' is not a body name: use letters, digits and underscores, starting with a letter (e.g. "
                         "Rock_1423)");
  const std::string key = lowercase(name);
  if (key == "departure" || key == "arrival")
    throw sentence_error("'" + name + "' cannot name a body: '" + key + "' is the id of the " + key + " constraint");
  return name;
}

// "MJD N" or "MJD2000 N" as MJD2000.
double mjd2000_of(const std::string& scale, const std::string& value) {
  try {
    return detail::day_number_epoch(scale, number(value), scale + " " + value);
  } catch (const detail::facts_error& e) {
    throw sentence_error(e.what());
  }
}

}  // namespace helios::spec::grammar

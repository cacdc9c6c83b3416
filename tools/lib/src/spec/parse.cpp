#include "helios/spec/parse.hpp"

#include <array>
#include <cctype>
#include <map>
#include <optional>
#include <regex>
#include <vector>

#include "helios/astro/constants.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/spec/units.hpp"
#include "helios/symbolic/expr.hpp"

namespace helios::spec {
namespace {

using io::json;

struct Sentence {
  std::string text;  // whitespace collapsed, final period removed
  int line = 0;      // line where it starts
};

// Thrown by the sentence handlers; turned into an input_error naming file, line and sentence.
struct sentence_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const std::string kNum = R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)";
const std::string kUnit = R"([A-Za-z][A-Za-z0-9^/]*)";
const std::string kQuantity = "(" + kNum + R"()\s*()" + kUnit + ")";
const std::string kVector =
    R"(\[\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*\]\s*()" + kUnit + ")";

std::vector<Sentence> split_sentences(const std::string& text) {
  std::vector<Sentence> out;
  std::string current;
  int line = 1, start_line = 1;
  bool in_comment = false, at_line_start = true;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      in_comment = false;
      at_line_start = true;
      if (!current.empty() && current.back() != ' ') current += ' ';
      continue;
    }
    if (in_comment) continue;
    if (at_line_start && c == '#') {
      in_comment = true;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) at_line_start = false;
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!current.empty() && current.back() != ' ') current += ' ';
      continue;
    }
    if (current.empty()) start_line = line;
    // A period ends a sentence unless it sits inside a number (digit on both sides).
    const bool next_is_digit = i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1]));
    if (c == '.' && !next_is_digit) {
      while (!current.empty() && current.back() == ' ') current.pop_back();
      if (!current.empty()) out.push_back({current, start_line});
      current.clear();
      continue;
    }
    current += c;
  }
  while (!current.empty() && current.back() == ' ') current.pop_back();
  if (!current.empty()) out.push_back({current, start_line});
  return out;
}

double number(const std::string& s) {
  return std::stod(s);
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

// "position [..] km with velocity [..] km/s", "a coasting target starting from position .. with
// velocity .." (its state at t0; it then moves unpowered) or "<Body>" (JPL low-precision ephemeris).
json parse_target(const std::string& phrase) {
  std::smatch m;
  static const std::regex state = re("(a coasting target starting from )?(?:position " + kVector + " and velocity " +
                                     kVector + "|position " + kVector + " with velocity " + kVector + ")");
  if (std::regex_match(phrase, m, state)) {
    const std::size_t base = m[2].matched ? 2 : 10;
    return {{"kind", m[1].matched ? "coasting" : "fixed_state"},
            {"position_km", vector3(m, base, Dimension::Length)},
            {"velocity_km_s", vector3(m, base + 4, Dimension::Speed)}};
  }
  static const std::regex body = re(R"((?:the )?(Earth|Mars|Venus|Jupiter))");
  if (std::regex_match(phrase, m, body)) {
    std::string name = lowercase(m[1].str());
    name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    return {{"kind", "body"}, {"body", name}, {"ephemeris", "jpl_lp"}};
  }
  throw sentence_error(
      "expected 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT', 'a coasting target starting from position "
      "... with velocity ...' or a planet name");
}

struct Builder {
  json problem, central_body, spacecraft = json::object(), objective, time = json::object(),
                              constraints = json::array(), perturbations = json::array();
  std::string propulsion = "low_thrust";
  std::map<std::string, int> seen;  // what each sentence set, to refuse contradictions

  void once(const std::string& what) {
    if (seen[what]++) throw sentence_error(what + " is given twice");
  }

  void handle(const std::string& s) {
    std::smatch m;
    static const std::regex problem_re = re(R"(Problem ([A-Za-z0-9_-]+)\s*:\s*(.+))");
    static const std::regex central_re = re(R"(The central body is (?:the )?([A-Za-z]+)(?: with (.+))?)");
    static const std::regex has_re = re(R"(The spacecraft has (.+))");
    static const std::regex depart_re = re(R"(The spacecraft departs(?: at (.+?))? from (.+))");
    static const std::regex tof_re = re(R"(The time of flight is (?:fixed at )?)" + kQuantity);
    static const std::regex free_tof_re = re(R"(The time of flight is free,? (?:at most )" + kQuantity + "|between " +
                                             kQuantity + " and " + kQuantity + ")");
    static const std::regex sail_re =
        re(R"(The spacecraft is an ideal (?:flat )?solar sail with (?:a )?characteristic acceleration (?:of )?)" +
           kQuantity + " at " + kQuantity);
    static const std::regex j2_re = re(R"(The dynamics include the J2 (?:perturbation|term) of the central body)");
    static const std::regex accel_re = re(
        R"(The dynamics include (?:a|an) (?:perturbing|additional) acceleration ([A-Za-z][A-Za-z0-9_]*) of \[(.+)\]\s*()" +
        kUnit + ")");
    static const std::regex time_re =
        re(R"(Minimi[sz]e (?:the )?(?:time of flight|flight time|final time|transfer time))");
    static const std::regex arrive_re = re(
        R"(At the final time the spacecraft (?:rendezvouses|must rendezvous) with (.+)|The spacecraft (?:rendezvouses|must rendezvous) with (.+) at the final time)");
    static const std::regex fuel_re =
        re(R"(Minimi[sz]e (?:the )?(?:fuel(?: consumption)?|propellant(?: mass)?|fuel use))");
    if (std::regex_match(s, m, problem_re)) {
      once("the problem name");
      problem = {{"id", m[1].str()}, {"title", m[2].str()}};
    } else if (std::regex_match(s, m, central_re)) {
      once("the central body");
      central(m[1].str(), m[2].matched ? m[2].str() : "");
    } else if (std::regex_match(s, m, sail_re)) {
      once("the propulsion");
      propulsion = "solar_sail";
      const double ac = quantity(m, 1, Dimension::Acceleration);
      const double ref = quantity(m, 3, Dimension::Length) / helios::astro::AU_KM;
      if (ac <= 0 || ref <= 0) throw sentence_error("the characteristic acceleration and distance must be positive");
      spacecraft["sail_characteristic_acceleration_mm_s2"] = ac;
      spacecraft["sail_reference_distance_AU"] = ref;
    } else if (std::regex_match(s, m, j2_re)) {
      once("the J2 perturbation");
      perturbations.push_back({{"kind", "j2"}});
    } else if (std::regex_match(s, m, accel_re)) {
      once("the acceleration " + m[1].str());
      perturbations.push_back(user_acceleration(m[1].str(), m[2].str(), m[3].str()));
    } else if (std::regex_match(s, m, free_tof_re)) {
      once("the time of flight");
      const double lo = m[1].matched ? 0.0 : quantity(m, 3, Dimension::Time);
      const double hi = m[1].matched ? quantity(m, 1, Dimension::Time) : quantity(m, 5, Dimension::Time);
      if (!(lo >= 0 && hi > lo)) throw sentence_error("the time-of-flight window must satisfy 0 <= min < max");
      time["final_time"] = "free";
      time["tof_min_days"] = lo;
      time["tof_max_days"] = hi;
    } else if (std::regex_match(s, m, has_re)) {
      spacecraft_clauses(m[1].str());
    } else if (std::regex_match(s, m, depart_re)) {
      once("the departure");
      if (m[1].matched) epoch(m[1].str());
      constraints.push_back(
          {{"id", "departure"}, {"kind", "initial_state"}, {"at", "t0"}, {"target", parse_target(m[2].str())}});
    } else if (std::regex_match(s, m, tof_re)) {
      once("the time of flight");
      const double tof = quantity(m, 1, Dimension::Time);
      if (tof <= 0) throw sentence_error("time of flight must be positive, got " + m[1].str() + " " + m[2].str());
      time["tof_days"] = tof;
      time["final_time"] = "fixed";
    } else if (std::regex_match(s, m, arrive_re)) {
      once("the final rendezvous");
      const std::string phrase = m[1].matched ? m[1].str() : m[2].str();
      constraints.push_back(
          {{"id", "arrival"}, {"kind", "rendezvous"}, {"at", "tf"}, {"target", parse_target(phrase)}});
    } else if (std::regex_match(s, m, fuel_re)) {
      once("the objective");
      objective = {{"kind", "minimum_fuel"}};
    } else if (std::regex_match(s, m, time_re)) {
      once("the objective");
      objective = {{"kind", "minimum_time"}};
    } else {
      throw sentence_error("it matches no form of the controlled English (see README.md, 'Controlled English')");
    }
  }

  // "gravitational parameter Q", "equatorial radius Q", "J2 coefficient N" in any order.
  void central(const std::string& name, const std::string& list) {
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
          central_body["mu_km3_s2"] = quantity(m, 1, Dimension::GravParam);
        } else if (std::regex_match(part, m, radius_re)) {
          central_body["radius_km"] = quantity(m, 1, Dimension::Length);
        } else if (std::regex_match(part, m, j2_re)) {
          central_body["j2"] = number(m[1].str());
        } else {
          throw sentence_error("cannot read '" + part +
                               "': expected 'gravitational parameter Q', 'equatorial radius Q' or 'J2 coefficient N'");
        }
      }
    if (!central_body.contains("mu_km3_s2")) {
      const auto mu = known_mu(name);
      if (!mu)
        throw sentence_error("no gravitational parameter known for '" + name +
                             "': add 'with gravitational parameter VALUE km^3/s^2'");
      central_body["mu_km3_s2"] = *mu;
    }
    if (!(central_body["mu_km3_s2"].get<double>() > 0))
      throw sentence_error("gravitational parameter must be positive");
    if (!central_body.contains("radius_km"))
      if (const auto r = known_radius(name)) central_body["radius_km"] = *r;
    if (central_body.contains("radius_km") && !(central_body["radius_km"].get<double>() > 0))
      throw sentence_error("the radius must be positive");
  }

  // A perturbing acceleration written as three expressions; refused here if it uses anything
  // but the documented variables, so the deriver never meets an unknown symbol.
  static json user_acceleration(const std::string& name, const std::string& list, const std::string& unit) {
    const std::vector<std::string> items = top_level_items(list);
    if (items.size() != 3)
      throw sentence_error("the acceleration " + name + " needs three components [ax, ay, az], got " +
                           std::to_string(items.size()));
    try {
      to_spec_unit(Dimension::Acceleration, unit);
    } catch (const std::invalid_argument& e) {
      throw sentence_error(e.what());
    }
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
    return {{"kind", "acceleration"}, {"name", name}, {"components", items}, {"unit", lowercase(unit)}};
  }

  void epoch(const std::string& phrase) {
    std::smatch m;
    static const std::regex t_re = re(R"(t\s*=\s*)" + kQuantity);
    static const std::regex mjd2000_re = re("MJD2000 (" + kNum + ")");
    static const std::regex mjd_re = re("MJD (" + kNum + ")");
    if (std::regex_match(phrase, m, t_re)) {
      time["t0_days"] = quantity(m, 1, Dimension::Time);
    } else if (std::regex_match(phrase, m, mjd2000_re)) {
      time["t0_days"] = 0.0;
      time["epoch_mjd2000"] = number(m[1].str());
    } else if (std::regex_match(phrase, m, mjd_re)) {
      time["t0_days"] = 0.0;
      time["epoch_mjd2000"] = number(m[1].str()) - helios::astro::MJD_MINUS_MJD2000;
    } else {
      throw sentence_error("departure time '" + phrase +
                           "' must read 't = VALUE UNIT', 'MJD VALUE' or 'MJD2000 VALUE'");
    }
  }

  void spacecraft_clauses(const std::string& list) {
    static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
    static const std::regex clause = re(R"((?:an? )?(maximum thrust|specific impulse|initial mass) of )" + kQuantity);
    static const std::map<std::string, std::pair<std::string, Dimension>> fields = {
        {"maximum thrust", {"thrust_N", Dimension::Force}},
        {"specific impulse", {"isp_s", Dimension::Duration}},
        {"initial mass", {"initial_mass_kg", Dimension::Mass}}};
    for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) {
      const std::string part = *it;
      std::smatch m;
      if (!std::regex_match(part, m, clause))
        throw sentence_error(
            "cannot read '" + part +
            "': expected 'a maximum thrust of Q', 'a specific impulse of Q' or 'an initial mass of Q'");
      const std::string key = lowercase(m[1].str());
      const auto& [field, dim] = fields.at(key);
      once("the " + key);
      ++seen["the spacecraft's engine"];
      const double value = quantity(m, 2, dim);
      if (value <= 0) throw sentence_error("the " + key + " must be positive, got " + m[2].str() + " " + m[3].str());
      spacecraft[field] = value;
    }
  }
};

}  // namespace

json parse_problem_text(const std::string& text, const std::string& source) {
  Builder b;
  for (const auto& sentence : split_sentences(text)) {
    try {
      b.handle(sentence.text);
    } catch (const sentence_error& e) {
      throw input_error(source + ":" + std::to_string(sentence.line) + ": cannot use sentence \"" + sentence.text +
                        "\": " + e.what());
    }
  }
  const auto missing = [&](const std::string& what, const std::string& example) {
    throw input_error(source + ": the problem text never states " + what + " (add a sentence such as \"" + example +
                      "\")");
  };
  if (b.problem.is_null()) missing("its name", "Problem S01: Earth to Mars.");
  if (b.central_body.is_null()) missing("the central body", "The central body is the Sun.");
  if (b.propulsion == "low_thrust")
    for (const auto& [field, example] : std::vector<std::pair<std::string, std::string>>{
             {"thrust_N", "The spacecraft has a maximum thrust of 0.5 N."},
             {"isp_s", "The spacecraft has a specific impulse of 2000 s."},
             {"initial_mass_kg", "The spacecraft has an initial mass of 1000 kg."}})
      if (!b.spacecraft.contains(field)) missing("the spacecraft's " + field, example);
  if (b.propulsion == "solar_sail" && b.seen.count("the spacecraft's engine"))
    throw input_error(source + ": the spacecraft is a solar sail, so it has no thrust, specific impulse or mass");
  if (!b.seen.count("the departure")) missing("the departure", "The spacecraft departs at t = 0 days from the Earth.");
  if (!b.time.contains("final_time")) missing("the time of flight", "The time of flight is 348.795 days.");
  for (const auto& p : b.perturbations)
    if (p["kind"] == "j2" && (!b.central_body.contains("j2") || !b.central_body.contains("radius_km")))
      throw input_error(source +
                        ": the J2 perturbation needs the central body's J2 coefficient and radius (\"The central "
                        "body is the Earth with J2 coefficient 1.08262668e-3 and equatorial radius 6378.137 km.\")");
  if (!b.seen.count("the final rendezvous"))
    missing("the final condition", "At the final time the spacecraft rendezvouses with Mars.");
  if (b.objective.is_null()) missing("the objective", "Minimize the fuel consumption.");
  if (!b.time.contains("t0_days")) b.time["t0_days"] = 0.0;
  json doc = io::artifact_header("spec", "helios-parse", "builtin");
  b.problem["source_file"] = source;
  doc["problem"] = b.problem;
  doc["central_body"] = b.central_body;
  doc["spacecraft"] = b.spacecraft;
  doc["dynamics"] = {{"model", "two_body"}, {"coordinates", "cartesian"}, {"propulsion", b.propulsion}};
  if (!b.perturbations.empty()) doc["dynamics"]["perturbations"] = b.perturbations;
  doc["objective"] = b.objective;
  json time = json::object();
  for (const char* k : {"t0_days", "epoch_mjd2000", "final_time", "tof_days", "tof_min_days", "tof_max_days"})
    if (b.time.contains(k)) time[k] = b.time[k];
  doc["time"] = time;
  doc["constraints"] = b.constraints;
  return doc;
}

}  // namespace helios::spec

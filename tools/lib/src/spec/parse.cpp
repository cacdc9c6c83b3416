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
  std::string key;
  for (char c : body) key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (key == "sun") return MU_SUN_KM3_S2;
  if (key == "earth") return MU_EARTH_KM3_S2;
  if (key == "mars") return MU_MARS_KM3_S2;
  return std::nullopt;
}

// "position [..] km with velocity [..] km/s" or "<Body>" (JPL low-precision ephemeris).
json parse_target(const std::string& phrase) {
  std::smatch m;
  static const std::regex state =
      re("position " + kVector + " and velocity " + kVector + "|position " + kVector + " with velocity " + kVector);
  if (std::regex_match(phrase, m, state)) {
    const std::size_t base = m[1].matched ? 1 : 9;
    return {{"kind", "fixed_state"},
            {"position_km", vector3(m, base, Dimension::Length)},
            {"velocity_km_s", vector3(m, base + 4, Dimension::Speed)}};
  }
  static const std::regex body = re(R"((?:the )?(Earth|Mars|Venus|Jupiter))");
  if (std::regex_match(phrase, m, body)) {
    std::string name = m[1].str();
    name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    for (std::size_t i = 1; i < name.size(); ++i)
      name[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(name[i])));
    return {{"kind", "body"}, {"body", name}, {"ephemeris", "jpl_lp"}};
  }
  throw sentence_error("expected 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT' or a planet name");
}

struct Builder {
  json problem, central_body, spacecraft = json::object(), objective, time = json::object(),
                              constraints = json::array();
  std::map<std::string, int> seen;  // what each sentence set, to refuse contradictions

  void once(const std::string& what) {
    if (seen[what]++) throw sentence_error(what + " is given twice");
  }

  void handle(const std::string& s) {
    std::smatch m;
    static const std::regex problem_re = re(R"(Problem ([A-Za-z0-9_-]+)\s*:\s*(.+))");
    static const std::regex central_re =
        re(R"(The central body is (?:the )?([A-Za-z]+)(?: with (?:a )?gravitational parameter (?:of )?)" + kQuantity +
           ")?");
    static const std::regex has_re = re(R"(The spacecraft has (.+))");
    static const std::regex depart_re = re(R"(The spacecraft departs(?: at (.+?))? from (.+))");
    static const std::regex tof_re = re(R"(The time of flight is (?:fixed at )?)" + kQuantity);
    static const std::regex arrive_re = re(
        R"(At the final time the spacecraft (?:rendezvouses|must rendezvous) with (.+)|The spacecraft (?:rendezvouses|must rendezvous) with (.+) at the final time)");
    static const std::regex fuel_re =
        re(R"(Minimi[sz]e (?:the )?(?:fuel(?: consumption)?|propellant(?: mass)?|fuel use))");
    if (std::regex_match(s, m, problem_re)) {
      once("the problem name");
      problem = {{"id", m[1].str()}, {"title", m[2].str()}};
    } else if (std::regex_match(s, m, central_re)) {
      once("the central body");
      const std::string name = m[1].str();
      const auto mu = m[2].matched ? std::optional<double>(quantity(m, 2, Dimension::GravParam)) : known_mu(name);
      if (!mu)
        throw sentence_error("no gravitational parameter known for '" + name +
                             "': add 'with gravitational parameter VALUE km^3/s^2'");
      if (*mu <= 0) throw sentence_error("gravitational parameter must be positive");
      central_body = {{"name", name}, {"mu_km3_s2", *mu}};
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
    } else {
      throw sentence_error("it matches no form of the controlled English (see README.md, 'Controlled English')");
    }
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
      std::string key = m[1].str();
      for (auto& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const auto& [field, dim] = fields.at(key);
      once("the " + key);
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
  for (const auto& [field, example] : std::vector<std::pair<std::string, std::string>>{
           {"thrust_N", "The spacecraft has a maximum thrust of 0.5 N."},
           {"isp_s", "The spacecraft has a specific impulse of 2000 s."},
           {"initial_mass_kg", "The spacecraft has an initial mass of 1000 kg."}})
    if (!b.spacecraft.contains(field)) missing("the spacecraft's " + field, example);
  if (!b.seen.count("the departure")) missing("the departure", "The spacecraft departs at t = 0 days from the Earth.");
  if (!b.time.contains("tof_days")) missing("the time of flight", "The time of flight is 348.795 days.");
  if (!b.seen.count("the final rendezvous"))
    missing("the final condition", "At the final time the spacecraft rendezvouses with Mars.");
  if (b.objective.is_null()) missing("the objective", "Minimize the fuel consumption.");
  if (!b.time.contains("t0_days")) b.time["t0_days"] = 0.0;
  json doc = io::artifact_header("spec", "helios-parse", "builtin");
  b.problem["source_file"] = source;
  doc["problem"] = b.problem;
  doc["central_body"] = b.central_body;
  doc["spacecraft"] = b.spacecraft;
  doc["dynamics"] = {{"model", "two_body"}, {"coordinates", "cartesian"}, {"propulsion", "low_thrust"}};
  doc["objective"] = b.objective;
  json time = json::object();
  for (const char* k : {"t0_days", "epoch_mjd2000", "final_time", "tof_days"})
    if (b.time.contains(k)) time[k] = b.time[k];
  doc["time"] = time;
  doc["constraints"] = b.constraints;
  return doc;
}

}  // namespace helios::spec

#include "helios/spec/parse.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <map>
#include <optional>
#include <regex>
#include <vector>

#include "facts.hpp"
#include "helios/astro/constants.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/spec/units.hpp"
#include "helios/symbolic/expr.hpp"
#include "text.hpp"

namespace helios::spec {
namespace {

using detail::Sentence;
using io::json;

// Thrown by the sentence handlers; turned into an input_error naming file, line and sentence.
struct sentence_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const std::string kNum = R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)";
const std::string kUnit = R"([A-Za-z][A-Za-z0-9^/]*)";
const std::string kQuantity = "(" + kNum + R"()\s*()" + kUnit + ")";
const std::string kVector =
    R"(\[\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*\]\s*()" + kUnit + ")";

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

// Where an item of the text stands, for errors found after the whole text was read.
struct Where {
  int line = 0;
  std::string text;
  bool table_row = false;
};

std::string num_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
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

// "position [..] km with velocity [..] km/s", "a coasting target starting from position .. with
// velocity .." (its state at t0; it then moves unpowered) or a body's name, kept as {"ref": NAME}
// and looked up once the whole text is read (a body given by its orbit, else a planet).
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
  if (phrase.find('[') == std::string::npos) {
    try {
      return {{"ref", body_name(phrase)}};
    } catch (const sentence_error& e) {
      throw sentence_error(std::string(e.what()) +
                           "; a state reads 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT'");
    }
  }
  throw sentence_error(
      "expected 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT', 'a coasting target starting from position "
      "... with velocity ...' or a body's name");
}

// Which element a name in an orbit sentence or a table header stands for: a, e, i, raan, argp,
// mean or true (the anomaly), or "" if none.
std::string element_field(const std::string& name) {
  static const std::map<std::string, std::string> fields = {{"a", "a"},
                                                            {"semi-major axis", "a"},
                                                            {"semimajor axis", "a"},
                                                            {"e", "e"},
                                                            {"eccentricity", "e"},
                                                            {"i", "i"},
                                                            {"inclination", "i"},
                                                            {"node", "raan"},
                                                            {"raan", "raan"},
                                                            {"ascending node", "raan"},
                                                            {"longitude of the ascending node", "raan"},
                                                            {"right ascension of the ascending node", "raan"},
                                                            {"argument of perihelion", "argp"},
                                                            {"argument of periapsis", "argp"},
                                                            {"argument of pericenter", "argp"},
                                                            {"argument of pericentre", "argp"},
                                                            {"mean anomaly", "mean"},
                                                            {"true anomaly", "true"}};
  const auto it = fields.find(lowercase(trimmed(name)));
  return it == fields.end() ? "" : it->second;
}

// Classical elements in the spec's units, checked for an ellipse.
json elements_json(double epoch_mjd2000, const std::map<std::string, double>& v) {
  const double a = v.at("a"), e = v.at("e");
  if (!(a > 0)) throw sentence_error("the semi-major axis must be positive, got " + num_text(a) + " AU");
  if (!(e >= 0 && e < 1)) throw sentence_error("the eccentricity must satisfy 0 <= e < 1, got " + num_text(e));
  const bool mean = v.count("mean") != 0;
  return {{"epoch_mjd2000", epoch_mjd2000},
          {"a_AU", a},
          {"e", e},
          {"i_deg", v.at("i")},
          {"raan_deg", v.at("raan")},
          {"argp_deg", v.at("argp")},
          {mean ? "mean_anomaly_deg" : "true_anomaly_deg", mean ? v.at("mean") : v.at("true")}};
}

// "MJD N" or "MJD2000 N" as MJD2000.
double mjd2000_of(const std::string& scale, const std::string& value) {
  const double v = number(value);
  return lowercase(scale) == "mjd" ? v - helios::astro::MJD_MINUS_MJD2000 : v;
}

// A window bound: "day N" (days after the epoch) or an absolute "MJD N" / "MJD2000 N".
struct EpochRef {
  double value = 0;  // days, or MJD2000 when absolute
  bool absolute = false;
};

// A body given by its orbital elements (a sentence or a table row).
struct OrbitDef {
  std::string name, about;  // about: the body it orbits as written ("" = the central body)
  json elements;
  Where where;
  bool used = false;
};

// An event on the way: a rendezvous, a flyby or a gravity assist inside a window.
struct Event {
  Where where;
  std::string kind, body;
  EpochRef lo, hi;
  std::optional<double> stay, drop, mu, rmin, max_speed;
  Where drop_where;
  json target;
  double window_lo = 0, window_hi = 0;
};

// The departure or the final condition (a rendezvous, or a flyby with an optional speed bound).
struct Endpoint {
  Where where;
  json target;
  std::string kind = "rendezvous";
  std::optional<double> max_speed;
};

// Columns of an elements table: unit factors of a and the angles, which anomaly, which epoch scale.
struct TableColumns {
  double a_factor = 1;
  std::array<double, 4> angle_factor{};  // i, node, argp, anomaly
  std::string anomaly, epoch_scale;
};

const char* const kTableHeader =
    "| body | a [AU] | e | i [deg] | node [deg] | argument of perihelion [deg] | mean anomaly [deg] | epoch [MJD] |";

struct Builder {
  explicit Builder(std::string src) : source(std::move(src)) {}

  std::string source;
  Where here;  // the item being read
  json problem, central_body, spacecraft = json::object(), objective, time = json::object(),
                              perturbations = json::array();
  std::optional<Endpoint> departure, arrival;
  std::vector<Event> events;
  std::vector<OrbitDef> orbits;
  std::optional<TableColumns> table;  // a table's header was read and its rows may follow
  bool table_separator_allowed = false;
  std::optional<Where> table_intro;  // a sentence announcing a table, waiting for its header
  std::string table_about;
  Where free_departure_where;
  bool departure_at_t = false;
  std::string propulsion = "low_thrust";
  std::map<std::string, int> seen;  // what each sentence set, to refuse contradictions

  void once(const std::string& what) {
    if (seen[what]++) throw sentence_error(what + " is given twice");
  }

  [[noreturn]] void fail(const Where& w, const std::string& why) const {
    throw input_error(source + ":" + std::to_string(w.line) + ": cannot use " +
                      (w.table_row ? "table row" : "sentence") + " \"" + w.text + "\": " + why);
  }

  // One item of the text; a sentence error is reported at it.
  void read(const Sentence& item) {
    here = {item.line, item.text, item.table_row};
    try {
      if (table_intro && !(item.table_row && is_table_header(item.text)))
        throw sentence_error("it follows a sentence announcing a table, so it must be the table's header " +
                             std::string(kTableHeader));
      if (item.table_row) {
        table_line(item.text);
      } else {
        table.reset();
        handle(item.text);
      }
    } catch (const sentence_error& e) {
      fail(here, e.what());
    }
  }

  // A sentence of the controlled English: the first rule whose pattern matches it whole applies.
  struct SentenceRule {
    std::regex pattern;
    void (Builder::*apply)(const std::smatch&);
  };

  void handle(const std::string& s) {
    static const std::vector<SentenceRule> rules = {
        {re(R"(Problem ([A-Za-z0-9_-]+)\s*:\s*(.+))"), &Builder::on_problem},
        {re(R"(The central body is (?:the )?([A-Za-z]+)(?: with (.+))?)"), &Builder::on_central},
        {re(R"(The spacecraft is an ideal (?:flat )?solar sail with (?:a )?characteristic acceleration (?:of )?)" +
            kQuantity + " at " + kQuantity),
         &Builder::on_sail},
        {re(R"(The dynamics include the J2 (?:perturbation|term) of the central body)"), &Builder::on_j2},
        {re(R"(The dynamics include (?:a|an) (?:perturbing|additional) acceleration ([A-Za-z][A-Za-z0-9_]*) of \[(.+)\]\s*()" +
            kUnit + ")"),
         &Builder::on_accel},
        {re(R"(The (?:total )?time of flight is free,? (?:at most )" + kQuantity + "|between " + kQuantity + " and " +
            kQuantity + ")"),
         &Builder::on_free_tof},
        {re(R"(The spacecraft has (.+))"), &Builder::on_has},
        {re(R"(The spacecraft departs from (.+) at ((?:t\s*=|MJD2000 |MJD ).+))"), &Builder::on_depart_from},
        {re(R"(The spacecraft departs(?: at (.+?))? from (.+))"), &Builder::on_depart},
        {re(R"(The (?:total )?time of flight is (?:fixed at )?)" + kQuantity), &Builder::on_tof},
        {re(R"(At the final time the spacecraft (?:rendezvouses|must rendezvous) with (.+)|The spacecraft (?:rendezvouses|must rendezvous) with (.+) at the final time)"),
         &Builder::on_arrive},
        {re(R"(At the final time the spacecraft (?:flies|must fly) by (.+?)(?:,? with a relative speed of at most )" +
            kQuantity + ")?"),
         &Builder::on_arrive_flyby},
        {re(R"(Minimi[sz]e (?:the )?(?:initial|launch|departure|wet) mass)"), &Builder::on_initial_mass},
        {re(R"(Minimi[sz]e (?:the )?(?:fuel(?: consumption)?|propellant(?: mass)?|fuel use))"), &Builder::on_fuel},
        {re(R"(Minimi[sz]e (?:the )?(?:time of flight|flight time|final time|transfer time))"), &Builder::on_time},
        {re(R"((?:the (?:asteroid|comet|planet|moon|body|object) )?(.+?) moves on an? (?:Keplerian )?orbit (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*) with (.+?)(?: at (?:the )?(?:epoch )?(MJD2000|MJD) ()" +
            kNum + "))?"),
         &Builder::on_orbit},
        {re(R"(The (?:following )?(?:bodies|asteroids|comets|planets|targets) move on (?:Keplerian )?orbits (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*)(?: with (?:these|the following) elements)?\s*:?)"),
         &Builder::on_intro},
        {re(R"(The departure (?:epoch|date) is free,? between )" + kQuantity + " (before|after) and " + kQuantity +
            " (before|after) (MJD2000|MJD) (" + kNum + ")"),
         &Builder::on_free_dep},
        {re(R"(The departure (?:epoch|date) is free,? within )" + kQuantity + " (?:of|around) (MJD2000|MJD) (" + kNum +
            ")"),
         &Builder::on_free_dep_within},
        {re(R"(The spacecraft (rendezvouses with|must rendezvous with|flies by|must fly by|swings by|must swing by) (.+))"),
         &Builder::on_event},
        {re(R"((?:It|The spacecraft) (?:leaves|drops|releases) (?:a|an) (?:lander|probe|payload|package) of )" +
            kQuantity + " at (.+)"),
         &Builder::on_drop},
    };
    std::smatch m;
    for (const auto& rule : rules)
      if (std::regex_match(s, m, rule.pattern)) return (this->*rule.apply)(m);
    if (detail::states_nothing(s))
      throw sentence_error("it matches no form of the controlled English (see README.md, 'Controlled English')");
    apply_facts(facts_of(s));
  }

  // ---- facts stated in other words (facts.cpp), when no form matches ---------------------------

  std::optional<json> r0, v0, rf, vf;  // state vectors stated one by one
  Where initial_where, final_where;
  bool mu_stated = false;
  std::optional<double> pending_mu;  // a gravitational parameter stated before the central body

  static detail::SentenceFacts facts_of(const std::string& s) {
    try {
      return detail::read_facts(s);
    } catch (const detail::facts_error& e) {
      throw sentence_error(std::string(e.what()) +
                           (e.suggestion.empty() ? "" : "; did you mean \"" + e.suggestion + "\"?"));
    }
  }

  void set_mu(double mu) {
    if (mu_stated) throw sentence_error("the gravitational parameter is given twice");
    mu_stated = true;
    if (central_body.is_null())
      pending_mu = mu;
    else
      central_body["mu_km3_s2"] = mu;
  }

  void apply_facts(const detail::SentenceFacts& f) {
    using detail::Field;
    if (!f.central.empty()) {
      once("the central body");
      central(f.central, "");
    }
    const auto engine = [&](Field field, const char* key, double v) {
      once(detail::field_name(field));
      ++seen["the spacecraft's engine"];
      spacecraft[key] = v;
    };
    const auto state = [&](std::optional<json>& slot, Field field, bool initial, const json& v) {
      once(detail::field_name(field));
      if (initial && !r0 && !v0) {
        once("the departure");
        initial_where = here;
      }
      if (!initial && !rf && !vf) {
        once("the final rendezvous");
        final_where = here;
      }
      slot = v;
    };
    for (const auto& fact : f.facts) {
      const double v = fact.value[0];
      const json vec = fact.value.size() == 3 ? json(fact.value) : json();
      switch (fact.field) {
        case Field::Thrust:
          engine(fact.field, "thrust_N", v);
          break;
        case Field::Isp:
          engine(fact.field, "isp_s", v);
          break;
        case Field::InitialMass:
          engine(fact.field, "initial_mass_kg", v);
          break;
        case Field::FinalMass:
          engine(fact.field, "final_mass_kg", v);
          break;
        case Field::Tof:
          once("the time of flight");
          time["tof_days"] = v;
          time["final_time"] = "fixed";
          break;
        case Field::T0:
          once("the departure time");
          time["t0_days"] = v;
          departure_at_t = true;
          break;
        case Field::Mu:
          set_mu(v);
          break;
        case Field::R0:
          state(r0, fact.field, true, vec);
          break;
        case Field::V0:
          state(v0, fact.field, true, vec);
          break;
        case Field::Rf:
          state(rf, fact.field, false, vec);
          break;
        case Field::Vf:
          state(vf, fact.field, false, vec);
          break;
      }
    }
    if (!f.objective.empty()) {
      once("the objective");
      objective = {{"kind", f.objective}};
    }
  }

  // The departure and the final state from vectors stated one by one.
  void finish_facts() {
    const auto endpoint = [&](const std::optional<json>& r, const std::optional<json>& v, const Where& w,
                              const char* which, std::optional<Endpoint>& out, const char* kind) {
      if (!r && !v) return;
      if (!r || !v)
        fail(w, std::string("it gives the ") + which + (r ? " position" : " velocity") + " but no sentence gives the " +
                    which + (r ? " velocity" : " position"));
      out = Endpoint{w, {{"kind", "fixed_state"}, {"position_km", *r}, {"velocity_km_s", *v}}, kind, std::nullopt};
    };
    endpoint(r0, v0, initial_where, "initial", departure, "initial_state");
    endpoint(rf, vf, final_where, "final", arrival, "rendezvous");
  }

  // ---- one handler per sentence form (handle's rules, in their order) ---------------------------

  void on_problem(const std::smatch& m) {
    once("the problem name");
    problem = {{"id", m[1].str()}, {"title", m[2].str()}};
  }

  void on_central(const std::smatch& m) {
    once("the central body");
    central(m[1].str(), m[2].matched ? m[2].str() : "");
  }

  void on_sail(const std::smatch& m) {
    once("the propulsion");
    propulsion = "solar_sail";
    const double ac = quantity(m, 1, Dimension::Acceleration);
    const double ref = quantity(m, 3, Dimension::Length) / helios::astro::AU_KM;
    if (ac <= 0 || ref <= 0) throw sentence_error("the characteristic acceleration and distance must be positive");
    spacecraft["sail_characteristic_acceleration_mm_s2"] = ac;
    spacecraft["sail_reference_distance_AU"] = ref;
  }

  void on_j2(const std::smatch&) {
    once("the J2 perturbation");
    perturbations.push_back({{"kind", "j2"}});
  }

  void on_accel(const std::smatch& m) {
    once("the acceleration " + m[1].str());
    perturbations.push_back(user_acceleration(m[1].str(), m[2].str(), m[3].str()));
  }

  void on_free_tof(const std::smatch& m) {
    once("the time of flight");
    const double lo = m[1].matched ? 0.0 : quantity(m, 3, Dimension::Time);
    const double hi = m[1].matched ? quantity(m, 1, Dimension::Time) : quantity(m, 5, Dimension::Time);
    if (!(lo >= 0 && hi > lo)) throw sentence_error("the time-of-flight window must satisfy 0 <= min < max");
    time["final_time"] = "free";
    time["tof_min_days"] = lo;
    time["tof_max_days"] = hi;
  }

  void on_has(const std::smatch& m) { spacecraft_clauses(m[1].str()); }

  void on_depart_from(const std::smatch& m) { depart(m[2].str(), m[1].str()); }

  void on_depart(const std::smatch& m) { depart(m[1].matched ? m[1].str() : "", m[2].str()); }

  void on_tof(const std::smatch& m) {
    once("the time of flight");
    const double tof = quantity(m, 1, Dimension::Time);
    if (tof <= 0) throw sentence_error("time of flight must be positive, got " + m[1].str() + " " + m[2].str());
    time["tof_days"] = tof;
    time["final_time"] = "fixed";
  }

  void on_arrive(const std::smatch& m) {
    once("the final rendezvous");
    const std::string phrase = m[1].matched ? m[1].str() : m[2].str();
    arrival = Endpoint{here, parse_target(phrase), "rendezvous", std::nullopt};
  }

  void on_arrive_flyby(const std::smatch& m) {
    once("the final rendezvous");
    arrival = Endpoint{here, parse_target(m[1].str()), "flyby", std::nullopt};
    if (m[2].matched) {
      const double v = quantity(m, 2, Dimension::Speed);
      if (!(v > 0)) throw sentence_error("the relative speed bound must be positive");
      arrival->max_speed = v;
    }
  }

  void on_initial_mass(const std::smatch&) {
    once("the objective");
    objective = {{"kind", "minimum_initial_mass"}};
  }

  void on_fuel(const std::smatch&) {
    once("the objective");
    objective = {{"kind", "minimum_fuel"}};
  }

  void on_time(const std::smatch&) {
    once("the objective");
    objective = {{"kind", "minimum_time"}};
  }

  void on_orbit(const std::smatch& m) { orbit_sentence(m); }

  void on_intro(const std::smatch& m) {
    table_intro = here;
    table_about = m[1].str();
  }

  void on_free_dep(const std::smatch& m) {
    once("the departure window");
    const double a = quantity(m, 1, Dimension::Time), b = quantity(m, 4, Dimension::Time);
    if (a < 0 || b < 0) throw sentence_error("say 'N days before' or 'N days after' with N >= 0");
    const double lo = lowercase(m[3].str()) == "before" ? -a : a;
    const double hi = lowercase(m[6].str()) == "before" ? -b : b;
    if (!(hi > lo)) throw sentence_error("the departure window is empty: its start must come before its end");
    free_departure(lo, hi, mjd2000_of(m[7].str(), m[8].str()));
  }

  void on_free_dep_within(const std::smatch& m) {
    once("the departure window");
    const double a = quantity(m, 1, Dimension::Time);
    if (!(a > 0)) throw sentence_error("the departure window's half-width must be positive");
    free_departure(-a, a, mjd2000_of(m[3].str(), m[4].str()));
  }

  void on_event(const std::smatch& m) {
    const std::string verb = lowercase(m[1].str());
    event(verb.find("rendezvous") != std::string::npos ? "rendezvous"
          : verb.find("fl") != std::string::npos       ? "flyby"
                                                       : "gravity_assist",
          m[2].str());
  }

  void on_drop(const std::smatch& m) { lander(quantity(m, 1, Dimension::Mass), body_name(m[3].str())); }

  // ---- departure and epochs -------------------------------------------------------------------

  void depart(const std::string& at, const std::string& target) {
    once("the departure");
    if (!at.empty()) epoch(at);
    departure = Endpoint{here, parse_target(target), "initial_state", std::nullopt};
  }

  void set_epoch(double mjd2000) {
    if (time.contains("epoch_mjd2000") && time["epoch_mjd2000"].get<double>() != mjd2000)
      throw sentence_error("the epoch MJD2000 " + num_text(mjd2000) + " contradicts the epoch MJD2000 " +
                           num_text(time["epoch_mjd2000"].get<double>()) + " stated before");
    time["t0_days"] = 0.0;
    time["epoch_mjd2000"] = mjd2000;
  }

  void epoch(const std::string& phrase) {
    std::smatch m;
    static const std::regex t_re = re(R"(t\s*=\s*)" + kQuantity);
    static const std::regex mjd_re = re("(MJD2000|MJD) (" + kNum + ")");
    if (std::regex_match(phrase, m, t_re)) {
      once("the departure time");
      time["t0_days"] = quantity(m, 1, Dimension::Time);
      departure_at_t = true;
    } else if (std::regex_match(phrase, m, mjd_re)) {
      set_epoch(mjd2000_of(m[1].str(), m[2].str()));
    } else {
      throw sentence_error("departure time '" + phrase +
                           "' must read 't = VALUE UNIT', 'MJD VALUE' or 'MJD2000 VALUE'");
    }
  }

  void free_departure(double lo, double hi, double mjd2000) {
    set_epoch(mjd2000);
    time["departure"] = "free";
    time["t0_window_days"] = json::array({lo, hi});
    free_departure_where = here;
  }

  // ---- bodies given by their orbits ----------------------------------------------------------

  void define_orbit(const std::string& written, const std::string& about, json elements) {
    const std::string name = body_name(written);
    for (const auto& o : orbits)
      if (lowercase(o.name) == lowercase(name))
        throw sentence_error("the orbit of " + name + " is given twice (first on line " + std::to_string(o.where.line) +
                             ")");
    orbits.push_back({name, about, std::move(elements), here});
  }

  // "NAME moves on a Keplerian orbit about the Sun with a = Q, e = N, ... at MJD N".
  void orbit_sentence(const std::smatch& m) {
    const std::string name = body_name(m[1].str());
    if (!m[4].matched)
      throw sentence_error("the elements of " + name +
                           " need their epoch: end the sentence with 'at MJD N' or "
                           "'at MJD2000 N'");
    static const std::regex clause = re(R"((.+?)\s*=\s*()" + kNum + R"()(?:\s*()" + kUnit + "))?");
    std::map<std::string, double> v;
    for (const auto& part : clauses_of(m[3].str())) {
      std::smatch c;
      const std::string field = std::regex_match(part, c, clause) ? element_field(c[1].str()) : "";
      if (field.empty())
        throw sentence_error("cannot read '" + part +
                             "': expected 'a = Q', 'e = N', 'i = Q', 'node = Q', 'argument of perihelion = Q' and "
                             "'mean anomaly = Q' or 'true anomaly = Q'");
      if (v.count(field) || (field == "mean" && v.count("true")) || (field == "true" && v.count("mean")))
        throw sentence_error("'" + part + "' repeats an element of " + name);
      v[field] = number(c[2].str()) * element_unit(field, c[3].matched ? c[3].str() : "");
    }
    for (const char* f : {"a", "e", "i", "raan", "argp"})
      if (!v.count(f)) throw sentence_error("the orbit of " + name + " lacks its " + element_label(f));
    if (!v.count("mean") && !v.count("true"))
      throw sentence_error("the orbit of " + name + " lacks its anomaly ('mean anomaly = Q' or 'true anomaly = Q')");
    define_orbit(name, m[2].str(), elements_json(mjd2000_of(m[4].str(), m[5].str()), v));
  }

  static std::string element_label(const std::string& field) {
    static const std::map<std::string, std::string> labels = {{"a", "semi-major axis ('a = Q')"},
                                                              {"e", "eccentricity ('e = N')"},
                                                              {"i", "inclination ('i = Q')"},
                                                              {"raan", "ascending node ('node = Q')"},
                                                              {"argp", "argument of perihelion"}};
    return labels.at(field);
  }

  // Factor to the spec unit of an element: a in AU, angles in deg, e a pure number.
  static double element_unit(const std::string& field, const std::string& unit) {
    if (field == "e") {
      if (!unit.empty()) throw sentence_error("the eccentricity is a pure number, not in '" + unit + "'");
      return 1.0;
    }
    if (unit.empty())
      throw sentence_error("the " + std::string(field == "a" ? "semi-major axis needs a length unit (AU, km)"
                                                             : "angles need a unit (deg or rad)"));
    if (field == "a") return unit_factor(Dimension::Length, unit) / helios::astro::AU_KM;
    return unit_factor(Dimension::Angle, unit);
  }

  // ---- elements tables -------------------------------------------------------------------------

  static std::vector<std::string> cells_of(const std::string& row) {
    if (row.size() < 2 || row.back() != '|') throw sentence_error("a table line starts and ends with '|'");
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < row.size(); ++i) {
      if (row[i] == '|') {
        cells.push_back(trimmed(cell));
        cell.clear();
      } else {
        cell += row[i];
      }
    }
    return cells;
  }

  static bool is_table_header(const std::string& row) {
    static const std::regex first = re(R"(\|\s*(?:body|name)\s*\|.*)");
    return std::regex_match(row, first);
  }

  void table_line(const std::string& row) {
    const std::vector<std::string> cells = cells_of(row);
    if (is_table_header(row)) {
      table = table_header(cells);
      table_separator_allowed = true;
      table_intro.reset();
      return;
    }
    static const std::regex rule(R"(\s*:?-+:?\s*)");
    const bool is_rule =
        std::all_of(cells.begin(), cells.end(), [](const std::string& c) { return std::regex_match(c, rule); });
    if (!table) throw sentence_error("a table row needs its header line just above it: " + std::string(kTableHeader));
    if (is_rule) {
      if (!table_separator_allowed) throw sentence_error("a rule line may only follow the table's header");
      table_separator_allowed = false;
      return;
    }
    table_separator_allowed = false;
    if (cells.size() != 8)
      throw sentence_error("the row has " + std::to_string(cells.size()) + " cells where the header has 8");
    static const std::regex num_re("\\s*" + kNum + "\\s*");
    for (std::size_t k = 1; k < cells.size(); ++k)
      if (!std::regex_match(cells[k], num_re))
        throw sentence_error("cell " + std::to_string(k + 1) + " '" + cells[k] + "' is not a number");
    const TableColumns& t = *table;
    std::map<std::string, double> v = {
        {"a", number(cells[1]) * t.a_factor},           {"e", number(cells[2])},
        {"i", number(cells[3]) * t.angle_factor[0]},    {"raan", number(cells[4]) * t.angle_factor[1]},
        {"argp", number(cells[5]) * t.angle_factor[2]}, {t.anomaly, number(cells[6]) * t.angle_factor[3]}};
    define_orbit(cells[0], table_about, elements_json(mjd2000_of(t.epoch_scale, cells[7]), v));
  }

  TableColumns table_header(const std::vector<std::string>& cells) {
    const std::string layout = std::string("the header reads ") + kTableHeader +
                               " (a in AU or km, angles in deg or rad, 'true anomaly' instead of 'mean anomaly', "
                               "epoch in MJD or MJD2000)";
    if (cells.size() != 8)
      throw sentence_error("the header has " + std::to_string(cells.size()) + " columns, not 8: " + layout);
    static const std::regex cell_re(R"(([^\[]*?)\s*(?:\[\s*([^\]]*?)\s*\])?)");
    static const std::array<std::string, 8> expected = {"body", "a", "e", "i", "raan", "argp", "anomaly", "epoch"};
    TableColumns t;
    for (std::size_t k = 1; k < 8; ++k) {
      std::smatch m;
      std::regex_match(cells[k], m, cell_re);
      const std::string key = lowercase(m[1].str()), unit = m[2].str();
      std::string field = key == "epoch" ? "epoch" : element_field(key);
      if (field == "mean" || field == "true") {
        t.anomaly = field;
        field = "anomaly";
      }
      if (field != expected[k])
        throw sentence_error("column " + std::to_string(k + 1) + " is '" + cells[k] + "': " + layout);
      if (field == "epoch") {
        if (lowercase(unit) != "mjd" && lowercase(unit) != "mjd2000")
          throw sentence_error("the epoch column must say [MJD] or [MJD2000], got '" + cells[k] + "'");
        t.epoch_scale = unit;
      } else if (field == "a") {
        t.a_factor = element_unit("a", unit);
      } else if (field == "e") {
        element_unit("e", unit);
      } else {
        t.angle_factor[k - 3] = element_unit(field, unit);
      }
    }
    return t;
  }

  // ---- events on the way ---------------------------------------------------------------------

  static EpochRef epoch_ref(const std::string& scale, const std::string& value) {
    if (lowercase(scale) == "day") return {number(value), false};
    return {mjd2000_of(scale, value), true};
  }

  // "<verb> NAME between day N and day N[ in an unpowered gravity assist][, CLAUSE[ and CLAUSE]]".
  void event(const std::string& kind, const std::string& rest) {
    static const std::regex window_re =
        re(R"((.+?) between (day|MJD2000|MJD) ()" + kNum + R"() and (day|MJD2000|MJD) ()" + kNum + R"()(.*))");
    std::smatch m;
    if (!std::regex_match(rest, m, window_re)) {
      if (rest.find(" between ") != std::string::npos)
        throw sentence_error(
            "the window must read 'between day N and day N' (days after the epoch) or 'between "
            "MJD2000 N and MJD2000 N'");
      throw sentence_error(
          "an event on the way needs its window ('... between day N and day N'); a rendezvous at "
          "the end reads 'At the final time the spacecraft rendezvouses with NAME'");
    }
    Event e;
    e.where = here;
    e.kind = kind;
    e.body = body_name(m[1].str());
    e.lo = epoch_ref(m[2].str(), m[3].str());
    e.hi = epoch_ref(m[4].str(), m[5].str());
    std::string tail = m[6].str();
    if (kind == "gravity_assist") {
      static const std::regex ga_re = re(R"(\s*(?:in|as|for) an? (?:unpowered )?gravity assist(.*))");
      std::smatch g;
      if (std::regex_match(tail, g, ga_re)) tail = g[1].str();
    }
    if (!trimmed(tail).empty()) {
      static const std::regex lead = re(R"(\s*(?:[;,]\s*(?:and\s+)?|and\s+)(.+))");
      std::smatch l;
      if (!std::regex_match(tail, l, lead))
        throw sentence_error("cannot read '" + trimmed(tail) + "' after the window: " + clause_forms(kind));
      for (const auto& part : clauses_of(l[1].str())) event_clause(e, part);
    }
    if (kind == "gravity_assist" && !e.mu) {
      const std::string key = lowercase(e.body);
      const auto mu = key == "sun" ? std::nullopt : known_mu(e.body);
      if (!mu)
        throw sentence_error("the gravitational parameter of " + e.body + " is not known: add '; " + e.body +
                             " has a gravitational parameter of Q km^3/s^2'");
      e.mu = *mu;
    }
    if (e.drop) e.drop_where = here;
    events.push_back(e);
  }

  static std::string clause_forms(const std::string& kind) {
    if (kind == "rendezvous")
      return "a rendezvous takes 'stays there for Q', 'does not stay' and 'leaves a lander of Q'";
    if (kind == "flyby") return "a flyby matches the position only and takes 'the relative speed must be at most Q'";
    return "a gravity assist takes 'NAME has a gravitational parameter of Q' and 'the periapsis radius must be at "
           "least Q'";
  }

  // The body a clause names ("at NAME", "NAME has ...") must be the event's.
  static void same_body(const Event& e, const std::string& phrase) {
    const std::string named = body_name(phrase);
    if (lowercase(named) != lowercase(e.body) && lowercase(named) != "it")
      throw sentence_error("the clause names " + named + " but the event is at " + e.body);
  }

  void event_clause(Event& e, const std::string& part) {
    static const std::regex stay_re = re(R"(stays(?: there| at (.+?))? for )" + kQuantity);
    static const std::regex no_stay_re = re(R"(does not stay(?: there)?)");
    static const std::regex lander_re =
        re(R"((?:leaves|drops|releases) (?:a|an) (?:lander|probe|payload|package) of )" + kQuantity +
           R"((?: there| at (.+))?)");
    static const std::regex mu_re = re(R"((.+?) has a gravitational parameter of )" + kQuantity);
    static const std::regex rmin_re = re(
        R"((?:(?:the )?(?:periapsis|pericenter|pericentre|closest approach) radius (?:must be|is) at least |(?:the )?(?:minimum|lowest) (?:periapsis|pericenter|pericentre) radius is ))" +
        kQuantity);
    static const std::regex speed_re =
        re(R"((?:(?:the )?relative speed (?:must be|is) at most |with a relative speed of at most ))" + kQuantity);
    std::smatch m;
    const auto set = [&](std::optional<double>& slot, double value, const std::string& what) {
      if (slot) throw sentence_error(what + " at " + e.body + " is given twice");
      slot = value;
    };
    if (e.kind == "rendezvous" && std::regex_match(part, m, stay_re)) {
      if (m[1].matched) same_body(e, m[1].str());
      const double stay = quantity(m, 2, Dimension::Time);
      if (stay < 0) throw sentence_error("the stay must not be negative, got " + m[2].str() + " " + m[3].str());
      set(e.stay, stay, "the stay");
    } else if (e.kind == "rendezvous" && std::regex_match(part, m, no_stay_re)) {
      set(e.stay, 0.0, "the stay");
    } else if (e.kind == "rendezvous" && std::regex_match(part, m, lander_re)) {
      if (m[3].matched) same_body(e, m[3].str());
      const double drop = quantity(m, 1, Dimension::Mass);
      if (!(drop > 0)) throw sentence_error("the lander's mass must be positive, got " + m[1].str() + " " + m[2].str());
      set(e.drop, drop, "the lander");
    } else if (e.kind == "gravity_assist" && std::regex_match(part, m, mu_re)) {
      same_body(e, m[1].str());
      const double mu = quantity(m, 2, Dimension::GravParam);
      if (!(mu > 0)) throw sentence_error("the gravitational parameter must be positive");
      set(e.mu, mu, "the gravitational parameter");
    } else if (e.kind == "flyby" && std::regex_match(part, m, speed_re)) {
      const double v = quantity(m, 1, Dimension::Speed);
      if (!(v > 0)) throw sentence_error("the relative speed bound must be positive");
      set(e.max_speed, v, "the relative speed bound");
    } else if (e.kind == "gravity_assist" && std::regex_match(part, m, rmin_re)) {
      const double r = quantity(m, 1, Dimension::Length);
      if (!(r > 0)) throw sentence_error("the periapsis radius must be positive");
      set(e.rmin, r, "the lowest periapsis radius");
    } else {
      throw sentence_error("cannot read '" + part + "': " + clause_forms(e.kind));
    }
  }

  // "It leaves a lander of Q at NAME": the one rendezvous with NAME stated before.
  void lander(double kg, const std::string& name) {
    if (!(kg > 0)) throw sentence_error("the lander's mass must be positive");
    Event* found = nullptr;
    int rendezvous = 0, others = 0;
    for (auto& e : events) {
      if (lowercase(e.body) != lowercase(name)) continue;
      if (e.kind == "rendezvous") {
        ++rendezvous;
        found = &e;
      } else {
        ++others;
      }
    }
    if (rendezvous == 0)
      throw sentence_error(others ? "only a rendezvous can leave a lander, and the spacecraft only passes " + name
                                  : "no rendezvous with " + name + " is stated before this sentence");
    if (rendezvous > 1)
      throw sentence_error("the spacecraft rendezvouses with " + name + " " + std::to_string(rendezvous) +
                           " times: put ', and leaves a lander of Q' in the rendezvous sentence meant");
    if (found->drop) throw sentence_error("the lander at " + name + " is given twice");
    found->drop = kg;
    found->drop_where = here;
  }

  // ---- central body and spacecraft -----------------------------------------------------------

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
          set_mu(quantity(m, 1, Dimension::GravParam));
        } else if (std::regex_match(part, m, radius_re)) {
          central_body["radius_km"] = quantity(m, 1, Dimension::Length);
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
            throw sentence_error(
                "cannot read '" + part +
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

  void spacecraft_clauses(const std::string& list) {
    static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
    static const std::regex clause =
        re(R"((?:an? )?(maximum thrust|specific impulse|initial mass|final mass) of )" + kQuantity);
    static const std::map<std::string, std::pair<std::string, Dimension>> fields = {
        {"maximum thrust", {"thrust_N", Dimension::Force}},
        {"specific impulse", {"isp_s", Dimension::Duration}},
        {"initial mass", {"initial_mass_kg", Dimension::Mass}},
        {"final mass", {"final_mass_kg", Dimension::Mass}}};
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
      const std::string key = lowercase(m[1].str());
      const auto& [field, dim] = fields.at(key);
      once("the " + key);
      ++seen["the spacecraft's engine"];
      const double value = quantity(m, 2, dim);
      if (value <= 0) throw sentence_error("the " + key + " must be positive, got " + m[2].str() + " " + m[3].str());
      spacecraft[field] = value;
    }
  }

  // ---- after the whole text ------------------------------------------------------------------

  // A target's {"ref": NAME} as the body given by its orbit, else a planet with an ephemeris.
  json resolve(const json& target, const Where& w) {
    if (!target.contains("ref")) return target;
    const std::string name = target["ref"];
    for (auto& o : orbits)
      if (lowercase(o.name) == lowercase(name)) {
        o.used = true;
        return {{"kind", "orbit"}, {"body", o.name}, {"elements", o.elements}};
      }
    if (is_planet(lowercase(name))) {
      std::string body = lowercase(name);
      body[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(body[0])));
      return {{"kind", "body"}, {"body", body}, {"ephemeris", "jpl_lp"}};
    }
    fail(w, "unknown body '" + name + "': state its orbit ('" + name +
                " moves on a Keplerian orbit about the Sun with a = Q, e = N, i = Q, node = Q, argument of "
                "perihelion = Q and mean anomaly = Q at MJD N') or name a planet with an ephemeris (Earth, Mars, "
                "Venus, Jupiter)");
  }

  // Checks that need the whole text: names, epochs, windows, landers.
  void finish_events() {
    const std::string central = central_body.value("name", "");
    for (const auto& o : orbits) {
      static const std::regex the = re(R"((?:the )?(.+))");
      std::smatch m;
      std::regex_match(o.about, m, the);
      const std::string about = lowercase(m[1].str());
      if (!o.about.empty() && about != "central body" && about != lowercase(central))
        fail(o.where, "the orbit is about " + m[1].str() + " but the central body is " + central);
    }
    const bool has_epoch = time.contains("epoch_mjd2000");
    const auto needs_epoch = [&](const json& target, const Where& w) {
      if (has_epoch || (target["kind"] != "body" && target["kind"] != "orbit")) return;
      fail(w, target["body"].get<std::string>() +
                  " moves with time, so the text needs a calendar epoch: depart 'at MJD2000 N' (or 'at MJD N') or "
                  "state 'The departure epoch is free between Q before and Q after MJD2000 N'");
    };
    departure->target = resolve(departure->target, departure->where);
    needs_epoch(departure->target, departure->where);
    for (auto& e : events) {
      e.target = resolve(json{{"ref", e.body}}, e.where);
      needs_epoch(e.target, e.where);
    }
    arrival->target = resolve(arrival->target, arrival->where);
    needs_epoch(arrival->target, arrival->where);
    for (const auto& o : orbits)
      if (!o.used)
        fail(o.where, "no sentence sends the spacecraft to " + o.name + ": remove its orbit or state the event");

    const bool free_dep = time.value("departure", "") == "free";
    if (free_dep && departure_at_t)
      fail(departure->where,
           "with a free departure epoch the departure reads 'from TARGET' or 'at MJD2000 N', "
           "not 't = Q'");
    if (free_dep && time["final_time"] == "free")
      fail(free_departure_where,
           "a free departure epoch needs a fixed total time of flight ('The total time of "
           "flight is Q.')");

    // Windows in days after the epoch, inside the flight, in order and apart.
    const double epoch = has_epoch ? time["epoch_mjd2000"].get<double>() : 0.0;
    const double start = free_dep ? time["t0_window_days"][0].get<double>() : 0.0;
    const double tof =
        time["final_time"] == "fixed" ? time["tof_days"].get<double>() : time["tof_max_days"].get<double>();
    const double end = (free_dep ? time["t0_window_days"][1].get<double>() : 0.0) + tof;
    const Event* previous = nullptr;
    for (auto& e : events) {
      e.window_lo = e.lo.absolute ? e.lo.value - epoch : e.lo.value;
      e.window_hi = e.hi.absolute ? e.hi.value - epoch : e.hi.value;
      const std::string window = "day " + num_text(e.window_lo) + " to day " + num_text(e.window_hi);
      if (!(e.window_hi > e.window_lo)) fail(e.where, "its window, " + window + ", is empty");
      if (!(e.window_lo > start && e.window_hi < end))
        fail(e.where, "its window, " + window + ", must lie inside the flight: after day " + num_text(start) +
                          " and before day " + num_text(end) + " (days count from the epoch)");
      if (previous && e.window_lo < previous->window_hi)
        fail(e.where, "its window, " + window + ", starts before the window of the event at " + previous->body +
                          " (day " + num_text(previous->window_lo) + " to day " + num_text(previous->window_hi) +
                          ") ends: state the events in the order they happen, with windows that do not overlap");
      if (previous && previous->stay && !(e.window_hi > previous->window_lo + *previous->stay))
        fail(e.where, "its window, " + window + ", ends before the stay at " + previous->body + " can end (day " +
                          num_text(previous->window_lo + *previous->stay) +
                          " at the earliest): widen or move the windows");
      previous = &e;
    }
    if (previous && previous->stay && !(end > previous->window_lo + *previous->stay))
      fail(previous->where,
           "the stay at " + previous->body + " cannot end before the final time (day " + num_text(end) + ")");
    double dropped = 0;
    for (const auto& e : events) {
      if (!e.drop) continue;
      if (propulsion == "solar_sail") fail(e.drop_where, "a solar sail has no mass to leave behind");
      dropped += *e.drop;
      if (spacecraft.contains("initial_mass_kg") && !(dropped < spacecraft["initial_mass_kg"].get<double>()))
        fail(e.drop_where, "the landers weigh " + num_text(dropped) + " kg, not less than the initial mass");
    }
  }

  json constraints() {
    json out = json::array();
    out.push_back({{"id", "departure"}, {"kind", "initial_state"}, {"at", "t0"}, {"target", departure->target}});
    std::map<std::string, int> visits;
    std::vector<std::string> ids;
    for (const auto& e : events) {
      const std::string base = lowercase(e.body);
      int& n = visits[base];
      std::string id = ++n == 1 ? base : base + "_" + std::to_string(n);
      while (std::find(ids.begin(), ids.end(), id) != ids.end()) id = base + "_" + std::to_string(++n);
      ids.push_back(id);
      json c = {{"id", id},
                {"kind", e.kind},
                {"at", "interior"},
                {"target", e.target},
                {"window_days", json::array({e.window_lo, e.window_hi})}};
      if (e.stay) c["stay_days"] = *e.stay;
      if (e.drop) c["mass_drop_kg"] = *e.drop;
      if (e.mu) c["body_mu_km3_s2"] = *e.mu;
      if (e.rmin) c["min_periapsis_radius_km"] = *e.rmin;
      if (e.max_speed) c["max_relative_speed_km_s"] = *e.max_speed;
      out.push_back(c);
    }
    json last = {{"id", "arrival"}, {"kind", arrival->kind}, {"at", "tf"}, {"target", arrival->target}};
    if (arrival->max_speed) last["max_relative_speed_km_s"] = *arrival->max_speed;
    out.push_back(last);
    return out;
  }
};

}  // namespace

json parse_problem_text(const std::string& text, const std::string& source) {
  detail::check_text(text, source);
  Builder b(source);
  for (const auto& item : detail::split_sentences(text)) {
    if (item.text.size() > kMaxSentenceChars)
      throw input_error(source + ":" + std::to_string(item.line) + ": the sentence is longer than " +
                        std::to_string(kMaxSentenceChars) + " characters, the limit of a line or sentence");
    b.read(item);
  }
  if (b.table_intro) b.fail(*b.table_intro, "no table follows it (its header reads " + std::string(kTableHeader) + ")");
  const auto missing = [&](const std::string& what, const std::string& example) {
    throw input_error(source + ": the problem text never states " + what + " (add a sentence such as \"" + example +
                      "\")");
  };
  b.finish_facts();
  if (b.problem.is_null()) missing("its name", "Problem S01: Earth to Mars.");
  if (b.central_body.is_null()) missing("the central body", "The central body is the Sun.");
  if (b.propulsion == "low_thrust") {
    // Minimizing the initial mass needs the final mass instead of the initial one.
    const bool find_m0 = b.objective.is_object() && b.objective.value("kind", "") == "minimum_initial_mass";
    for (const auto& [field, example] :
         std::vector<std::pair<std::string, std::string>>{{"thrust_N", "The spacecraft has a maximum thrust of 0.5 N."},
                                                          {"isp_s", "The spacecraft has a specific impulse of 2000 s."},
                                                          {find_m0 ? "final_mass_kg" : "initial_mass_kg",
                                                           find_m0 ? "The spacecraft has a final mass of 1500 kg."
                                                                   : "The spacecraft has an initial mass of 1000 kg."}})
      if (!b.spacecraft.contains(field)) missing("the spacecraft's " + field, example);
    const std::string extra = find_m0 ? "initial_mass_kg" : "final_mass_kg";
    if (b.spacecraft.contains(extra))
      throw input_error(source + ": the spacecraft's " + extra + " is stated, but the objective " +
                        (find_m0 ? "finds the initial mass from the final one" : "takes the initial mass") +
                        ": state only the " + (find_m0 ? "final" : "initial") + " mass");
  }
  if (b.propulsion == "solar_sail" && b.seen.count("the spacecraft's engine"))
    throw input_error(source + ": the spacecraft is a solar sail, so it has no thrust, specific impulse or mass");
  if (!b.seen.count("the departure")) missing("the departure", "The spacecraft departs at MJD2000 400 from Earth.");
  if (!b.time.contains("final_time")) missing("the time of flight", "The time of flight is 348.795 days.");
  for (const auto& p : b.perturbations)
    if (p["kind"] == "j2" && (!b.central_body.contains("j2") || !b.central_body.contains("radius_km")))
      throw input_error(source +
                        ": the J2 perturbation needs the central body's J2 coefficient and radius (\"The central "
                        "body is the Earth with J2 coefficient 1.08262668e-3 and equatorial radius 6378.137 km.\")");
  if (!b.seen.count("the final rendezvous"))
    missing("the final condition", "At the final time the spacecraft rendezvouses with Mars.");
  if (b.objective.is_null()) missing("the objective", "Minimize the fuel consumption.");
  b.finish_events();
  if (!b.time.contains("t0_days")) b.time["t0_days"] = 0.0;
  json doc = io::artifact_header("spec", "helios-parse", "builtin");
  b.problem["source_file"] = source;
  doc["problem"] = b.problem;
  doc["central_body"] = b.central_body;
  json spacecraft = json::object();  // in one order, however the text states the facts
  for (const char* k : {"thrust_N", "isp_s", "initial_mass_kg", "final_mass_kg"})
    if (b.spacecraft.contains(k)) spacecraft[k] = b.spacecraft[k];
  for (const auto& [k, v] : b.spacecraft.items())
    if (!spacecraft.contains(k)) spacecraft[k] = v;
  doc["spacecraft"] = spacecraft;
  doc["dynamics"] = {{"model", "two_body"}, {"coordinates", "cartesian"}, {"propulsion", b.propulsion}};
  if (!b.perturbations.empty()) doc["dynamics"]["perturbations"] = b.perturbations;
  doc["objective"] = b.objective;
  json time = json::object();
  for (const char* k : {"t0_days", "epoch_mjd2000", "departure", "t0_window_days", "final_time", "tof_days",
                        "tof_min_days", "tof_max_days"})
    if (b.time.contains(k)) time[k] = b.time[k];
  doc["time"] = time;
  doc["constraints"] = b.constraints();
  return doc;
}

void check_problem_text(const std::string& text, const std::string& source) {
  detail::check_text(text, source);
}

}  // namespace helios::spec

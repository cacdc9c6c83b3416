#pragma once
// The reader of the controlled English (internal to tools/lib/src/spec): the Builder that gathers a
// problem text's sentences into a spec, and the pieces its sentence forms share. Each concept's
// sentences are handled in their own file:
//   rules.cpp        the rule table: which sentence form a sentence is, and its handler
//   spacecraft.cpp   the central body, the spacecraft, the dynamics' perturbations, the objective
//   time.cpp         the time of flight, the departure, its epoch and window
//   events.cpp       the final condition, events on the way (rendezvous, flyby, gravity assist,
//                    stays, landers) and the constraints they become
//   orbit_target.cpp a final condition that is an orbit (its elements, the position on it free)
//   tables.cpp       bodies given by their orbital elements: orbit sentences and elements tables
//   apply_facts.cpp  facts stated in other words (facts.cpp), applied to the spec
//   grammar.cpp      numbers with units, vectors, names and clause lists
//   parse.cpp        reading the text item by item, and the spec assembled from it
#include <array>
#include <map>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "facts.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/spec/units.hpp"
#include "text.hpp"

namespace helios::spec::grammar {

using detail::Sentence;
using io::json;

// Thrown by the sentence handlers; turned into an input_error naming file, line and sentence.
struct sentence_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline const std::string kNum = R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)";
inline const std::string kUnit = R"([A-Za-z][A-Za-z0-9^/]*)";
inline const std::string kQuantity = "(" + kNum + R"()\s*()" + kUnit + ")";
inline const std::string kVector =
    R"(\[\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*,\s*()" + kNum + R"()\s*\]\s*()" + kUnit + ")";

// ---- shared pieces of the sentence forms (grammar.cpp) -----------------------------------------

double number(const std::string& s);
double quantity(const std::smatch& m, std::size_t idx, Dimension d);
json vector3(const std::smatch& m, std::size_t idx, Dimension d);
// The pattern matched whole and without case.
std::regex re(const std::string& pattern);
// Known gravitational parameters [km^3/s^2] for a central body named without one.
std::optional<double> known_mu(const std::string& body);
// Known equatorial radii [km].
std::optional<double> known_radius(const std::string& body);
// Splits "a, b, c" at the commas outside parentheses.
std::vector<std::string> top_level_items(const std::string& list);
std::string trimmed(const std::string& s);
// Factor converting `unit` into the spec unit of `d`, as a sentence error when unknown.
double unit_factor(Dimension d, const std::string& unit);
// Splits a clause list at ';', ',', ', and' and ' and '.
std::vector<std::string> clauses_of(const std::string& list);
bool is_planet(const std::string& key);
// A body's name as written: letters, digits and underscores, starting with a letter.
std::string body_name(const std::string& phrase);
// "MJD N" or "MJD2000 N" as MJD2000.
double mjd2000_of(const std::string& scale, const std::string& value);
// A state, a coasting target or a body's name as {"ref": NAME} (events.cpp).
json parse_target(const std::string& phrase);
// An orbit given by some of its elements, as a target of kind orbital_elements (orbit_target.cpp);
// "geostationary" is kept as a flag until the central body is known (Builder::geostationary).
json parse_orbit_target(const std::string& phrase);
// Orbital elements {a [AU], e, i, raan, argp [deg], mean or true [deg]} as the spec's (tables.cpp).
json elements_json(double epoch_mjd2000, const std::map<std::string, double>& v);

// Where an item of the text stands, for errors found after the whole text was read.
struct Where {
  int line = 0;
  std::string text;
  bool table_row = false;
};

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
  std::string kind, body;  // an orbit on the way (kind orbit_insertion) has no body, its target is the orbit
  EpochRef lo, hi;
  std::optional<double> stay, drop, mu, rmin, max_speed;
  Where drop_where;
  json target;
  double window_lo = 0, window_hi = 0;
  std::string place() const { return body.empty() ? "the orbit on the way" : body; }
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

inline constexpr const char* kTableHeader =
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
  std::optional<Where> windowless_rendezvous;  // "The spacecraft rendezvouses with Mars.", read as the final one
  // "arrives at t = Q" [days] or "arrives on DATE" [MJD2000], made a time of flight at the end
  struct ArrivalTime {
    double value;
    bool date;
    Where where;
  };
  std::optional<ArrivalTime> arrival_time;
  std::string propulsion = "low_thrust";
  std::map<std::string, int> seen;     // what each sentence set, to refuse contradictions
  std::optional<json> r0, v0, rf, vf;  // state vectors stated one by one
  Where initial_where, final_where;
  bool mu_stated = false;
  std::optional<double> pending_mu;  // a gravitational parameter stated before the central body
  std::optional<std::pair<std::string, Where>> constants_body;  // the body whose mu, radius or J2 a sentence gave
  bool radius_stated = false;                                   // else the radius is the known one

  // A sentence of the controlled English: the first rule whose pattern matches it whole applies.
  struct SentenceRule {
    std::regex pattern;
    void (Builder::*apply)(const std::smatch&);
  };

  // ---- reading the text (parse.cpp) ----
  void once(const std::string& what);
  // A fact of the table (facts.hpp), keyed by its field; its value checked as the table says.
  void once(detail::Field f);
  void check_value(detail::Field f, double v, const std::string& written) const;
  [[noreturn]] void fail(const Where& w, const std::string& why) const;
  void read(const Sentence& item);
  void on_problem(const std::smatch& m);

  // ---- the rule table (rules.cpp) ----
  void handle(const std::string& s);

  // ---- central body, spacecraft, perturbations, objective (spacecraft.cpp) ----
  void on_central(const std::smatch& m);
  void central(const std::string& name, const std::string& list);
  void set_mu(double mu);
  void on_has(const std::smatch& m);
  void spacecraft_clauses(const std::string& list);
  void on_sail(const std::smatch& m);
  void sail(double ac_mm_s2, double ref_au);
  void on_j2(const std::smatch&);
  void on_accel(const std::smatch& m);
  static json user_acceleration(const std::string& name, const std::string& list, const std::string& unit);
  // ---- a third body perturbing the spacecraft (third_body.cpp) ----
  void on_third_body(const std::smatch& m);
  void on_initial_mass(const std::smatch&);
  void on_fuel(const std::smatch&);
  void on_time(const std::smatch&);
  void on_final_state_objective(const std::smatch& m);
  void on_full_throttle(const std::smatch&);

  // ---- time of flight, departure and epochs (time.cpp) ----
  void on_tof(const std::smatch& m);
  void on_free_tof(const std::smatch& m);
  void on_depart_from(const std::smatch& m);
  void on_depart(const std::smatch& m);
  void depart(const std::string& at, const std::string& target);
  void depart_from_orbit(const std::string& at, const std::string& orbit);
  void on_depart_orbit(const std::smatch& m);
  void set_epoch(double mjd2000);
  void epoch(const std::string& phrase);
  void on_free_dep(const std::smatch& m);
  void on_free_dep_within(const std::smatch& m);
  void free_departure(double lo, double hi, double mjd2000);

  // ---- the final condition, events on the way, constraints (events.cpp) ----
  void on_arrive(const std::smatch& m);
  void on_arrive_flyby(const std::smatch& m);
  // ---- a final condition that is an orbit (orbit_target.cpp) ----
  void on_arrive_orbit(const std::smatch& m);
  void on_orbit_on_the_way(const std::smatch& m);
  void on_final_conditions(const std::smatch& m);
  json geostationary(json target, const Where& w) const;
  void on_event(const std::smatch& m);
  static EpochRef epoch_ref(const std::string& scale, const std::string& value);
  void event(const std::string& kind, const std::string& rest);
  static std::string clause_forms(const std::string& kind);
  static void same_body(const Event& e, const std::string& phrase);
  void event_clause(Event& e, const std::string& part);
  void add_event(Event e);
  Event& rendezvous_of(const std::string& name);
  void on_drop(const std::smatch& m);
  void lander(double kg, const std::string& name);
  json resolve(const json& target, const Where& w);
  void finish_events();
  json constraints();
  void check_event_ids(const std::vector<std::string>& ids) const;

  // ---- bodies given by their orbits, elements tables (tables.cpp) ----
  void on_orbit(const std::smatch& m);
  void orbit_sentence(const std::smatch& m);
  void define_orbit(const std::string& written, const std::string& about, json elements);
  static std::string element_label(const std::string& field);
  static double element_unit(const std::string& field, const std::string& unit);
  void on_intro(const std::smatch& m);
  static std::vector<std::string> cells_of(const std::string& row);
  static bool is_table_header(const std::string& row);
  void table_line(const std::string& row);
  TableColumns table_header(const std::vector<std::string>& cells);

  // ---- facts stated in other words (apply_facts.cpp) ----
  std::map<std::string, std::string> body_names() const;
  detail::SentenceFacts facts_of(const std::string& s) const;
  void apply_facts(const detail::SentenceFacts& f);
  void apply_fact(const detail::Fact& fact);
  void apply_orbit(const detail::SentenceFacts& f);
  void set_engine(detail::Field field, double v);
  void set_state(std::optional<json>& slot, detail::Field field, bool initial, const json& v);
  void set_central_value(const char* key, double v, bool stated);
  void apply_event(const detail::SentenceFacts& f);
  void finish_facts();
};

}  // namespace helios::spec::grammar

#pragma once
// The reader of the controlled English (internal to tools/lib/src/spec): the Builder that gathers a
// problem text's sentences into a spec, and the pieces its sentence forms share. Each sentence form
// is a file of forms/ (form.hpp); what several forms and the facts in other words share is here:
//   form_registry.cpp the forms in their order, the one that reads a sentence, their examples' problems
//   spacecraft.cpp   the central body and its constants, the propulsion
//   time.cpp         the departure's epoch and window
//   events.cpp       targets, events on the way, the checks of the whole text and the constraints
//   orbit_target.cpp an orbit given by some of its elements (a departure, a final or interior target)
//   tables.cpp       bodies given by their orbital elements, elements tables
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
// An orbit phrase with no window, one capture group ("a circular orbit of radius 7000 km"): an
// orbit on the way has a window ("between day N and day N", orbit_on_the_way.cpp).
inline const std::string kOrbitPhrase = R"(((?!.*\bbetween (?:day|MJD))(?:.+ )?orbit\b.*?))";
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
// Known equatorial radii [km], which a central body named without one takes.
std::optional<double> known_radius(const std::string& body);
// The radius below which nothing can fly [km]: the known equatorial radius, and the Sun's.
std::optional<double> surface_radius(const std::string& body);
// The sentence with the numbers written in words before a unit as digits: "six weeks" is "6 weeks",
// "three hundred days" "300 days" (grammar.cpp).
std::string with_digits(const std::string& sentence);
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
// "geostationary", "altitude_km" and "about" (the body named) are kept until the central body is
// known (Builder::resolve_orbit).
json parse_orbit_target(const std::string& phrase);
// Orbital elements {a [AU], e, i, raan, argp [deg], mean or true [deg]} as the spec's (tables.cpp).
json elements_json(double epoch_mjd2000, const std::map<std::string, double>& v);
// Which element a name in an orbit sentence or a table header stands for: a, e, i, raan, argp, mean
// or true (the anomaly), or "" if none (tables.cpp).
std::string element_field(const std::string& name);

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

// What a table holds: bodies by their orbital elements (tables.cpp), or a thruster's thrust and mass
// flow at its input powers (forms/thruster_table.cpp). A table's introducing sentence chooses it; a
// table without one is an elements table.
enum class TableKind { Elements, Thruster };

// Columns of a table, in the order written: what each holds (of an elements table "body", "a", "e",
// "i", "raan", "argp", "mean" or "true", "epoch"; of a thruster's "power", "thrust", "flow"), its
// factor to the spec's unit (a in AU, angles in deg; SI for a thruster's) and its unit as written;
// the epoch's scale (MJD or MJD2000).
struct TableColumns {
  TableKind kind = TableKind::Elements;
  std::vector<std::string> fields;
  std::vector<double> factors;
  std::vector<std::string> units;
  std::string epoch_scale;
};

inline constexpr const char* kTableHeader =
    "| body | a [AU] | e | i [deg] | node [deg] | argument of perihelion [deg] | mean anomaly [deg] | epoch [MJD] |";
inline constexpr const char* kThrusterTableHeader = "| input power [kW] | thrust [mN] | mass flow [mg/s] |";

// A table header's cell as its name and unit: "a [AU]", "i (deg)", "e" (tables.cpp).
std::pair<std::string, std::string> name_and_unit(const std::string& cell);

struct Builder {
  explicit Builder(std::string src) : source(std::move(src)) {}

  std::string source;
  Where here;            // the item being read
  std::string sentence;  // the sentence being read, its numbers in words as digits
  json problem, central_body, spacecraft = json::object(), objective, time = json::object(),
                              perturbations = json::array();
  std::optional<Endpoint> departure, arrival;
  std::vector<Event> events;
  std::vector<OrbitDef> orbits;
  std::optional<TableColumns> table;  // a table's header was read and its rows may follow
  bool table_separator_allowed = false;
  std::optional<Where> table_intro;            // a sentence announcing a table, waiting for its header
  TableKind table_kind = TableKind::Elements;  // what the last sentence announcing a table announced
  std::string table_about;
  // The thruster's table (forms/thruster_table.cpp): where its sentence stands, its rows read so far
  // in SI, made spacecraft.thruster_table once its last row is read.
  Where thruster_table_where;
  json thruster_rows = json::array();
  Where free_departure_where;
  std::optional<std::pair<double, double>> window_dates;  // a departure window between two dates [MJD2000]
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
  // The central body named "scaled", "normalized", ...: its constants are the text's on purpose, none
  // is taken from the body's known ones or checked against them.
  bool central_on_purpose = false;
  std::map<std::string, Where> constant_where;  // where the central body's mu_km3_s2, radius_km, j2 were stated
  std::optional<Where> objective_where;
  std::optional<Where> tof_where;  // the sentence that gave the time of flight or its bounds
  json notes = json::array();      // what the parser derived rather than read (the spec's notes)
  // A radius a sentence states that must lie above the central body's surface (a third body's orbit).
  struct StatedRadius {
    double km;
    std::string what;
    Where where;
  };
  std::vector<StatedRadius> stated_radii;

  // ---- reading the text (parse.cpp) ----
  void once(const std::string& what);
  // A fact of the table (facts.hpp), keyed by its field; its value checked as the table says.
  void once(detail::Field f);
  void check_value(detail::Field f, double v, const std::string& written) const;
  [[noreturn]] void fail(const Where& w, const std::string& why) const;
  void read(const Sentence& item);

  // ---- a sentence: the form that reads it, else the facts in other words (form_registry.cpp) ----
  void handle(const std::string& s);

  // ---- what cannot be: a place inside the central body, a constant far from a body's known one,
  // an objective the other facts make constant (plausibility.cpp) ----
  void check_physics() const;
  void check_constants() const;
  void check_objective() const;

  // ---- the central body and its constants, the propulsion (spacecraft.cpp) ----
  // The central body, and its constants "gravitational parameter Q", "equatorial radius Q", "J2
  // coefficient N" in any order (also "mu = Q", "R = Q", "J2 = N").
  void central(const std::string& name, const std::string& list);
  void central_constant(const std::string& part);
  void set_mu(double mu);
  void sail(double ac_mm_s2, double ref_au);

  // ---- the time of flight, the departure's epoch and window (time.cpp) ----
  void fixed_time_of_flight(double days);
  // A free time of flight, with the bounds a sentence gives (each once); the others are filled in once
  // the whole text is read (finish_time).
  void bound_time_of_flight(std::optional<double> lo, std::optional<double> hi);
  // The free time of flight's bounds the text leaves open: 0, and for a minimum time an upper bound
  // from the physics, said in the spec's notes.
  void finish_time();
  std::optional<double> departure_period_days() const;
  void set_epoch(double mjd2000);
  void free_departure(double lo, double hi, double mjd2000);
  // A departure window between two dates [MJD2000], made the epoch's window once the text is read.
  void departure_window_dates(double lo, double hi);
  void finish_departure_window();

  // ---- targets, events on the way, the checks of the whole text, constraints (events.cpp) ----
  // "day N" (days after the epoch), "MJD N" or "MJD2000 N" (absolute).
  static EpochRef epoch_ref(const std::string& scale, const std::string& value);
  // The clauses an event of `kind` takes, for its errors.
  static std::string clause_forms(const std::string& kind);
  // An event stated whole: a gravity assist takes the known mu of its body unless it states one.
  void add_event(Event e);
  Event& rendezvous_of(const std::string& name);
  json resolve(const json& target, const Where& w);
  void resolve_targets();
  void finish_events();
  json constraints();
  void check_event_ids(const std::vector<std::string>& ids) const;
  // An orbit target's elements once the central body is known (orbit_target.cpp).
  json resolve_orbit(json target, const Where& w) const;

  // ---- bodies given by their orbits, elements tables (tables.cpp) ----
  void define_orbit(const std::string& written, const std::string& about, json elements);
  static std::string element_label(const std::string& field);
  static double element_unit(const std::string& field, const std::string& unit);
  static std::vector<std::string> cells_of(const std::string& row);
  static bool is_table_header(const std::string& row);
  // The item after a sentence announcing a table may be its header: any table line for a thruster's
  // table (its header is read as one), an elements header for an elements table.
  bool may_be_header(const Sentence& item) const;
  // The header a table of the kind announced reads, for errors.
  const char* header_example() const;
  void table_line(const std::string& row);
  TableColumns table_header(const std::vector<std::string>& cells);
  // The table being read ends (a sentence follows it, another header, or the end of the text): a
  // thruster's table is then checked whole and stored.
  void end_table();

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

// ---- a thruster's table (forms/thruster_table.cpp) ----
// The columns of its header: the input power, the thrust and the mass flow, each once with its unit.
TableColumns thruster_table_header(const std::vector<std::string>& cells);
// A row, checked and added to b.thruster_rows in SI.
void thruster_table_row(Builder& b, const TableColumns& columns, const std::vector<std::string>& cells);
// The table once its last row is read: enough rows, stored as spacecraft.thruster_table.
void finish_thruster_table(Builder& b);

}  // namespace helios::spec::grammar

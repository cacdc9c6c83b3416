#pragma once
// What the verifier's check families read (internal to tools/lib/src/verify): the derivation's
// problem statement read once into a Context (symbols and their kinds, dynamics, costs,
// constraints, events, the shooting system as written), H and its control gradients recomputed
// from that statement, and the sample points. Built once by its constructor, then read-only: the
// families take it by const reference.
#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "helios/derivation/document.hpp"
#include "helios/derivation/names.hpp"
#include "helios/io/json_io.hpp"
#include "helios/symbolic/evaluate.hpp"
#include "helios/symbolic/expr.hpp"
#include "helios/verify/verify.hpp"

namespace helios::verify::detail {

namespace names = derivation::names;

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;
using io::json;
using symbolic::Compiled;
using symbolic::Point;

constexpr int kThrottleGrid = 40;  // intervals of the grid of u in [0, 1]

// What a symbol stands for; it decides how the sample points draw its value.
enum class Kind {
  Position,
  Velocity,
  Mass,
  OtherState,
  Costate,
  Multiplier,
  Homotopy,
  Throttle,
  Direction,
  Sail,
  Parameter,
  Sourced,  // a parameter the runtime evaluates (ephemeris, rate, coast): its value may be a placeholder
  EventValue,
  Free
};

// An endpoint constraint psi = 0 at t0 or tf.
struct Constraint {
  std::string id, at;
  std::vector<ex> psi;                   // in the state symbols
  std::vector<std::string> multipliers;  // nu of each row, as written (may be empty)
  // Every multiplier a shooting variable: psi is not solved for the states it involves (an
  // orbit), so each of their transversality rows lambda(tf) = lambda0 dphi/dx + nu^T dpsi/dx is
  // an equation of its own.
  bool multipliers_unknown = false;
  // Shooting variables inside psi at t0 (a departure orbit's anomaly): found by stationarity.
  std::vector<std::string> free_params;
};

// A shooting equation as written, with its values at the sample points.
struct Equation {
  std::string name, text, error;
  bool ok = false;
  ex e;
  Compiled c;
  std::vector<double> values;     // at the sample points
  std::set<std::string> symbols;  // its free symbols
};

// A value the runtime evaluates at an event (event_values), such as H_tf.
struct EventValue {
  std::string name, meaning;
  bool hamiltonian = false;  // H under the optimal control at `at`
  std::string at = "tf";     // t0, tf, or <event>_m / <event>_p (just before / after an interior event)
};

// One costate of an interior event's costate_map: a shooting variable or an expression.
struct CostateEntry {
  bool given = false, is_variable = false;
  std::string variable, text;
  ex expr;
};

// An interior event (events[]) as written; `error` says why it could not be read.
struct Event {
  std::string id, kind, error;
  std::vector<ex> psi;
  std::vector<std::string> psi_text, multiplier_text;
  std::vector<ex> map;  // state_map, in state order
  std::vector<std::string> map_text;
  std::vector<CostateEntry> costate_map;  // in state order
  std::vector<std::string> free_params;   // symbols psi or state_map introduce (Category C parameters)
  std::vector<std::string> time_vars;     // symbols time.expression introduces (the epoch's fraction)
  std::string time_text;
  ex time_expr;
  std::vector<double> window;
  std::string Hm, Hp;  // event values: H just before / just after
};

using symbolic::is_identifier;

// A uniform draw in [a, b) and a uniformly distributed unit vector of R^n.
double uniform(std::mt19937_64& rng, double a, double b);
std::vector<double> random_unit(std::mt19937_64& rng, std::size_t n);

class Context {
 public:
  // Reads the problem statement, recomputes H and draws the sample points. Throws
  // std::invalid_argument / input_error naming the field when the statement is unusable.
  Context(const json& derivation, const VerifyOptions& options);

  const derivation::Document doc;  // the derivation as read (units left as text)
  const VerifyOptions options;

  // ----- symbols
  symbolic::SymbolTable symbols;
  std::map<std::string, int> slots;  // symbol name -> its index in a Point
  std::vector<Kind> kinds;           // by slot
  std::vector<double> values;        // by slot: the value of a parameter

  // ----- names
  std::vector<std::string> states, costates, directions, sails, parameters;
  std::string throttle, multiplier, eps;
  std::vector<std::size_t> positions;          // indices of the position states (r-hat of the sail)
  std::map<std::string, std::string> sources;  // parameter -> source ("ephemeris:Mars:tf", ...)
  std::vector<EventValue> event_values;

  // ----- times. Free final time: tf = tf_expression(shooting variables); a sliding departure:
  // t0 = t0_expression(t0_frac), tf = tf_expression = t0 + the fixed total time.
  bool free_tf = false;
  std::string tf_text, tf_error;
  ex tf_expr;
  std::vector<std::string> tf_vars;  // symbols of tf_expression declared by it (e.g. tf_frac)
  bool free_t0 = false;
  std::string t0_error;
  ex t0_expr, t0_tf_expr;
  std::vector<std::string> t0_vars;

  // ----- the problem statement
  std::vector<ex> state_rhs;
  ex running_cost, endpoint_cost;  // the endpoint cost in the state symbols
  std::vector<Constraint> constraints;
  // States some constraint at t0 / tf involves (at tf: one whose multipliers are eliminated).
  std::set<std::string> fixed_at_t0, fixed_at_tf;
  std::vector<Event> interior_events;
  // Uncontrolled dynamics of coasting targets.
  bool has_coast = false;
  std::vector<std::string> coast_states;
  std::vector<ex> coast_rhs;
  std::string coast_error;
  GiNaC::exmap sail_definitions;  // control_law.sail.definitions, each with the earlier ones inlined
  std::string sail_definitions_error;

  // ----- recomputed from the statement
  ex hamiltonian;
  Compiled hamiltonian_compiled;
  std::vector<ex> dH_da;  // dH/da_j of the direction controls
  std::vector<Compiled> dH_da_compiled;
  std::vector<ex> dH_dn;  // dH/dn of the sail normal
  std::vector<Compiled> dH_dn_compiled;
  std::vector<ex> direction_law;  // a* = -g/|g| at full thrust, for the exact throttle checks

  // ----- sample points and the shooting system as written
  std::vector<Point> points;
  std::vector<std::string> variables;
  std::vector<Equation> equations;

  int slot(const std::string& name) const { return slots.at(name); }
  ex sym(const std::string& name) const { return symbols.symtab().at(name); }
  Compiled compile(const ex& e) const { return Compiled(e, slots); }
  // The expression `text` of the field `where`, over the verifier's symbols.
  ex statement(const std::string& text, const std::string& where) const;

  Point set_direction(Point p, const std::vector<double>& a) const;
  std::vector<double> direction_of(const Point& p) const;
  Point with_direction(const Point& p, double u) const;
  Point optimal_controls(const Point& p, bool with_throttle) const;
  Point at_tf(const Point& p) const;
  Point at_label(const Point& p, const std::string& label) const;

 private:
  int declare(const std::string& name, Kind kind, double value = 0);
  void declare_new(const std::string& name, Kind kind);
  std::vector<std::string> declare_unknown(const std::string& text);
  void read_names();
  void read_times_and_events();
  void read_departure(const derivation::Times& times);
  void declare_constraint_multipliers();
  void read_interior_events();
  void declare_event_symbols(Event& e);
  void read_event_maps(const derivation::Event& written, Event& e, const std::string& where);
  void read_statement();
  void read_coast();
  void read_sail_definitions();
  void recompute_hamiltonian();
  void sample_points(std::mt19937_64& rng);
  void read_shooting();
};

}  // namespace helios::verify::detail

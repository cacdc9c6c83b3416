#pragma once
// The derivation artifact as one typed document: what derivation::Reader reads (names, units,
// symbols) and every section after them (times, dynamics, Hamiltonian, state and costate
// equations, control law, constraints, interior events, event values, coasting target, shooting
// system), read once and strictly from the JSON of schemas/derivation.schema.json. The verifier and
// the code generator read this document, not the JSON: a field missing or of the wrong type is an
// error "<file>: field <pointer> ..." here, which the llm backend returns to the model as feedback.
//
// Expressions stay text with the JSON pointer where they stand; parse() turns one into GiNaC over
// the document's symbols. The verifier parses a claim itself, over its own larger table, because
// a claim it cannot parse is a failed check there, not an unreadable document.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <vector>

#include "helios/derivation/reader.hpp"
#include "helios/derivation/sections.hpp"
#include "helios/derivation/terms.hpp"
#include "helios/io/json_io.hpp"
#include "helios/symbolic/chain_rule.hpp"

namespace helios::derivation {

// times: the initial time, the final one (fixed or an expression of a shooting variable), and a
// sliding departure's t0 as an expression of one.
struct Times {
  double t0 = 0;
  std::optional<double> tf, epoch_mjd2000;
  std::string final_time, departure = "fixed";  // "fixed" or "free"
  std::optional<Expression> tf_expression, t0_expression;
  std::vector<double> tf_window, t0_window;  // empty when absent
};

// dynamics: f by state (in state order), the running cost L and the endpoint cost.
struct Dynamics {
  std::vector<Expression> state_rhs;
  Expression running_cost, endpoint_cost;
};

// One entry of state_odes / costate_odes: the state or costate it is for, and its right-hand side.
struct Ode {
  std::string name;
  Expression rhs;
};

// coast_dynamics: a coasting target's states and their uncontrolled dynamics.
struct CoastDynamics {
  std::vector<std::string> states;
  std::vector<Expression> rhs;
};

// A body on a Keplerian orbit about the central body (bodies[]): normalized a and epoch, angles in rad.
struct Body {
  std::string name;
  double epoch = 0, a = 0, e = 0, i_rad = 0, raan_rad = 0, argp_rad = 0, mean_anomaly_rad = 0;
};

class Document : public Reader {
 public:
  // Reads `derivation` strictly; `file` names it in the errors. parse_units as for Reader.
  explicit Document(const io::json& derivation, const std::string& file = "derivation", bool parse_units = true);

  std::string file;
  std::string problem_id, objective;
  io::json producer;  // as written: the verifier echoes it
  double homotopy_start = 1;
  std::vector<Body> bodies;
  Times times;
  std::vector<Intermediate> intermediate_list;  // each in t, the states, the parameters and the earlier ones
  Dynamics dynamics;
  Expression hamiltonian;
  std::vector<Ode> state_odes, costate_odes;
  std::vector<InitialValue> initial_values;  // a state's value at t0, where a constraint fixes it
  ControlLaw control_law;
  std::vector<Constraint> constraints;
  std::vector<Event> interior_events;
  std::vector<EventValue> event_value_list;
  std::optional<CoastDynamics> coast_dynamics;
  Shooting shooting;
  std::optional<std::vector<Term>> terms;  // the listed terms of f and L; none when not listed

  // `e` over the document's symbols; throws input_error "<file>: field <pointer>: cannot parse ...".
  GiNaC::ex parse(const Expression& e) const;
  // The intermediates parsed, for differentiating through them or substituting them.
  symbolic::ChainRule chain_rule() const;

 private:
  void read_sections();
  void check_intermediates() const;
};

}  // namespace helios::derivation

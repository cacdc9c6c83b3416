#pragma once
// The catalogue of terms: every force and cost the derivation can list, each described once, by
// the file of tools/lib/src/pmp/terms that derives it (its function of the file's name returns its
// entries; the build lists those files). Everything else reads the entries: the problem model
// builds the forces a spec asks for from them, the derivation's reader and the verifier know the
// names and the parameters' roles from them, and the schemas' term and perturbation definitions
// and the derivation prompt's list of terms are written from them (tests/unit/catalogue_test.cpp
// checks the schemas; `make catalogue` rewrites them). A new force is its term file here, its
// recomputation in tools/lib/src/verify/terms/ and, if a sentence states it, its form in
// tools/lib/src/spec/forms/.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::pmp {

struct Problem;
namespace terms {
class ForceTerm;
}

// A parameter a term lists, in its order: its role (what the runtime and the verifier ask for, e.g.
// "thrust_scale"; empty for a coefficient only the term reads), what it is, its dimension, and how
// the report typesets it where its name alone would print upright (Tmax: T with subscript \max).
struct TermParameter {
  TermParameter(std::string n, std::string m, std::string d, std::string r = "")
      : name(std::move(n)), meaning(std::move(m)), dimension(std::move(d)), role(std::move(r)) {}
  // This parameter printed as `base` with the subscript `subscript` (LaTeX; "" for none).
  TermParameter typeset(std::string base, std::string subscript) const {
    TermParameter out = *this;
    out.symbol_base = std::move(base);
    out.symbol_subscript = std::move(subscript);
    return out;
  }
  std::string name, meaning, dimension;
  std::string role;
  std::string symbol_base, symbol_subscript;  // empty: the typesetter's own rules
};

// What a builder sees: the problem so far (units, mass unit, objective), the spec, and the
// spec's perturbation entry the term is built from (nullptr for a term not built from one).
struct TermSource {
  const Problem& problem;
  const io::json& spec;
  const io::json* perturbation;
  std::string mass_unit;
};

struct TermEntry {
  std::string name;
  std::string kind;     // force | cost
  std::string summary;  // what it adds, in words and formulas (the derivation prompt's line)
  // The parameters it lists, in order: the first `required` always, the rest all or none.
  std::vector<TermParameter> parameters;
  std::size_t required = 0;
  // The listing fields beyond name, kind and parameters it must carry ("body"; "label", "acceleration").
  std::vector<std::string> details;
  // Properties the rest of the tool chain asks of a force.
  bool field = false;              // it belongs to the natural field a coasting target also moves in
  bool axially_symmetric = false;  // unchanged by a turn about the central body's z axis
  bool engine = false;             // the spacecraft's propulsion: exactly one engine term per problem
  bool varying_flow = false;       // an engine whose full-throttle mass flow follows the state (T(r))
  // A force built from the spec's perturbations: their "kind" and the JSON schema of one entry (its
  // "then" branch in spec.schema.json's definition "perturbation").
  std::string spec_kind;
  io::json spec_schema;
  // Where it is in the dynamics (forces are built and their symbols registered by increasing order)
  // and in the lists of names.
  int order = 0;
  // The force term the spec asks for (nullptr where it asks for none); a perturbation's term is
  // built once for each entry of its kind. Null for a name another entry of the file builds.
  std::unique_ptr<terms::ForceTerm> (*build)(const TermSource&) = nullptr;
};

// Every entry: the forces, then the costs, each by increasing order (equal orders by file name and
// within a file as listed).
const std::vector<TermEntry>& term_catalogue();

// The entry of `name`, or nullptr.
const TermEntry* find_term(const std::string& name);

// The entry built from the spec's perturbations of kind `spec_kind`, or nullptr.
const TermEntry* find_perturbation(const std::string& spec_kind);

// The first parameter named `name` that says how it is typeset, or nullptr.
const TermParameter* find_typeset_parameter(const std::string& name);

// The parameter counts a listing of the entry may have: {required, all} (one value when equal).
std::vector<std::size_t> parameter_counts(const TermEntry& entry);

// The spec schema's "perturbation" definition and the derivation schema's term-name enum, as the
// catalogue makes them.
io::json perturbation_schema();
io::json term_name_enum();

// The derivation prompt's list of terms: one line per entry, "name [p1, p2] (kind): summary".
std::string term_catalogue_text();

}  // namespace helios::pmp

#pragma once
// A family of conditions of the verifier (internal to tools/lib/src/verify), one file each in the
// manner of Orekit's control/indirect package: controls.cpp (H, the state and costate ODEs, the
// control laws), boundary.cpp (transversality, endpoints, times, coasting targets), events.cpp
// (interior events, a sliding departure), shape.cpp (the shooting system's shape, its
// normalization, the states' use). Each recomputes its conditions from the read-only Context and
// returns its checks; the base class holds what several families use.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "context.hpp"
#include "helios/symbolic/compare.hpp"

namespace helios::verify::detail {

using symbolic::exact_equal;
using symbolic::exact_proportional;
using symbolic::kExactBudget;
using symbolic::print;
using symbolic::term_diagnosis;
using symbolic::tidy;
using symbolic::tree_size;

class Family {
 public:
  explicit Family(const Context& ctx);
  virtual ~Family() = default;
  // Recomputes the family's conditions and returns their checks, in report order.
  virtual std::vector<Check> run() = 0;

 protected:
  const Context& ctx;
  std::vector<Check> checks;

  // A passing check; `points` is the number of sample points unless the method is structural.
  Check start(const std::string& id, const std::string& category, const std::string& method) const;
  // The equality of the derivation's expression `given_text` (the field `label`) with the
  // recomputed `expected` at every sample point, or exactly; `diagnose` adds a term by term
  // comparison to the feedback, `forbidden` names symbols the given one must not depend on.
  Check equality(const std::string& id, const std::string& category, const std::string& label,
                 const std::string& expected_name, const Expected& expected, const std::string& given_text,
                 bool diagnose, const std::vector<std::string>& forbidden = {}) const;

  // ----- the shooting equations as written

  // The inequality of the shooting equation `name` as written, or null.
  const derivation::Inequality* inequality_of(const std::string& name) const;
  // A bound psi_j <= 0 (the row `name`, multiplier nu): the solver makes it inactive (its equation
  // nu = 0) or active (psi_j = 0), so the inequality must name the row's own multiplier, and the
  // inactive equation must be that multiplier; the sense is psi_j <= 0 (nu >= 0 when active).
  void check_bound(const std::string& name, const derivation::Inequality& bound, const ex& nu);
  // The mismatch of `g` (compiled, or its values at the sample points) with k * `e` for the best
  // constant k != 0 (k from the point of largest |e|).
  double proportional_mismatch(const Compiled& e, const Compiled& g) const;
  double proportional_mismatch(const Compiled& e, const std::vector<double>& gv) const;
  // Looks for an equation equivalent to `expected` = 0 (up to a constant factor); fails c with
  // `missing` when there is none.
  void find_equation(Check& c, const ex& expected, const std::string& missing) const;
  // An equation of shooting.equations equivalent to `expected` = 0 (a constant multiple), the one
  // named `name` first; `resolve` rewrites an equation first (costates the map gives explicitly).
  const Equation* matching_equation(const std::string& name, const ex& expected, Check& c,
                                    const GiNaC::exmap& resolve) const;
  const Equation* named_equation(const std::string& name) const;

  // ----- moving epochs and multipliers

  // Time derivatives of the parameters evaluated at `label` (t0, tf, an interior event's id,
  // <id>_dep) that move with it: an ephemeris component has its ephemeris_rate partner (same body;
  // the parameter named <name>_rate, else the same position among that body's rates), a coasting
  // target's component the coast dynamics. What is missing is added to `problems`.
  std::map<std::string, ex> rates_at(const std::string& label, std::vector<std::string>& problems) const;
  // sum_j nu_j dpsi_j with nu solved from rows i of sum_j nu_j dpsi_j/dx_i = rhs(i), the rows taken
  // where the Jacobian of psi is best conditioned at a sample point.
  ex nu_dot(const std::vector<ex>& psi, const std::vector<ex>& dpsi, const std::function<ex(std::size_t)>& rhs) const;
  // d e/dt through an explicit epoch symbol and the parameters that move with it.
  ex time_derivative(const ex& e, const std::string& epoch, const std::map<std::string, ex>& rates) const;

  // Term-by-term comparison of two expressions linear in `basis` (multipliers, costates, event
  // values), by evaluation: the given one may be any constant multiple of the expected one.
  struct Linear {
    std::vector<std::string> missing, flipped, wrong, extra;
    bool rest_wrong = false;
    bool ok() const { return missing.empty() && flipped.empty() && wrong.empty() && extra.empty() && !rest_wrong; }
    bool has(const std::vector<std::string>& list, const std::string& name) const {
      return std::find(list.begin(), list.end(), name) != list.end();
    }
    std::string text() const {
      std::vector<std::string> parts;
      if (!missing.empty()) parts.push_back("it lacks the term(s) in " + join(missing, ", "));
      if (!flipped.empty()) parts.push_back("the term(s) in " + join(flipped, ", ") + " have the wrong sign");
      if (!wrong.empty()) parts.push_back("the coefficient(s) of " + join(wrong, ", ") + " are wrong");
      if (!extra.empty()) parts.push_back("it has unexpected term(s) in " + join(extra, ", "));
      if (rest_wrong) parts.push_back("its part free of those symbols is wrong");
      return join(parts, "; ");
    }
  };
  // `anchor`: the basis symbol whose ratio wins a tie for the scale; `fixed`: the scale is 1 (an
  // expression, not an equation).
  Linear linear_compare(const ex& expected, const ex& given, const std::vector<ex>& basis, const ex& anchor = ex(0),
                        bool fixed = false) const;

  // An expression for feedback, or "(a long expression)".
  static std::string short_print(const ex& e) { return tree_size(e, 400) > 400 ? "(a long expression)" : print(e); }
};

std::unique_ptr<Family> control_family(const Context& ctx);
std::unique_ptr<Family> boundary_family(const Context& ctx);
std::unique_ptr<Family> event_family(const Context& ctx);
std::unique_ptr<Family> shape_family(const Context& ctx);
// The constraints' psi against their targets, and the initial values against psi (targets.cpp).
std::unique_ptr<Family> target_family(const Context& ctx);
// The dynamics and running cost as the sums of their listed terms (terms.cpp).
std::unique_ptr<Family> terms_family(const Context& ctx);

}  // namespace helios::verify::detail

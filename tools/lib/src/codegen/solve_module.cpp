// The SOLVE module: the start's guess and the call of the runtime's search.
#include "context.hpp"

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios::codegen::detail {

std::string solve_module(Context& c) {
  const auto& vars = c.shooting.variables;
  const std::string& mult = c.multiplier;
  std::ostringstream o;
  o << "// ----- module SOLVE (generated) ----------------------------------------------------------\n"
    << "namespace helios_rt {\n\n"
    << "// Seeded random guess: the multiplier in (0, 1), the other variables in (-1, 1), the whole\n"
    << "// vector projected on the unit sphere of the normalization condition.\n"
    << "inline void initial_guess(std::mt19937_64& rng, double* x) {\n"
    << "  std::uniform_real_distribution<double> positive(0.0, 1.0), symmetric(-1.0, 1.0);\n"
    << "  double norm2 = 0;\n";
  // The sphere holds the variables of the normalization equation; the others (a final-time
  // fraction) are drawn in (0, 1) and left alone.
  const std::vector<std::string> in_sphere = c.sphere_variables();
  std::vector<std::size_t> sphere;
  for (std::size_t i = 0; i < vars.size(); ++i) {
    const std::string& name = vars[i].name;
    const bool normalized = index_of(in_sphere, name) >= 0;
    if (normalized) sphere.push_back(i);
    // In (0, 1): the cost multiplier and time fractions; in (-1, 1): costates, multipliers,
    // parameters; an initial state in its range.
    const std::string role = !vars[i].role.empty() ? vars[i].role : normalized ? "costate" : "time_fraction";
    const bool positive = name == mult || role == "time_fraction";
    if (role == "initial_state") {
      if (vars[i].range.size() != 2)
        throw std::invalid_argument("field /shooting/variables/" + std::to_string(i) + "/range: an initial state " +
                                    "needs its range [lo, hi]");
      const double lo = vars[i].range[0], hi = vars[i].range[1];
      o << "  x[" << i << "] = " << number(lo) << " + positive(rng) * " << number(hi - lo) << ";\n";
      continue;
    }
    o << "  x[" << i << "] = " << (positive ? "positive(rng)" : "symmetric(rng)") << " * " << number(vars[i].scale)
      << ";\n";
  }
  if (sphere.empty()) throw std::invalid_argument("field /shooting/equations: no normalization equation");
  std::string indices;
  for (const auto i : sphere) indices += (indices.empty() ? "" : ", ") + std::to_string(i);
  o << "  for (const int i : {" << indices << "}) norm2 += x[i] * x[i];\n"
    << "  for (const int i : {" << indices << "}) x[i] /= std::sqrt(norm2);\n"
    << "}\n\n"
    << "Result solve_problem(const Settings& settings) {\n"
    << "  // A minimum needs lambda0 > 0 (lambda0 = 0 would be an abnormal extremal).\n"
    << "  const auto admissible = [](const double* x) { return x[" << index_of(c.variables, mult) << "] > 0; };\n"
    << "  const auto solve = [&](const Settings& s) { return "
    << (!c.interior_events.empty() ? "events_homotopy_solve(s, kLegPlan, kEventPlan, initial_guess, admissible)"
                                   : "homotopy_solve(s, initial_guess, admissible)")
    << "; };\n";
  // Bounds psi <= 0, in the order of their rows (bound_row's index).
  std::string bounds;
  for (const auto& e : c.shooting.equations) {
    if (!e.inequality) continue;
    const std::string& nu = e.inequality->multiplier;
    const int k = index_of(c.variables, nu);
    if (k < 0) throw std::invalid_argument("field /shooting/equations: bound multiplier " + nu + " is not a variable");
    bounds += "      {" + cpp_string(e.name) + ", " + cpp_string(e.meaning) + ", " + std::to_string(k) + "},\n";
  }
  if (bounds.empty())
    o << "  return solve(settings);\n";
  else
    o << "  static const std::vector<Bound> bounds = {\n"
      << bounds << "  };\n"
      << "  return two_pass_solve(settings, bounds, solve, admissible);\n";
  o << "}\n\n}  // namespace helios_rt\n";
  return o.str();
}

}  // namespace helios::codegen::detail

// Independent check of an interior event's conditions at a converged solution (tests/bats/events.bats).
// Built with a generated shooting program (SHOOT_CPP, its main renamed) and the runtime's source,
// it re-solves the problem with one condition replaced and compares finite differences of the
// optimal cost with what the multipliers claim:
//   epoch EVENT: with t_EVENT fixed at t* +- h the final mass is stationary at t* (the H-jump
//     condition's claim): |m(t*+h) - m(t*-h)| must be small against the curvature term
//     |m(t*+h) + m(t*-h) - 2 m(t*)|;
//   psi ROW of EVENT: shifting the constraint c_ROW = 0 to c_ROW = d changes the optimal fuel by
//     -nu_ROW/lambda0 per unit d (Phi = lambda0 J + nu^T c), so dm_f/dd = nu_ROW/lambda0; an active
//     bound's row (psi_ROW <= 0 held at 0) the same way.
// The shift of a psi row is 1e-6 unless given (a larger one where the rows carry more integration
// noise: S10's 2201-day legs).
// usage: sensitivity RESULT.json epoch EVENT | psi EVENT ROW [SHIFT]; prints the two numbers compared.
// The program links the runtime library; the harness needs the runtime's internals (Shooter,
// kContinuationStart), so it compiles the runtime from its source (runtime.cpp) instead.
#define main generated_main
#include SHOOT_CPP
#undef main
#include "runtime.cpp"

#include "helios/derivation/names.hpp"

namespace {

using namespace helios_rt;

int index_of(const char* const* names, int n, const std::string& name) {
  for (int i = 0; i < n; ++i)
    if (name == names[i]) return i;
  throw std::runtime_error("no variable or equation " + name);
}

// Final mass (normalized) after solving the problem with equation `row` replaced by `replaced`,
// the bounds' rows under the active set `active`.
double final_mass(std::vector<double> x, const std::vector<char>& active, int row,
                  const std::function<double(const double*, double)>& replaced) {
  Settings s;
  s.active_bounds = active;
  s.jacobian = "finite-difference";  // the replaced row has no exact derivative here
  const Function residual = [&](const double* z, double eps, Propagator& prop, double* F, double*) {
    shooting_function(z, eps, prop, F);
    F[row] = replaced(z, F[row]);
  };
  Shooter shooter(s, residual, kContinuationStart);  // a step next to a solution
  int info = 0;
  double res = 0;
  if (!shooter.solve(x, 0.0, s.final_residual, info, res))
    throw std::runtime_error("the modified problem did not converge");
  Propagator prop(s);
  std::vector<Sample> samples;
  prop.samples = &samples;
  std::vector<double> F(problem::kNumVars);
  shooting_function(x.data(), 0.0, prop, F.data());
  return samples.back().y[problem::kMassIndex];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 4) throw std::runtime_error("usage: sensitivity RESULT.json epoch EVENT | psi EVENT ROW [SHIFT]");
    const nlohmann::json result = nlohmann::json::parse(std::ifstream(argv[1]));
    std::vector<double> x;
    for (const auto& v : result.at("x")) x.push_back(v.at("value").get<double>());
    // The bounds as the solution left them: an active bound's row is its psi, an inactive one's its multiplier.
    std::vector<char> active;
    for (const auto& b : result.value("bounds", nlohmann::json::array()))
      active.push_back(b.at("active").get<bool>() ? 1 : 0);
    const std::string what = argv[2], event = argv[3];
    const int nv = problem::kNumVars;
    if (what == "epoch") {
      const int frac = index_of(problem::kVariableNames, nv, helios::derivation::names::event_fraction(event));
      const int row = index_of(problem::kEquationNames, nv, helios::derivation::names::time_row(event));
      const double h = 5e-4, star = x[frac];
      const auto at = [&](double value) {
        return final_mass(x, active, row, [&](const double* z, double) { return z[frac] - value; });
      };
      const double m0 = at(star), mp = at(star + h), mm = at(star - h);
      std::printf("%.6e %.6e\n", std::fabs(mp - mm), std::fabs(mp + mm - 2 * m0));
    } else if (what == "psi" && (argc == 5 || argc == 6)) {
      const std::size_t k = static_cast<std::size_t>(std::atoi(argv[4]));
      const int row = index_of(problem::kEquationNames, nv, helios::derivation::names::constraint_row(event, k));
      const double nu = x[index_of(problem::kVariableNames, nv, helios::derivation::names::multiplier(event, k))];
      const double lambda0 = x[index_of(problem::kVariableNames, nv, "lambda0")];
      const double d = argc == 6 ? std::atof(argv[5]) : 1e-6;
      const auto shifted = [&](double delta) {
        return final_mass(x, active, row, [delta](const double*, double f) { return f - delta; });
      };
      std::printf("%.9e %.9e\n", (shifted(d) - shifted(-d)) / (2 * d), nu / lambda0);
    } else {
      throw std::runtime_error("usage: sensitivity RESULT.json epoch EVENT | psi EVENT ROW [SHIFT]");
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sensitivity: %s\n", e.what());
    return 1;
  }
}

// Measures start strategies for the global search (templates/runtime/search/pipeline.hpp) on a problem
// without interior events whose shooting variables are all on the normalization sphere (S01,
// S13). Built with its generated program (SHOOT_CPP, its main renamed) and the runtime's source,
// it spends the same budget of shooting-function evaluations at eps_start per seed on each strategy:
//   random: the generated guess from start_generator(seed, k), then hybrd (what the search does);
//   halton: scrambled Halton points (a random shift per seed) mapped like the guess (lambda0 in
//     (0, 1), the others in (-1, 1), projected on the sphere), then hybrd;
//   de: differential evolution (DE/rand/1/bin, F = 0.7, CR = 0.9, 20 members) on log max|F| at
//     eps_start for half the budget, then hybrd from its members, best first;
// and prints, per strategy, the converged solves, the distinct extremals found and whether the
// lowest-cost one was among them (the lowest over all strategies and seeds), summed over seeds.
// usage: search_methods SEEDS EVALUATIONS   e.g. search_methods 10 8000
// The program links the runtime library; this measure needs the runtime's internals (Shooter,
// shape_of, merge_extremal), so it compiles the runtime from its source (runtime.cpp) instead.
#define main generated_main
#include SHOOT_CPP
#undef main
#include "runtime.cpp"

namespace {

using namespace helios_rt;
constexpr int N = problem::kNumVars;

struct Tally {
  int converged = 0, solves = 0;
  std::vector<StartExtremal> found;
};

// hybrd at eps_start from x; merges a converged solution into tally.found.
void solve_from(const Settings& s, std::vector<double> x, Tally& tally, int& evaluations) {
  Shooter shooter(s);
  int info = 0;
  double res = 0;
  const bool ok = shooter.solve(x, s.eps_start, s.accept_residual, info, res) && x[0] > 0;
  evaluations += shooter.evaluations;
  ++tally.solves;
  if (!ok) return;
  ++tally.converged;
  merge_extremal(tally.found, x, shape_of(s, x, s.eps_start), tally.solves, StartExtremal{});
}

void on_sphere(std::vector<double>& x) {
  double n2 = 0;
  for (double v : x) n2 += v * v;
  for (double& v : x) v /= std::sqrt(n2);
  if (x[0] < 0)
    for (double& v : x) v = -v;
}

double radical_inverse(int k, int base) {
  double f = 1, r = 0;
  for (; k > 0; k /= base) {
    f /= base;
    r += f * (k % base);
  }
  return r;
}

Tally random_starts(const Settings& s, unsigned seed, int budget) {
  Tally t;
  int evaluations = 0;
  for (int k = 0; evaluations < budget; ++k) {
    std::mt19937_64 rng = start_generator(seed, k);
    std::vector<double> x(N);
    initial_guess(rng, x.data());
    solve_from(s, x, t, evaluations);
  }
  return t;
}

Tally halton_starts(const Settings& s, unsigned seed, int budget) {
  static const int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> shift(N);
  for (double& v : shift) v = unit(rng);
  Tally t;
  int evaluations = 0;
  for (int k = 1; evaluations < budget; ++k) {
    std::vector<double> x(N);
    for (int i = 0; i < N; ++i) {
      const double u = std::fmod(radical_inverse(k, primes[i % 16]) + shift[i], 1.0);
      x[i] = i == 0 ? u : 2 * u - 1;
    }
    on_sphere(x);
    solve_from(s, x, t, evaluations);
  }
  return t;
}

double fitness(const Settings& s, const std::vector<double>& x, int& evaluations) {
  Propagator prop(s);
  std::vector<double> F(N);
  ++evaluations;
  try {
    shooting_function(x.data(), s.eps_start, prop, F.data());
  } catch (const numerical_error&) {
    return INFINITY;
  }
  double m = 0;
  for (double f : F) m = std::max(m, std::fabs(f));
  return std::isfinite(m) ? std::log(m) : INFINITY;
}

Tally de_starts(const Settings& s, unsigned seed, int budget) {
  constexpr int members = 20;
  std::mt19937_64 rng = start_generator(seed, 1 << 20);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> pick(0, members - 1), dim(0, N - 1);
  std::vector<std::vector<double>> pop(members, std::vector<double>(N));
  std::vector<double> fit(members);
  int evaluations = 0;
  for (int m = 0; m < members; ++m) {
    std::mt19937_64 r = start_generator(seed, m);
    initial_guess(r, pop[m].data());
    fit[m] = fitness(s, pop[m], evaluations);
  }
  while (evaluations < budget / 2) {
    for (int m = 0; m < members; ++m) {
      int a, b, c;
      do a = pick(rng);
      while (a == m);
      do b = pick(rng);
      while (b == m || b == a);
      do c = pick(rng);
      while (c == m || c == a || c == b);
      std::vector<double> trial = pop[m];
      const int forced = dim(rng);
      for (int i = 0; i < N; ++i)
        if (i == forced || unit(rng) < 0.9) trial[i] = pop[a][i] + 0.7 * (pop[b][i] - pop[c][i]);
      on_sphere(trial);
      const double f = fitness(s, trial, evaluations);
      if (f <= fit[m]) pop[m] = trial, fit[m] = f;
    }
  }
  std::vector<int> order(members);
  for (int m = 0; m < members; ++m) order[m] = m;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return fit[a] < fit[b]; });
  Tally t;
  for (int k = 0; evaluations < budget; ++k) {
    if (k < members) {
      solve_from(s, pop[order[k]], t, evaluations);
    } else {  // the population spent: random starts for the rest of the budget
      std::mt19937_64 r = start_generator(seed, 1000 + k);
      std::vector<double> x(N);
      initial_guess(r, x.data());
      solve_from(s, x, t, evaluations);
    }
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: search_methods SEEDS EVALUATIONS\n");
    return 2;
  }
  const int seeds = std::atoi(argv[1]), budget = std::atoi(argv[2]);
  Settings s;
  wall_seconds();
  struct Row {
    const char* name;
    Tally (*run)(const Settings&, unsigned, int);
    std::vector<Tally> tallies;
  };
  std::vector<Row> rows = {{"random", random_starts, {}}, {"halton", halton_starts, {}}, {"de", de_starts, {}}};
  double lowest = INFINITY;
  for (auto& row : rows)
    for (int seed = 1; seed <= seeds; ++seed) {
      row.tallies.push_back(row.run(s, static_cast<unsigned>(seed), budget));
      for (const auto& e : row.tallies.back().found) lowest = std::min(lowest, e.shape.cost);
    }
  std::printf("%d seeds, %d evaluations each at eps = %g; lowest cost seen %.6g (normalized)\n", seeds, budget,
              s.eps_start, lowest);
  std::printf("%-7s %8s %10s %12s %14s\n", "method", "solves", "converged", "extremals", "lowest found");
  for (const auto& row : rows) {
    int solves = 0, converged = 0, extremals = 0, lowest_found = 0;
    for (const auto& t : row.tallies) {
      solves += t.solves;
      converged += t.converged;
      extremals += static_cast<int>(t.found.size());
      for (const auto& e : t.found)
        if (std::fabs(e.shape.cost - lowest) <= 1e-6 * lowest) ++lowest_found;
    }
    std::printf("%-7s %8d %10d %12.2f %11d/%d\n", row.name, solves, converged, static_cast<double>(extremals) / seeds,
                lowest_found, seeds);
  }
  return 0;
}

// The shooting runtime library (libhelios-runtime.a) and the template DYNAMICS/SWITCH module,
// linked as a generated program links them, with the S01 constants: costate equations against
// finite differences of H, H constant along extremals with switches, and the throttle consistent
// with the switching function's sign.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <vector>

#include "helios/astro/constants.hpp"
#include "helios/astro/ephemeris.hpp"
#include "helios/astro/kepler.hpp"
#include "helios_runtime.hpp"
#include "test_helpers.hpp"

// NOTE: this test is a program of the runtime library (libhelios-runtime.a, linked as a generated
// program links it): it defines the problem's shape and the modules the library calls.
namespace problem {
constexpr int kNumStates = 7;
constexpr int kNumControls = 4;
constexpr int kThrottleIndex = 0;
constexpr int kNumVars = 8;
constexpr int kMassIndex = 6;
constexpr bool kHasEvents = false;
constexpr bool kCoastingTarget = true;  // coast_dynamics below, for coast_state
HELIOS_PARAMETER(kT0, 0.0);
HELIOS_PARAMETER(kTf, 348.795 / 365.25);
HELIOS_PARAMETER(kHomotopyStart, 1.0);
HELIOS_PARAMETER(kTimeUnitDays, 365.25);
HELIOS_PARAMETER(kLengthUnitKm, 149597870.691);
HELIOS_PARAMETER(kSpeedUnitKmS, 149597870.691 / 31557600.0);
HELIOS_PARAMETER(kEpochMjd2000, 400.0);
HELIOS_PARAMETER(kMassUnitKg, 1000.0);
HELIOS_PARAMETER(kExhaustVelocityMS, 0.0);
HELIOS_PARAMETER(mu, 39.47692642137688);    // AU^3/yr^2
HELIOS_PARAMETER(Tmax, 3.328530390038211);  // m0 AU/yr^2
HELIOS_PARAMETER(c, 4.137416349718383);     // AU/yr
const char* const kNames[] = {"rx", "ry", "rz", "vx", "vy", "vz", "m", "u", "ax", "ay", "az"};
HELIOS_PARAMETER_ARRAY(kUnit, 1, 1, 1, 1, 1, 1, 1);
// Nikko's GTOC7 row (a in AU; epoch MJD 56800 as years from MJD2000 400).
HELIOS_PARAMETER_ARRAY(kOrbitBody0, 2.2375176, 0.1052183, 5.70117 * helios::astro::DEG_TO_RAD,
                       71.94548 * helios::astro::DEG_TO_RAD, 2.08462 * helios::astro::DEG_TO_RAD,
                       287.3844555 * helios::astro::DEG_TO_RAD, (56800.0 - 51544.0 - 400.0) / 365.25);
const helios_rt::OrbitBody kOrbitBodies[] = {{"Nikko", kOrbitBody0}};
}  // namespace problem

namespace helios_rt {
constexpr int kNY = 2 * problem::kNumStates;
const ProblemShape kProblem = {"runtime-test",
                               problem::kNumStates,
                               problem::kNumControls,
                               problem::kThrottleIndex,
                               problem::kNumVars,
                               problem::kMassIndex,
                               Objective::propellant,
                               problem::kT0,
                               problem::kTf,
                               problem::kTf,
                               problem::kHomotopyStart,
                               problem::kTimeUnitDays,
                               problem::kLengthUnitKm,
                               problem::kSpeedUnitKmS,
                               problem::kEpochMjd2000,
                               problem::kMassUnitKg,
                               problem::kExhaustVelocityMS,
                               problem::mu,
                               problem::kNames,
                               problem::kNames,
                               problem::kUnit,
                               problem::kNames + 7,
                               problem::kNames,
                               problem::kNames,
                               problem::kOrbitBodies,
                               1};
// The modules the library calls that these tests do not use.
void shooting_function(const double*, double, Propagator&, double*) {
  throw std::logic_error("not used");
}
Result solve_problem(const Settings&) {
  throw std::logic_error("not used");
}
}  // namespace helios_rt

// NOTE: the template's modules, as a generated program pastes them.
#include "../modules/dynamics_cartesian_low_thrust.cpp"

namespace helios_rt {
// Unpowered two-body motion for the coasting-target propagator (the generated program's
// coast_dynamics comes from the derivation; this is the same field without J2). Defined before the
// table: GCC folds a function's address to a constant only once the function is defined, and a
// sanitized build refuses the table's static_assert otherwise.
void coast_dynamics(const double* y, double* dy) {
  const double r2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2];
  const double k = -problem::mu / (r2 * std::sqrt(r2));
  for (int i = 0; i < 3; ++i) {
    dy[i] = y[3 + i];
    dy[3 + i] = k * y[i];
  }
}

// The optional modules this program defines: the throttle's slopes (the problem has a throttle) and
// a coasting target's dynamics.
constexpr ModuleTable kModuleTable = [] {
  ModuleTable t;
  t.throttle_slopes = &throttle_slopes;
  t.coast_dynamics = &coast_dynamics;
  return t;
}();
HELIOS_MODULE_TABLE(kModuleTable);
}  // namespace helios_rt

namespace {

using helios_rt::kNY;
using helios_rt::Multipliers;

std::array<double, kNY> random_extremal_start(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> sym(-1, 1);
  // Earth-like circular orbit at 1 AU, unit mass; costates scaled so that the switching function
  // S = Tmax/c (lambda0 - l_m) - Tmax |l_v|/m changes sign within half a year.
  std::array<double, kNY> y{1.0, 0.0, 0.0, 0.0, 2 * M_PI, 0.0, 1.0};
  for (int i = 7; i < 10; ++i) y[i] = 0.5 * sym(rng);
  for (int i = 10; i < 13; ++i) y[i] = 0.1 * sym(rng);
  y[13] = 0.3;
  return y;
}

std::array<double, 4> optimal_control(const double* y, const Multipliers& m) {
  std::array<double, 4> control{};
  helios_rt::control_in_mode(y, helios_rt::mode_at(y, m), m, control.data());
  return control;
}

// NOTE: -dH/dx and dH/dlambda by central differences (step 1e-6) agree with the module to ~1e-8.
TEST(Runtime, TemplateDynamicsAreTheCanonicalEquationsOfH) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    auto y = random_extremal_start(seed);
    const Multipliers m{0.7, 0.3};
    const auto control = optimal_control(y.data(), m);
    std::array<double, kNY> dy{};
    helios_rt::dynamics(0.0, y.data(), control.data(), m, dy.data());
    // Central difference of H in component i of y.
    const auto dH = [&](int i) {
      auto plus = y, minus = y;
      const double h = 1e-6;
      plus[i] += h;
      minus[i] -= h;
      return (helios_rt::hamiltonian(0.0, plus.data(), control.data(), m) -
              helios_rt::hamiltonian(0.0, minus.data(), control.data(), m)) /
             (2 * h);
    };
    for (int i = 0; i < 7; ++i) {
      EXPECT_TRUE(IsClose(dy[i], dH(7 + i), 1e-7, 1e-7)) << "state " << i << ": x' = dH/dlambda";
      EXPECT_TRUE(IsClose(dy[7 + i], -dH(i), 1e-7, 1e-7)) << "costate " << i << ": lambda' = -dH/dx";
    }
  }
}

// NOTE: H is autonomous, so along any extremal with the optimal control it is constant, also across
// bang-bang switches (u changes where S = 0, where H does not jump). Tolerance 1e-10 absolute
// against integration at rtol = atol = 1e-13.
TEST(Runtime, HamiltonianIsConstantAlongExtremalsWithSwitches) {
  int total_switches = 0;
  for (double eps : {0.0, 0.1}) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
      helios_rt::Settings settings;
      helios_rt::Propagator prop(settings);
      std::vector<helios_rt::Sample> samples;
      std::vector<helios_rt::Switch> switches;
      prop.samples = &samples;
      prop.switches = &switches;
      auto y = random_extremal_start(seed);
      const Multipliers m{0.8, eps};
      prop.propagate(0.0, 0.5, y.data(), m);
      total_switches += static_cast<int>(switches.size());
      double hmin = INFINITY, hmax = -INFINITY;
      for (const auto& s : samples) {
        hmin = std::min(hmin, s.H);
        hmax = std::max(hmax, s.H);
        // Throttle consistent with the switching function's sign (bang-bang at eps = 0).
        if (eps == 0 && std::fabs(s.S) > 1e-9) {
          EXPECT_EQ(s.control[0], s.S < 0 ? 1.0 : 0.0) << "t = " << s.t;
        }
      }
      EXPECT_LT(hmax - hmin, 1e-10) << "eps " << eps << " seed " << seed << " switches " << switches.size();
    }
  }
  EXPECT_GT(total_switches, 0) << "the test must exercise switches";
}

// Multiple shooting (Propagator::ArcNodes, the RESIDUAL module's propagate): an arc in parts
// records the values it reaches at each node; started from those values it reaches the same end
// with every continuity defect exactly 0, and the end agrees with the undivided propagation to
// the integrator's accuracy. A node moved by d moves its own defect by -d and the next one's; the
// end depends on the last node alone.
TEST(Runtime, ArcNodesRecordReplaceAndMeasureContinuity) {
  helios_rt::Settings settings;
  const Multipliers m{0.8, 0.0};
  const auto start = random_extremal_start(3);
  auto whole = start;
  {
    helios_rt::Propagator prop(settings);
    helios_rt::propagate(prop, 0.0, 0.5, whole.data(), m);
  }
  std::vector<double> reached;
  auto recorded_end = start;
  {
    helios_rt::Propagator prop(settings);
    helios_rt::Propagator::ArcNodes nodes;
    nodes.segments = 4;
    nodes.reached = &reached;
    prop.nodes = &nodes;
    helios_rt::propagate(prop, 0.0, 0.5, recorded_end.data(), m);
    EXPECT_EQ(nodes.used, 3);
    ASSERT_EQ(nodes.times.size(), 3u);
    EXPECT_DOUBLE_EQ(nodes.times[0], 0.125);
    EXPECT_DOUBLE_EQ(nodes.times[2], 0.375);
  }
  ASSERT_EQ(reached.size(), 3u * kNY);
  {  // the parts are one arc: no repeated sample, one arc index
    std::vector<helios_rt::Sample> samples;
    std::vector<double> again;
    helios_rt::Propagator prop(settings);
    helios_rt::Propagator::ArcNodes nodes;
    nodes.segments = 4;
    nodes.reached = &again;
    prop.nodes = &nodes;
    prop.samples = &samples;
    auto y = start;
    helios_rt::propagate(prop, 0.0, 0.5, y.data(), m);
    ASSERT_GT(samples.size(), 4u);
    for (std::size_t i = 1; i < samples.size(); ++i) {
      EXPECT_GT(samples[i].t, samples[i - 1].t) << i;
      EXPECT_EQ(samples[i].arc, samples[0].arc) << i;
    }
  }
  for (int i = 0; i < kNY; ++i) EXPECT_NEAR(recorded_end[i], whole[i], 1e-10 * (1 + std::fabs(whole[i]))) << i;
  const auto from_nodes = [&](const std::vector<double>& values, std::vector<double>& defects) {
    auto y = start;
    helios_rt::Propagator prop(settings);
    helios_rt::Propagator::ArcNodes nodes;
    nodes.segments = 4;
    nodes.values = values.data();
    nodes.defects = defects.data();
    prop.nodes = &nodes;
    helios_rt::propagate(prop, 0.0, 0.5, y.data(), m);
    return y;
  };
  std::vector<double> defects(reached.size(), 1.0);
  const auto end = from_nodes(reached, defects);
  for (const double d : defects) EXPECT_EQ(d, 0.0);
  for (int i = 0; i < kNY; ++i) EXPECT_EQ(end[i], recorded_end[i]) << i;
  std::vector<double> moved = reached;
  moved[kNY + 3] += 1e-6;  // the second node's vx
  const auto moved_end = from_nodes(moved, defects);
  EXPECT_NEAR(defects[kNY + 3], -1e-6, 1e-15);
  // the part from the moved node reaches the third node elsewhere; the end is the third node's
  EXPECT_GT(std::fabs(defects[2 * kNY]), 1e-8);
  for (int i = 0; i < kNY; ++i) EXPECT_EQ(moved_end[i], recorded_end[i]) << i;
}

// The companion's price of the throttle (Propagator::fuel_weight w, search/companion.hpp) adds
// w lambda0 (Tmax/c)(1 -+ eps) to dH/du at u = 0 and 1. The template module is minimum fuel, whose
// slopes already hold lambda0 (Tmax/c)(1 -+ eps) and whose costate equations do not contain
// lambda0: with w = 1 its extremal from a start is the one of lambda0 doubled, to round-off.
TEST(Runtime, FuelWeightPricesTheThrottleAsMoreFuel) {
  helios_rt::Settings settings;
  int switches_seen = 0;
  for (const double eps : {0.0, 0.3}) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const auto start = random_extremal_start(seed);
      auto priced = start, doubled = start;
      std::vector<helios_rt::Switch> switches;
      helios_rt::Propagator weighted(settings), plain(settings);
      weighted.fuel_weight = 1;
      weighted.switches = &switches;
      helios_rt::propagate(weighted, 0.0, 0.5, priced.data(), Multipliers{0.4, eps});
      helios_rt::propagate(plain, 0.0, 0.5, doubled.data(), Multipliers{0.8, eps});
      switches_seen += static_cast<int>(switches.size());
      for (int i = 0; i < kNY; ++i)
        EXPECT_TRUE(IsClose(priced[i], doubled[i], 1e-12, 1e-12)) << "eps " << eps << " seed " << seed << " y" << i;
    }
  }
  EXPECT_GT(switches_seen, 0);  // the price moved switches, not only interior throttles
}

// The transfer angle's device (Propagator::end_rotation, search/families.hpp): the position and velocity
// triples and their costates at the end are turned by the matrix; the mass and its costate, and
// the trajectory itself, are not.
TEST(Runtime, EndRotationTurnsThePositionVelocityAndTheirCostates) {
  helios_rt::Settings settings;
  const double a = 0.7;
  const std::array<double, 9> R{std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1};
  const auto start = random_extremal_start(5);
  auto turned = start, plain = start;
  std::vector<helios_rt::Sample> turned_samples, plain_samples;
  helios_rt::Propagator with(settings), without(settings);
  with.end_rotation = &R;
  with.samples = &turned_samples;
  without.samples = &plain_samples;
  helios_rt::propagate(with, 0.0, 0.5, turned.data(), Multipliers{0.8, 0.1});
  helios_rt::propagate(without, 0.0, 0.5, plain.data(), Multipliers{0.8, 0.1});
  for (const int first : {0, 3, 7, 10}) {  // r, v, lambda_r, lambda_v
    for (int i = 0; i < 3; ++i) {
      const double expected =
          R[3 * i] * plain[first] + R[3 * i + 1] * plain[first + 1] + R[3 * i + 2] * plain[first + 2];
      EXPECT_TRUE(IsClose(turned[first + i], expected, 1e-15, 1e-15)) << first + i;
    }
  }
  EXPECT_EQ(turned[6], plain[6]);    // mass
  EXPECT_EQ(turned[13], plain[13]);  // its costate
  ASSERT_EQ(turned_samples.size(), plain_samples.size());
  for (int i = 0; i < kNY; ++i) EXPECT_EQ(turned_samples.back().y[i], plain_samples.back().y[i]) << i;
}

TEST(Runtime, SwitchTimesAreLocatedToRoundOff) {
  helios_rt::Settings settings;
  helios_rt::Propagator prop(settings);
  std::vector<helios_rt::Switch> switches;
  prop.switches = &switches;
  auto y = random_extremal_start(3);
  const Multipliers m{0.8, 0.0};
  auto y0 = y;
  prop.propagate(0.0, 0.5, y.data(), m);
  ASSERT_FALSE(switches.empty());
  // Integrate to the first switch alone: the switching function vanishes there.
  helios_rt::Propagator to_switch(settings);
  auto ys = y0;
  to_switch.propagate(0.0, switches[0].t, ys.data(), m);
  double s0 = 0, s1 = 0;
  helios_rt::throttle_slopes(ys.data(), m, s0, s1);
  EXPECT_LT(std::fabs(s0), 1e-12);
}

// NOTE: a throttle arc shorter than an integrator step has both switches inside that step, where
// the step's ends do not show them (Propagator::dip looks inside). Here lambda0 is bisected to
// where the switching function first touches zero (above it no switch, below it a first short
// burn), and just below that the burn lasts less than the integrator's steps (~6 days here). Propagated with steps of
// at most 1e-5 year (5 minutes) the burn is seen at the step ends; unlimited steps must find the same two switches.
TEST(Runtime, ShortArcsInsideOneStepAreFound) {
  helios_rt::Settings settings;
  int short_arcs = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const auto switches_with = [&](double lambda0, double max_step) {
      std::vector<helios_rt::Switch> found;
      helios_rt::Propagator prop(settings);
      prop.switches = &found;
      prop.max_step = max_step;
      auto y = random_extremal_start(seed);
      prop.propagate(0.0, 0.5, y.data(), Multipliers{lambda0, 0.0});
      return found;
    };
    double hi = 5.0, lo = hi;  // lambda0: none at hi (the engine off throughout), switches at lo
    if (!switches_with(hi, 1e-4).empty()) continue;
    while (lo > 1e-3 && switches_with(lo, 1e-4).empty()) hi = lo, lo *= 0.9;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (switches_with(mid, 1e-4).empty() ? hi : lo) = mid;
    }
    for (double below : {1e-3, 1e-4, 1e-5}) {
      const double lambda0 = lo * (1 - below);
      const auto fine = switches_with(lambda0, 1e-5), free_steps = switches_with(lambda0, INFINITY);
      if (fine.size() != 2) break;  // the first burn starts at the end of the span, not inside it
      ASSERT_EQ(free_steps.size(), fine.size()) << "seed " << seed << ", 1 - lambda0/lambda0* = " << below;
      for (std::size_t k = 0; k < fine.size(); ++k) EXPECT_NEAR(fine[k].t, free_steps[k].t, 1e-9);
      short_arcs += fine[1].t - fine[0].t < 5e-3;  // shorter than 2 days: less than a step here
    }
  }
  EXPECT_GT(short_arcs, 0) << "the test must exercise arcs shorter than a step";
}

TEST(Runtime, EphemerisModeIsJplLpInNormalizedUnits) {
  const auto n = helios_rt::ephemeris_state("Mars", 0.5);
  const auto s = helios::astro::jpl_lp_state(helios::astro::Planet::Mars, 400.0 + 0.5 * 365.25);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(IsClose(n[i] * problem::kLengthUnitKm, s[i], 0, 1e-15));
    EXPECT_TRUE(IsClose(n[3 + i] * problem::kSpeedUnitKmS, s[3 + i], 0, 1e-15));
  }
}

// A circular orbit at 1 AU turns by 2 pi t / T: the coasting propagator reaches 1e-12.
TEST(Runtime, CoastingTargetFollowsTheKeplerOrbit) {
  const double v = std::sqrt(problem::mu);
  const double period = 2 * M_PI / std::sqrt(problem::mu);
  const auto y = helios_rt::coast_state({1.0, 0.0, 0.0, 0.0, v, 0.0}, 0.0, 0.3 * period);
  const double angle = 2 * M_PI * 0.3;
  EXPECT_TRUE(IsClose(y[0], std::cos(angle), 1e-12, 0));
  EXPECT_TRUE(IsClose(y[1], std::sin(angle), 1e-12, 0));
  EXPECT_TRUE(IsClose(y[4], v * std::cos(angle), 1e-11, 0));
  const auto back = helios_rt::coast_state(y, 0.3 * period, 0.0);  // and backwards
  EXPECT_TRUE(IsClose(back[0], 1.0, 1e-12, 0));
}

// The rate is the derivative of the ephemeris model itself: Richardson-consistent and close to
// (but, because the elements drift, not equal to) the Kepler velocity the model reports.
TEST(Runtime, EphemerisRateIsTheModelsTimeDerivative) {
  const double t = 0.7;
  const auto rate = helios_rt::ephemeris_rate("Mars", t);
  const auto state = helios_rt::ephemeris_state("Mars", t);
  const double h = 1e-6;
  const auto plus = helios_rt::ephemeris_state("Mars", t + h), minus = helios_rt::ephemeris_state("Mars", t - h);
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(IsClose(rate[i], (plus[i] - minus[i]) / (2 * h), 1e-7, 1e-9)) << i;
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(IsClose(rate[i], state[3 + i], 1e-3, 1e-3)) << i;
}

// Dual numbers (the RESIDUAL module's scalar for the exact Jacobian): every operation and function
// the generated expressions use carries the exact derivative, constants carry none.
TEST(Runtime, DualNumbersCarryExactDerivatives) {
  using helios_rt::Dual;
  const double x[2] = {0.7, 1.9};
  double F[2], J[4];
  helios_rt::dual_jacobian(2, x, F, J, [](const Dual* v, Dual* f) {
    using std::atan2, std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt;
    const Dual a = v[0], b = v[1];
    f[0] = sin(a) * b + pow(a, 2.5) / b - 3.0 + 2.0 * a;
    f[1] = atan2(b, a) + exp(a) * log(b) - sqrt(a * b) + cos(b) / (1.0 + a) + pow(b, a);
  });
  const double a = x[0], b = x[1];
  EXPECT_TRUE(IsClose(F[0], std::sin(a) * b + std::pow(a, 2.5) / b - 3 + 2 * a, 1e-15, 1e-15));
  const double expected[4] = {std::cos(a) * b + 2.5 * std::pow(a, 1.5) / b + 2,  // dF0/da
                              -b / (a * a + b * b) + std::exp(a) * std::log(b) - 0.5 * std::sqrt(b / a) -
                                  std::cos(b) / ((1 + a) * (1 + a)) + std::pow(b, a) * std::log(b),  // dF1/da
                              std::sin(a) - std::pow(a, 2.5) / (b * b),                              // dF0/db
                              a / (a * a + b * b) + std::exp(a) / b - 0.5 * std::sqrt(a / b) - std::sin(b) / (1 + a) +
                                  a * std::pow(b, a - 1)};  // dF1/db
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(IsClose(J[k], expected[k], 1e-14, 1e-14)) << k;
}

// A body given by elements moves on its Kepler orbit: at its epoch it is at the elements' state,
// and the model's rate is (v, -mu r/|r|^3) to the rate's truncation error.
TEST(Runtime, OrbitBodyFollowsItsElements) {
  const double* el = problem::kOrbitBodies[0].elements;
  const auto at_epoch = helios_rt::ephemeris_state("Nikko", el[6]);
  const helios::astro::Elements elements{el[0], el[1], el[2], el[3], el[4], el[5]};
  const auto expected = helios::astro::elements_to_state(elements, problem::mu);
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(IsClose(at_epoch[i], expected[i], 1e-13, 1e-13)) << i;
  const double t = el[6] + 1.3;
  const auto state = helios_rt::ephemeris_state("Nikko", t);
  const auto rate = helios_rt::ephemeris_rate("Nikko", t);
  const double r = std::sqrt(state[0] * state[0] + state[1] * state[1] + state[2] * state[2]);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(IsClose(rate[i], state[3 + i], 1e-9, 1e-10)) << i;
    EXPECT_TRUE(IsClose(rate[3 + i], -problem::mu * state[i] / (r * r * r), 1e-9, 1e-10)) << i;
  }
  EXPECT_TRUE(IsClose(r, 2.2375176 * (1 - 0.1052183), 0, 0.5));  // within the orbit's range
}

// The parameters file (helios_runtime.hpp's load_parameters): this program's every number by name.
nlohmann::json parameter_values() {
  nlohmann::json v = {{"kT0", problem::kT0},
                      {"kTf", problem::kTf},
                      {"kHomotopyStart", problem::kHomotopyStart},
                      {"kTimeUnitDays", problem::kTimeUnitDays},
                      {"kLengthUnitKm", problem::kLengthUnitKm},
                      {"kSpeedUnitKmS", problem::kSpeedUnitKmS},
                      {"kEpochMjd2000", problem::kEpochMjd2000},
                      {"kMassUnitKg", problem::kMassUnitKg},
                      {"kExhaustVelocityMS", problem::kExhaustVelocityMS},
                      {"mu", problem::mu},
                      {"Tmax", problem::Tmax},
                      {"c", problem::c}};
  v["kUnit"] = std::vector<double>(problem::kUnit, problem::kUnit + 7);
  v["kOrbitBody0"] = std::vector<double>(problem::kOrbitBody0, problem::kOrbitBody0 + 7);
  return v;
}

// The file's text, and load_parameters' message on it ("" when it loads).
std::string load_text(const std::string& text) {
  const std::string path = ::testing::TempDir() + "parameters.json";
  std::ofstream(path) << text;
  try {
    helios_rt::load_parameters(path);
    return "";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    return what.substr(what.find(": ") + 2);  // without "parameters <path>"
  }
}

std::string load(const nlohmann::json& values) {
  return load_text(nlohmann::json{{"schema", "helios/parameters"}, {"values", values}}.dump());
}

// Every number is replaced, the shape reads the new values, and the round trip of a double through
// the file is exact.
TEST(Runtime, ParametersFileReplacesTheProblemsNumbers) {
  const nlohmann::json original = parameter_values();
  nlohmann::json changed = original;
  changed["Tmax"] = 0.1 + 0.2;
  changed["kTf"] = 1.0 / 3.0;
  changed["kOrbitBody0"][6] = -2.5e-300;
  ASSERT_EQ(load(changed), "");
  EXPECT_EQ(problem::Tmax, 0.1 + 0.2);
  EXPECT_EQ(helios_rt::kProblem.tf, 1.0 / 3.0);
  EXPECT_EQ(helios_rt::kProblem.tf_min, 1.0 / 3.0);
  EXPECT_EQ(problem::kOrbitBodies[0].elements[6], -2.5e-300);
  ASSERT_EQ(load(original), "");
  EXPECT_EQ(problem::Tmax, 3.328530390038211);
  EXPECT_EQ(parameter_values(), original);
}

// Each refusal is one line naming the value; nothing is replaced unless everything is good.
TEST(Runtime, ParametersFileRefusesWhatIsNotThisProgramsNumbers) {
  const nlohmann::json good = parameter_values();
  nlohmann::json unknown = good, missing = good, text = good, short_array = good, nested = good;
  unknown["Tmin"] = 1.0;
  unknown["Tmax"] = 99.0;
  missing.erase("mu");
  text["c"] = "4.1";
  short_array["kUnit"] = {1, 1};
  nested["kT0"] = {0.0};
  EXPECT_EQ(load(unknown), "values/Tmin is not a parameter of this program");
  EXPECT_EQ(load(missing), "values/mu is missing (the program's parameter)");
  EXPECT_EQ(load(text), "values/c is not a finite number");
  EXPECT_EQ(load(short_array), "values/kUnit is not an array of 7 finite numbers");
  EXPECT_EQ(load(nested), "values/kT0 is not a finite number");
  nlohmann::json marked = good;
  marked["Tmax"] = 12345.5;
  std::string huge = nlohmann::json{{"schema", "helios/parameters"}, {"values", marked}}.dump();
  huge.replace(huge.find("12345.5"), 7, "1e999");
  EXPECT_EQ(load_text(huge), "not JSON: [json.exception.out_of_range.406] number overflow parsing '1e999'");
  EXPECT_EQ(load_text(R"({"schema": "helios/parameters", "values": {)"),
            "not JSON: [json.exception.parse_error.101] parse error at line 1, column 44: syntax error while parsing "
            "object key - unexpected end of input; expected string literal");
  EXPECT_EQ(load_text("[]"), "not {\"schema\": \"helios/parameters\", \"values\": {...}}");
  EXPECT_EQ(load_text(R"({"schema": "helios/settings", "values": {}})"),
            "not {\"schema\": \"helios/parameters\", \"values\": {...}}");
  EXPECT_EQ(problem::Tmax, 3.328530390038211);
  EXPECT_EQ(parameter_values(), good);
  EXPECT_THROW(helios_rt::load_parameters(::testing::TempDir() + "no-such-file.json"), std::runtime_error);
}

}  // namespace

// NOTE: the runtime calls the throttle's slopes through the module table, which names the
// template's function; the modules this program lacks are null there.
TEST(Runtime, ModuleTableNamesTheProgramsOptionalModules) {
  EXPECT_EQ(helios_rt::kModules.throttle_slopes, &helios_rt::throttle_slopes);
  EXPECT_EQ(helios_rt::kModules.coast_dynamics, &helios_rt::coast_dynamics);
  EXPECT_EQ(helios_rt::kModules.shooting_legs, nullptr);
  EXPECT_EQ(helios_rt::kModules.shooting_jacobian, nullptr);
  auto y = random_extremal_start(5);
  const Multipliers m{0.7, 0.3};
  double direct_lower = 0, direct_upper = 0, lower = 0, upper = 0;
  helios_rt::throttle_slopes(y.data(), m, direct_lower, direct_upper);
  helios_rt::kModules.throttle_slopes(y.data(), m, lower, upper);
  EXPECT_EQ(lower, direct_lower);
  EXPECT_EQ(upper, direct_upper);
}

// NOTE: a Result no solve has touched says so; the others' texts are solution.json's statuses.
TEST(Runtime, StatusDefaultSaysNotSolvedAndEachHasItsArtifactText) {
  const helios_rt::Result never_run;
  EXPECT_EQ(never_run.status, helios_rt::Status::kNotSolved);
  EXPECT_STREQ(helios_rt::status_text(never_run.status), "not_solved");
  EXPECT_STREQ(helios_rt::status_text(helios_rt::Status::kConverged), "converged");
  EXPECT_STREQ(helios_rt::status_text(helios_rt::Status::kNotConverged), "not_converged");
  EXPECT_STREQ(helios_rt::status_text(helios_rt::Status::kTimeout), "timeout");
}

// NOTE: a bound's row follows the active set of the settings its propagator was made with, and
// psi is recorded on that propagator alone: two propagators (two threads of a search, or a pass
// and the report) do not see each other's set or values.
TEST(Runtime, BoundRowReadsTheActiveSetOfItsPropagator) {
  helios_rt::Settings inactive, active;
  active.active_bounds = {0, 1};
  helios_rt::Propagator a(inactive), b(active);
  EXPECT_EQ(helios_rt::bound_row(a, 1, 0.25, -3.0), -3.0);  // inactive: the multiplier's row
  EXPECT_EQ(helios_rt::bound_row(b, 1, 0.5, -3.0), 0.5);    // active: psi
  EXPECT_EQ(helios_rt::bound_row(b, 0, 0.75, -2.0), -2.0);  // bound 0 is not in b's set
  EXPECT_EQ(a.bound_values, (std::vector<double>{0.0, 0.25}));
  EXPECT_EQ(b.bound_values, (std::vector<double>{0.75, 0.5}));
  EXPECT_EQ(helios_rt::bound_row(b, 7, 1.5, -1.0), -1.0);  // beyond the set: inactive
  const helios_rt::Dual psi(0.5), nu(-3.0);
  EXPECT_EQ(helios_rt::bound_row(b, 1, psi, nu).v, 0.5);
  EXPECT_EQ(helios_rt::bound_row(a, 1, psi, nu).v, -3.0);
}

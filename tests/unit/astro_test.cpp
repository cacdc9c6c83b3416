#include "helios/astro/calendar.hpp"
#include "helios/astro/constants.hpp"
#include "helios/astro/ephemeris.hpp"
#include "helios/astro/kepler.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "helios/oem/oem.hpp"
#include "test_helpers.hpp"

namespace {

using helios::astro::Elements;
using State = std::array<double, 6>;

double norm3(const double* x) {
  return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

double energy(const State& s, double mu) {
  return 0.5 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]) - mu / norm3(s.data());
}

std::array<double, 3> ang_mom(const State& s) {
  return {s[1] * s[5] - s[2] * s[4], s[2] * s[3] - s[0] * s[5], s[0] * s[4] - s[1] * s[3]};
}

// Position compared relative to |r|, velocity relative to |v| (component-wise relative
// tolerances are meaningless for components that pass through zero).
::testing::AssertionResult StateClose(const State& a, const State& b, double rtol) {
  const double rs = std::max(norm3(a.data()), norm3(b.data()));
  const double vs = std::max(norm3(a.data() + 3), norm3(b.data() + 3));
  for (int k = 0; k < 6; ++k) {
    const double scale = k < 3 ? rs : vs;
    if (!close(a[k], b[k], rtol * scale, 0.0)) {
      return ::testing::AssertionFailure()
             << "component " << k << ": " << IsClose(a[k], b[k], rtol * scale, 0.0).message();
    }
  }
  return ::testing::AssertionSuccess();
}

double angle_diff(double a, double b) {
  return std::remainder(a - b, helios::astro::TWO_PI);
}

const double kMuEarth = helios::astro::MU_EARTH_KM3_S2;

}  // namespace

TEST(AstroConstants, Values) {
  using namespace helios::astro;
  EXPECT_TRUE(IsClose(MU_SUN_KM3_S2, 1.32712440018e11, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(AU_KM, 149597870.691, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(JD_OF_MJD2000 - 2400000.5, MJD_MINUS_MJD2000, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(JULIAN_CENTURY_DAYS, 100.0 * JULIAN_YEAR_DAYS, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(std::cos(PI), -1.0, 0.0, 1e-16));
}

TEST(AstroKepler, EccentricAnomalyResidual) {
  using helios::astro::eccentric_anomaly;
  const double es[] = {0.0, 1e-8, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999, 0.999999};
  for (double e : es) {
    for (int k = -200; k <= 200; ++k) {
      const double M = 0.0731 * k + (k % 7 == 0 ? 1e-9 : 0.0);  // spans about +-2.3 turns
      const double E = eccentric_anomaly(M, e);
      const double resid = E - e * std::sin(E) - M;
      EXPECT_TRUE(IsClose(resid, 0.0, 4e-15 * std::max(1.0, std::fabs(M)), 0.0)) << "M=" << M << " e=" << e;
      // E and M stay in the same revolution.
      EXPECT_LE(std::fabs(E - M), e + 1e-12);
    }
  }
  // Exact special points.
  EXPECT_TRUE(IsClose(eccentric_anomaly(0.0, 0.9), 0.0, 1e-30, 0.0));
  EXPECT_TRUE(IsClose(eccentric_anomaly(helios::astro::PI, 0.9), helios::astro::PI, 0.0, 1e-15));
  EXPECT_THROW(eccentric_anomaly(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(eccentric_anomaly(1.0, -0.1), std::invalid_argument);
}

TEST(AstroKepler, ElementsStateRoundTrip) {
  using namespace helios::astro;
  const Elements cases[] = {
      {7000.0, 0.01, 0.5, 1.0, 2.0, 3.0},  {26600.0, 0.74, 1.1, 4.0, 4.7, 0.2},   {42164.0, 0.3, 2.9, 6.0, 0.1, 5.9},
      {8000.0, 0.95, 0.02, 0.3, 5.5, 1.5}, {1.5e8, 0.093, 0.032, 0.86, 5.0, 0.4}, {7000.0, 0.5, 1.0, 0.0, 0.0, 0.0},
  };
  for (const auto& el : cases) {
    const State s = elements_to_state(el, kMuEarth);
    const Elements back = state_to_elements(s, kMuEarth);
    EXPECT_TRUE(IsClose(back.a, el.a, 0.0, 1e-12));
    EXPECT_TRUE(IsClose(back.e, el.e, 1e-13, 0.0));
    EXPECT_TRUE(IsClose(back.i, el.i, 1e-13, 0.0));
    EXPECT_TRUE(IsClose(angle_diff(back.raan, el.raan), 0.0, 1e-12, 0.0));
    EXPECT_TRUE(IsClose(angle_diff(back.argp, el.argp), 0.0, 1e-11, 0.0));
    EXPECT_TRUE(IsClose(angle_diff(back.mean_anomaly, el.mean_anomaly), 0.0, 1e-11, 0.0));
    EXPECT_TRUE(StateClose(elements_to_state(back, kMuEarth), s, 1e-13));
  }
}

TEST(AstroKepler, StateToElementsDegenerateOrbits) {
  using namespace helios::astro;
  // Circular equatorial, circular inclined, elliptic equatorial and retrograde equatorial: the
  // angles are conventional there, but the elements must still reproduce the state.
  const double r = 7000.0, v = std::sqrt(kMuEarth / r);
  const State cases[] = {
      {r, 0.0, 0.0, 0.0, v, 0.0},
      {0.0, r, 0.0, -v * std::cos(0.7), 0.0, v * std::sin(0.7)},
      {r, 1000.0, 0.0, -0.5, 1.15 * v, 0.0},
      {r * 0.6, r * 0.8, 0.0, 0.8 * 1.1 * v, -0.6 * 1.1 * v, 0.0},
  };
  for (const auto& s : cases) {
    const Elements el = state_to_elements(s, kMuEarth);
    EXPECT_GE(el.i, 0.0);
    EXPECT_LE(el.i, PI);
    EXPECT_TRUE(std::isfinite(el.raan) && std::isfinite(el.argp) && std::isfinite(el.mean_anomaly));
    EXPECT_TRUE(StateClose(elements_to_state(el, kMuEarth), s, 1e-13));
  }
  const State hyperbolic = {r, 0.0, 0.0, 0.0, 1.5 * v, 0.0};
  EXPECT_THROW(state_to_elements(hyperbolic, kMuEarth), std::invalid_argument);
}

TEST(AstroKepler, PropagateForwardBackward) {
  using namespace helios::astro;
  const State s0 = elements_to_state({9000.0, 0.6, 0.9, 1.2, 0.4, 0.3}, kMuEarth);
  const double period = TWO_PI * std::sqrt(9000.0 * 9000.0 * 9000.0 / kMuEarth);
  for (double dt : {1.0, 100.0, 0.37 * period, 0.5 * period, 2.7 * period, -0.8 * period}) {
    const State s1 = propagate(s0, dt, kMuEarth);
    const State s2 = propagate(s1, -dt, kMuEarth);
    for (int k = 0; k < 6; ++k) EXPECT_TRUE(IsClose(s2[k], s0[k], 0.0, 1e-12)) << "dt=" << dt << " k=" << k;
  }
  EXPECT_EQ(propagate(s0, 0.0, kMuEarth), s0);
}

TEST(AstroKepler, PropagateFullPeriod) {
  using namespace helios::astro;
  for (double e : {0.0, 0.1, 0.5, 0.9}) {
    const Elements el{12000.0, e, 0.3, 0.2, 1.0, 2.0};
    const State s0 = elements_to_state(el, kMuEarth);
    const double period = TWO_PI * std::sqrt(el.a * el.a * el.a / kMuEarth);
    EXPECT_TRUE(StateClose(propagate(s0, period, kMuEarth), s0, 1e-13)) << "e=" << e;
    EXPECT_TRUE(StateClose(propagate(s0, 3.0 * period, kMuEarth), s0, 1e-13)) << "e=" << e;
    EXPECT_TRUE(StateClose(propagate(s0, -period, kMuEarth), s0, 1e-13)) << "e=" << e;
  }
}

TEST(AstroKepler, PropagateConservesEnergyAndAngularMomentum) {
  using namespace helios::astro;
  const State s0 = elements_to_state({20000.0, 0.7, 0.4, 3.0, 2.0, 5.0}, kMuEarth);
  const double E0 = energy(s0, kMuEarth);
  const auto h0 = ang_mom(s0);
  for (double dt = -50000.0; dt <= 50000.0; dt += 3333.3) {
    const State s = propagate(s0, dt, kMuEarth);
    EXPECT_TRUE(IsClose(energy(s, kMuEarth), E0, 0.0, 1e-13)) << dt;
    const auto h = ang_mom(s);
    const double hn = norm3(h0.data());
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(IsClose(h[k], h0[k], 1e-13 * hn, 0.0)) << dt;
  }
}

TEST(AstroKepler, PropagateHyperbolic) {
  using namespace helios::astro;
  // Periapsis at 7000 km with v_inf ~ 3.9 km/s.
  const double rp = 7000.0, vp = 1.25 * std::sqrt(2.0 * kMuEarth / rp);
  const State s0 = {rp, 0.0, 0.0, 0.0, vp * std::cos(0.4), vp * std::sin(0.4)};
  const double E0 = energy(s0, kMuEarth);
  ASSERT_GT(E0, 0.0);
  const auto h0 = ang_mom(s0);
  const double hn = norm3(h0.data());
  const double a = -kMuEarth / (2.0 * E0), e = 1.0 - rp / a;
  for (double dt : {-86400.0 * 5, -3600.0, -10.0, 10.0, 600.0, 3600.0, 86400.0 * 30}) {
    const State s = propagate(s0, dt, kMuEarth);
    EXPECT_TRUE(IsClose(energy(s, kMuEarth), E0, 0.0, 1e-12)) << dt;
    // r x v can only be as accurate as |r||v|, which far out is much larger than |h|.
    const auto h = ang_mom(s);
    const double h_scale = std::max(hn, norm3(s.data()) * norm3(s.data() + 3));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(IsClose(h[k], h0[k], 1e-14 * h_scale, 0.0)) << dt;
    // Hyperbolic Kepler equation: with cosh F = (1 - r/a)/e and sign from r.v,
    // e sinh F - F = sqrt(mu/(-a)^3) * dt (periapsis at t = 0).
    const double r = norm3(s.data());
    const double rv = s[0] * s[3] + s[1] * s[4] + s[2] * s[5];
    const double F = std::copysign(std::acosh((1.0 - r / a) / e), rv);
    EXPECT_TRUE(IsClose(e * std::sinh(F) - F, std::sqrt(kMuEarth / (-a * a * a)) * dt, 1e-9, 1e-10)) << dt;
    // Coming back from far out, periapsis results from cancelling terms of size |r(dt)|: the
    // round trip is only as good as rounding at that size.
    const State back = propagate(s, -dt, kMuEarth);
    const double far = std::max(1.0, norm3(s.data()) / rp);
    EXPECT_TRUE(StateClose(back, s0, 1e-13 * far)) << dt;
  }
}

TEST(AstroKepler, PropagateMatchesMeanAnomalyAdvance) {
  using namespace helios::astro;
  const Elements el{1.3 * AU_KM, 0.35, 0.2, 1.7, 4.1, 0.9};
  const State s0 = elements_to_state(el, MU_SUN_KM3_S2);
  const double n = std::sqrt(MU_SUN_KM3_S2 / (el.a * el.a * el.a));
  for (double days : {1.0, 37.5, 200.0, 433.0, 1000.0, -250.0}) {
    const double dt = days * DAY_S;
    Elements el1 = el;
    el1.mean_anomaly += n * dt;
    EXPECT_TRUE(StateClose(propagate(s0, dt, MU_SUN_KM3_S2), elements_to_state(el1, MU_SUN_KM3_S2), 1e-12)) << days;
  }
}

TEST(AstroEphemeris, EarthAndMars) {
  using namespace helios::astro;
  for (double mjd2000 : {-3000.0, 0.0, 0.5, 1234.5, 7000.0, 12000.0}) {
    const State s = jpl_lp_state(Planet::EarthMoonBarycenter, mjd2000);
    const double r = norm3(s.data()), v = norm3(s.data() + 3);
    EXPECT_GT(r, 0.98 * AU_KM);
    EXPECT_LT(r, 1.02 * AU_KM);
    EXPECT_GT(v, 29.2);
    EXPECT_LT(v, 30.4);
    EXPECT_LT(std::fabs(s[2]), 1e-3 * AU_KM);  // ecliptic frame: EMB stays near z = 0

    const State m = jpl_lp_state(Planet::Mars, mjd2000);
    const Elements me = state_to_elements(m, MU_SUN_KM3_S2);
    const double T = (mjd2000 - 0.5) / JULIAN_CENTURY_DAYS;
    EXPECT_TRUE(IsClose(me.a, (1.52371034 + 0.00001847 * T) * AU_KM, 0.0, 1e-12));
    EXPECT_TRUE(IsClose(me.e, 0.09339410 + 0.00007882 * T, 1e-12, 0.0));
    EXPECT_TRUE(IsClose(me.i, (1.84969142 - 0.00813131 * T) * DEG_TO_RAD, 1e-12, 0.0));
  }
  // J2000.0: Earth heliocentric ecliptic position is about (-0.1771, 0.9672, 0) AU.
  const State e0 = jpl_lp_state(Planet::EarthMoonBarycenter, 0.5);
  EXPECT_TRUE(IsClose(e0[0] / AU_KM, -0.1771, 3e-4, 0.0));
  EXPECT_TRUE(IsClose(e0[1] / AU_KM, 0.9672, 3e-4, 0.0));
  // Prograde motion about +z of the ecliptic.
  EXPECT_GT(ang_mom(e0)[2], 0.0);
}

TEST(AstroEphemeris, ElementsFollowTable) {
  using namespace helios::astro;
  const Elements j = jpl_lp_elements(Planet::Jupiter, 0.5);
  EXPECT_TRUE(IsClose(j.a, 5.20288700 * AU_KM, 0.0, 1e-15));
  EXPECT_TRUE(IsClose(j.argp, (14.72847983 - 100.47390909) * DEG_TO_RAD, 1e-15, 0.0));
  EXPECT_TRUE(IsClose(j.mean_anomaly, (34.39644051 - 14.72847983) * DEG_TO_RAD, 1e-15, 0.0));
  const Elements v = jpl_lp_elements(Planet::Venus, 0.5 + JULIAN_CENTURY_DAYS);
  EXPECT_TRUE(IsClose(v.raan, (76.67984255 - 0.27769418) * DEG_TO_RAD, 1e-14, 0.0));
  const State vs = jpl_lp_state(Planet::Venus, 100.0);
  EXPECT_TRUE(IsClose(norm3(vs.data()) / AU_KM, 0.723, 0.01, 0.0));
}

// The model's exact rate (elements drift included) against fourth-order central differences of
// its state (h = 0.05 day: truncation and round-off both under 1e-9 of the state's scale), and
// apart from the Kepler velocity the state reports (the drift is visible, ~1e-5 relative).
TEST(AstroEphemeris, StateRateIsTheModelsDerivative) {
  using namespace helios::astro;
  for (Planet p : {Planet::EarthMoonBarycenter, Planet::Mars, Planet::Jupiter, Planet::Venus}) {
    for (double t : {-3000.0, 400.0, 8000.0, 12000.0}) {
      const State d = jpl_lp_state_rate(p, t);
      const double h = 0.05;
      const State p1 = jpl_lp_state(p, t + h), m1 = jpl_lp_state(p, t - h);
      const State p2 = jpl_lp_state(p, t + 2 * h), m2 = jpl_lp_state(p, t - 2 * h);
      const State s = jpl_lp_state(p, t);
      const double velocity_scale = norm3(s.data() + 3);
      for (int i = 0; i < 6; ++i) {
        const double fd = (8 * (p1[i] - m1[i]) - (p2[i] - m2[i])) / (12 * h);
        // km/day and km/s/day: the scales are the state's per day (a day's motion is ~1e-2 rad)
        const double scale = (i < 3 ? velocity_scale * DAY_S : 1e-2 * velocity_scale);
        EXPECT_LE(std::fabs(fd - d[i]), 1e-8 * scale) << "planet " << static_cast<int>(p) << " t " << t << " i " << i;
      }
      EXPECT_GT(std::fabs(d[0] - s[3] * DAY_S), 1e-7 * velocity_scale * DAY_S) << "the drift is in the rate";
    }
  }
}

TEST(AstroEphemeris, PlanetFromName) {
  using namespace helios::astro;
  EXPECT_EQ(planet_from_name("Earth"), Planet::EarthMoonBarycenter);
  EXPECT_EQ(planet_from_name("EMB"), Planet::EarthMoonBarycenter);
  EXPECT_EQ(planet_from_name("earth"), Planet::EarthMoonBarycenter);
  EXPECT_EQ(planet_from_name("MARS"), Planet::Mars);
  EXPECT_EQ(planet_from_name("jUpItEr"), Planet::Jupiter);
  EXPECT_EQ(planet_from_name("Venus"), Planet::Venus);
  try {
    planet_from_name("Pluto");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("'Pluto'"), std::string::npos) << ex.what();
  }
  EXPECT_THROW(planet_from_name(""), std::invalid_argument);
  EXPECT_THROW(planet_from_name("Earth "), std::invalid_argument);
}

// The calendar date of an MJD2000 epoch (TDB): the project's MJD2000 starts at 2000-01-01T00:00
// (MJD - 51544, as the parser's dates and the OEM's epochs), so J2000.0 (noon) is MJD2000 0.5.
TEST(Calendar, Mjd2000ZeroIsMidnightAndJ2000IsNoon) {
  using helios::astro::iso_date_tdb;
  EXPECT_EQ(iso_date_tdb(0.0), "2000-01-01T00:00:00");
  EXPECT_EQ(iso_date_tdb(helios::astro::JD_J2000 - helios::astro::JD_OF_MJD2000), "2000-01-01T12:00:00");
  EXPECT_EQ(iso_date_tdb(-0.25), "1999-12-31T18:00:00");
  EXPECT_EQ(iso_date_tdb(366.0), "2001-01-01T00:00:00");    // 2000 is a leap year
  EXPECT_EQ(iso_date_tdb(8456.0), "2023-02-25T00:00:00");   // MJD 60000
  EXPECT_EQ(iso_date_tdb(10336.6), "2028-04-19T14:24:00");  // S07's epoch
  EXPECT_EQ(iso_date_tdb(-36525.0), "1899-12-31T00:00:00");
  EXPECT_EQ(iso_date_tdb(73050.0), "2200-01-02T00:00:00");
  EXPECT_EQ(iso_date_tdb(400.999999), "2001-02-05T00:00:00");  // rounded to the second
  EXPECT_THROW(iso_date_tdb(std::nan("")), std::invalid_argument);
  EXPECT_THROW(iso_date_tdb(3e6), std::invalid_argument);
}

// The same instant as the OEM's epoch over four centuries: a quarter second past a whole second
// (clear of both rounding edges), which the date rounds down to and the OEM prints with its fraction.
TEST(Calendar, AgreesWithTheOemEpochs) {
  for (double mjd2000 = -36525.0; mjd2000 < 109575.0; mjd2000 += 97.123456789) {
    const double quarter_past = (std::round(mjd2000 * 86400.0) + 0.25) / 86400.0;
    const std::string oem = helios::oem::oem_epoch(quarter_past);
    EXPECT_EQ(helios::astro::iso_date_tdb(quarter_past), oem.substr(0, 19)) << mjd2000;
    EXPECT_EQ(oem.substr(19, 2), ".2") << oem;  // a quarter second, to the double's resolution
  }
}

TEST(Calendar, DurationsInHoursBelowThreeDays) {
  using helios::astro::duration_text;
  EXPECT_EQ(duration_text(14.800364354648908 / 24), "14.80 h");
  EXPECT_EQ(duration_text(2.9), "69.60 h");
  EXPECT_EQ(duration_text(348.795, 1), "348.8 days");
}

// The time of flight (fixed, or free between bounds, an open upper bound derived for a minimum time),
// the departure's calendar epoch and its window, set by the sentences of forms/ and the facts in
// other words.
#include <cmath>

#include "grammar.hpp"
#include "helios/astro/constants.hpp"
#include "helios/astro/ephemeris.hpp"

namespace helios::spec::grammar {
namespace {

// A minimum time the text leaves unbounded is searched up to this fraction of the time the engine at
// full thrust takes to burn the whole initial mass (beyond it, less than 5 % of the mass is left) ...
constexpr double kBurnFraction = 0.95;
// ... or, with no mass flow (a solar sail), up to this many periods of the departure orbit.
constexpr double kSailPeriods = 10;

std::string days(double d) {
  return io::short_number(d) + " days";
}

}  // namespace

void Builder::fixed_time_of_flight(double days) {
  once(detail::Field::Tof);
  if (time.value("final_time", "") == "free") throw sentence_error("the time of flight is given twice");
  time["tof_days"] = days;
  time["final_time"] = "fixed";
  tof_where = here;
}

void Builder::bound_time_of_flight(std::optional<double> lo, std::optional<double> hi) {
  if (time.value("final_time", "") == "fixed") throw sentence_error("the time of flight is given twice");
  for (const auto& [bound, key] : {std::pair{lo, "tof_min_days"}, std::pair{hi, "tof_max_days"}}) {
    if (!bound) continue;
    if (time.contains(key)) throw sentence_error("the time of flight is given twice");
    time[key] = *bound;
  }
  if (lo && !(*lo >= 0)) throw sentence_error("the shortest time of flight must not be negative");
  if (hi && !(*hi > 0)) throw sentence_error("the longest time of flight must be positive");
  if (time.contains("tof_min_days") && time.contains("tof_max_days") &&
      !(time["tof_max_days"].get<double>() > time["tof_min_days"].get<double>()))
    throw sentence_error("the time-of-flight window must satisfy 0 <= min < max");
  time["final_time"] = "free";
  tof_where = here;
}

// The period of the orbit the spacecraft departs on [days]: of its initial state, of the body it
// leaves, or of the orbit it departs from; none when that is not a closed orbit.
std::optional<double> Builder::departure_period_days() const {
  const double mu = central_body["mu_km3_s2"].get<double>();
  const json& t = departure->target;
  double a = 0;
  if (t.contains("semi_major_axis_km")) a = t["semi_major_axis_km"].get<double>();
  if (t.value("kind", "") == "orbit") a = t["elements"]["a_AU"].get<double>() * astro::AU_KM;
  std::optional<std::array<double, 6>> state;
  if (t.contains("position_km"))
    state = std::array<double, 6>{t["position_km"][0],   t["position_km"][1],   t["position_km"][2],
                                  t["velocity_km_s"][0], t["velocity_km_s"][1], t["velocity_km_s"][2]};
  if (t.value("kind", "") == "body")
    state = astro::jpl_lp_state(astro::planet_from_name(t["body"]), time["epoch_mjd2000"].get<double>());
  if (state) {  // vis-viva: a = -mu / (2 energy), a closed orbit's energy negative
    const auto& s = *state;
    const double energy = (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]) / 2 - mu / std::hypot(s[0], s[1], s[2]);
    a = energy < 0 ? -mu / (2 * energy) : 0;
  }
  if (!(a > 0)) return std::nullopt;
  return 2 * astro::PI * std::sqrt(a * a * a / mu) / astro::DAY_S;
}

void Builder::finish_time() {
  if (time.value("final_time", "") != "free") return;
  if (!time.contains("tof_min_days")) time["tof_min_days"] = 0.0;
  if (time.contains("tof_max_days")) return;
  const Where w = tof_where.value_or(objective_where.value_or(here));
  if (objective.value("kind", "") != "minimum_time")
    fail(w, "the time of flight is free with no upper bound, which only a minimum time leaves open (the " +
                objective.value("kind", std::string("objective")) +
                " would take the flight as long as it may): bound it ('The time of flight is free, at most Q.')");
  double bound = 0;
  std::string why;
  if (spacecraft.contains("array_power_1AU_W"))
    fail(w,
         "the time of flight is free with no upper bound, and a solar-electric engine burns at a rate that follows "
         "its path: bound it ('The time of flight is free, at most Q.')");
  if (propulsion == "low_thrust" && spacecraft.value("mass_model", "") != "constant") {
    const double m0 = spacecraft["initial_mass_kg"].get<double>(), thrust = spacecraft["thrust_N"].get<double>(),
                 isp = spacecraft["isp_s"].get<double>();
    const double burn = m0 * astro::G0_M_S2 * isp / thrust / astro::DAY_S;
    bound = kBurnFraction * burn;
    why = "95 % of the " + days(burn) + " the engine at full thrust (" + io::short_number(thrust) + " N at " +
          io::short_number(isp) + " s) takes to burn the whole initial mass (" + io::short_number(m0) + " kg)";
  } else if (const auto period = departure_period_days()) {
    bound = kSailPeriods * *period;
    why = io::short_number(kSailPeriods) + " periods of the departure orbit (" + days(*period) +
          (propulsion == "solar_sail" ? "; a sail burns no mass to bound it)"
                                      : "; an engine of constant mass never runs out to bound it)");
  } else {
    fail(w,
         "the time of flight is free with no upper bound, and the departure is on no closed orbit to bound it "
         "by: bound it ('The time of flight is free, at most Q.')");
  }
  if (!(bound > time["tof_min_days"].get<double>()))
    fail(w, "the shortest time of flight, " + days(time["tof_min_days"].get<double>()) + ", is beyond " + days(bound) +
                ", " + why + ": bound the time of flight ('The time of flight is free, at most Q.')");
  time["tof_max_days"] = bound;
  notes.push_back("The text bounds no time of flight: HELIOS searches the minimum time up to " + days(bound) + ", " +
                  why + ".");
}

void Builder::set_epoch(double mjd2000) {
  // The same epoch written on two scales (MJD 61880.6, MJD2000 10336.6) differs by rounding only.
  constexpr double kSameEpochDays = 1e-6;
  if (time.contains("epoch_mjd2000")) {
    const double before = time["epoch_mjd2000"].get<double>();
    if (std::fabs(before - mjd2000) > kSameEpochDays)
      throw sentence_error("the epoch MJD2000 " + io::short_number(mjd2000) + " contradicts the epoch MJD2000 " +
                           io::short_number(before) + " stated before");
  }
  time["t0_days"] = 0.0;
  if (!time.contains("epoch_mjd2000")) time["epoch_mjd2000"] = mjd2000;
}

void Builder::departure_window_dates(double lo, double hi) {
  if (!(hi > lo)) throw sentence_error("the departure window is empty: its start must come before its end");
  window_dates = {lo, hi};
  free_departure_where = here;
}

// The window between two dates about the departure epoch the text states, else about its start.
void Builder::finish_departure_window() {
  if (!window_dates) return;
  const auto [lo, hi] = *window_dates;
  if (time.contains("epoch_mjd2000")) {
    const double epoch = time["epoch_mjd2000"].get<double>();
    if (epoch < lo || epoch > hi)
      fail(free_departure_where, "the departure epoch MJD2000 " + io::short_number(epoch) +
                                     " lies outside the departure window (MJD2000 " + io::short_number(lo) + " to " +
                                     io::short_number(hi) + "): state one epoch inside it, or none");
  }
  const double epoch = time.value("epoch_mjd2000", lo);
  Where stated = free_departure_where;
  free_departure(lo - epoch, hi - epoch, epoch);
  free_departure_where = stated;
}

void Builder::free_departure(double lo, double hi, double mjd2000) {
  set_epoch(mjd2000);
  time["departure"] = "free";
  time["t0_window_days"] = json::array({lo, hi});
  free_departure_where = here;
}

}  // namespace helios::spec::grammar

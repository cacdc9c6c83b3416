// The departure's calendar epoch and its window, set by the sentences of the departure (forms/)
// and the facts in other words.
#include <cmath>

#include "grammar.hpp"

namespace helios::spec::grammar {

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

void Builder::free_departure(double lo, double hi, double mjd2000) {
  set_epoch(mjd2000);
  time["departure"] = "free";
  time["t0_window_days"] = json::array({lo, hi});
  free_departure_where = here;
}

}  // namespace helios::spec::grammar

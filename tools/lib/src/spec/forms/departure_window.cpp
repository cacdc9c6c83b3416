// A sliding departure: "The departure epoch is free between Q before and Q after MJD2000 N." (also
// "Q after and Q after", "MJD N") and "The departure date is free within Q of MJD N.". The epoch is the
// window's reference; the total time of flight must be fixed (parse.cpp).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void around(Builder& b, const std::smatch& m) {
  b.once("the departure window");
  const double a = quantity(m, 1, Dimension::Time), c = quantity(m, 4, Dimension::Time);
  if (a < 0 || c < 0) throw sentence_error("say 'N days before' or 'N days after' with N >= 0");
  const double lo = lowercase(m[3].str()) == "before" ? -a : a;
  const double hi = lowercase(m[6].str()) == "before" ? -c : c;
  if (!(hi > lo)) throw sentence_error("the departure window is empty: its start must come before its end");
  b.free_departure(lo, hi, mjd2000_of(m[7].str(), m[8].str()));
}

void within(Builder& b, const std::smatch& m) {
  b.once("the departure window");
  const double a = quantity(m, 1, Dimension::Time);
  if (!(a > 0)) throw sentence_error("the departure window's half-width must be positive");
  b.free_departure(-a, a, mjd2000_of(m[3].str(), m[4].str()));
}

}  // namespace

std::vector<Form> departure_window() {
  return {
      {"the departure window around an epoch",
       250,
       R"(The departure (?:epoch|date) is free,? between )" + kQuantity + " (before|after) and " + kQuantity +
           " (before|after) (MJD2000|MJD) (" + kNum + ")",
       around,
       {{"The departure epoch is free between 30 days before and 30 days after MJD2000 400.",
         "planets -departure +from_earth",
         R"~({"/time": {"t0_days": 0, "epoch_mjd2000": 400, "departure": "free", "t0_window_days": [-30, 30],
                 "final_time": "fixed", "tof_days": 900}})~"},
        {"The departure epoch is free between 30 days after and 10 days after MJD2000 400.",
         "planets -departure +from_earth", R"~({"error": "the departure window is empty"})~"}}},
      {"the departure window within a time of an epoch",
       260,
       R"(The departure (?:epoch|date) is free,? within )" + kQuantity + " (?:of|around) (MJD2000|MJD) (" + kNum + ")",
       within,
       {{"The departure date is free within 20 days of MJD 51944.", "planets -departure +from_earth",
         R"~({"/time/epoch_mjd2000": 400, "/time/t0_window_days": [-20, 20]})~"}}}};
}

}  // namespace helios::spec::grammar::forms

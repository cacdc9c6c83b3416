// A sliding departure: "The departure epoch is free between Q before and Q after DATE." (also "Q after
// and Q after"), "The departure date is free within Q of DATE.", "The departure date is free between
// DATE and DATE.", "The spacecraft may depart at any date between DATE and DATE.", "Launch window: DATE
// to DATE.", "The launch window opens on DATE and closes on DATE."; DATE a calendar date, MJD N, MJD2000
// N, JD N or "N days after DATE". Around an epoch the epoch is the window's reference; between two dates
// it is the one the text states, else the window's start (time.cpp). The total time of flight must be
// fixed (events.cpp).
#include "../fact_scan.hpp"
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const std::string kFree =
    "(?:The (?:departure|launch) (?:epoch|date) is free|The departure is free|The spacecraft (?:may|can) "
    "(?:depart|launch|leave)(?: at any (?:date|time)| any time)?),?";

double date(const std::string& text) {
  std::optional<double> epoch;
  try {
    epoch = detail::epoch_of(text);
  } catch (const detail::facts_error& e) {
    throw sentence_error(e.what());
  }
  if (!epoch)
    throw sentence_error("'" + text +
                         "' is no date: a window's dates read e.g. '2030-01-01', '4 February 2031', 'MJD 62000', "
                         "'MJD2000 11000' or '30 days after 2030-01-01'");
  return *epoch;
}

void around(Builder& b, const std::smatch& m) {
  b.once("the departure window");
  const double a = quantity(m, 1, Dimension::Time), c = quantity(m, 4, Dimension::Time);
  if (a < 0 || c < 0) throw sentence_error("say 'N days before' or 'N days after' with N >= 0");
  const double lo = lowercase(m[3].str()) == "before" ? -a : a;
  const double hi = lowercase(m[6].str()) == "before" ? -c : c;
  if (!(hi > lo)) throw sentence_error("the departure window is empty: its start must come before its end");
  b.free_departure(lo, hi, date(m[7].str()));
}

void within(Builder& b, const std::smatch& m) {
  b.once("the departure window");
  const double a = quantity(m, 1, Dimension::Time);
  if (!(a > 0)) throw sentence_error("the departure window's half-width must be positive");
  b.free_departure(-a, a, date(m[3].str()));
}

void between(Builder& b, const std::smatch& m) {
  b.once("the departure window");
  const std::size_t at = m[1].matched ? 1 : m[3].matched ? 3 : 5;  // the alternative that matched
  b.departure_window_dates(date(m[at].str()), date(m[at + 1].str()));
}

}  // namespace

std::vector<Form> departure_window() {
  return {
      {"the departure window around an epoch",
       250,
       kFree + " between " + kQuantity + " (before|after) and " + kQuantity + " (before|after) (.+)",
       around,
       {{"The departure epoch is free between 30 days before and 30 days after MJD2000 400.",
         "planets -departure +from_earth",
         R"~({"/time": {"t0_days": 0, "epoch_mjd2000": 400, "departure": "free", "t0_window_days": [-30, 30],
                 "final_time": "fixed", "tof_days": 900}})~"},
        {"The departure date is free, between 45 days before and 45 days after 2030-09-01.",
         "planets -departure +from_earth", R"~({"/time/epoch_mjd2000": 11201, "/time/t0_window_days": [-45, 45]})~"},
        {"The departure epoch is free between 30 days after and 10 days after MJD2000 400.",
         "planets -departure +from_earth", R"~({"error": "the departure window is empty"})~"}}},
      {"the departure window within a time of an epoch",
       251,
       kFree + R"( within (?:\+/- ?|± ?|plus or minus )?)" + kQuantity + " (?:of|around) (.+)",
       within,
       {{"The departure date is free within 20 days of MJD 51944.", "planets -departure +from_earth",
         R"~({"/time/epoch_mjd2000": 400, "/time/t0_window_days": [-20, 20]})~"},
        {"The departure is free within 30 days of 2031-06-15.", "planets -departure +from_earth",
         R"~({"/time/epoch_mjd2000": 11488, "/time/t0_window_days": [-30, 30]})~"},
        {"The departure date is free within 20 days of teatime.", "planets -departure +from_earth",
         R"~({"error": "'teatime' is no date"})~"}}},
      {"the departure window between two dates",
       252,
       kFree + " between (.+?) and (.+)|(?:The )?(?:launch|departure) window(?: is|:)?(?: from)? (.+?) " +
           "(?:to|until|through) (.+)|The (?:launch|departure) window opens (?:on )?(.+?) and closes (?:on )?(.+)",
       between,
       {{"The departure date is free between 2030-01-01 and 2030-12-31.", "planets -departure +from_earth",
         R"~({"/time": {"t0_days": 0, "epoch_mjd2000": 10958, "departure": "free", "t0_window_days": [0, 364],
                 "final_time": "fixed", "tof_days": 900}})~"},
        {"The spacecraft may depart at any date between MJD 62000 and 400 days after 2028-08-27.",
         "planets -departure +from_earth", R"~({"/time/epoch_mjd2000": 10456, "/time/t0_window_days": [0, 410]})~"},
        {"Launch window: 2030-05-01 to 2030-06-30.", "planets -departure +window_epoch",
         R"~({"/time/epoch_mjd2000": 11100, "/time/t0_window_days": [-22, 38]})~"},
        {"The launch window opens on 1 March 2031 and closes on 30 April 2031.", "planets -departure +from_earth",
         R"~({"/time/epoch_mjd2000": 11382, "/time/t0_window_days": [0, 60]})~"},
        {"The departure date is free between 2030-06-01 and 2030-01-01.", "planets -departure +from_earth",
         R"~({"error": "the departure window is empty"})~"},
        {"Launch window: 2030-05-01 to 2030-06-30.", "planets",
         R"~({"error": "the departure epoch MJD2000 400 lies outside the departure window"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

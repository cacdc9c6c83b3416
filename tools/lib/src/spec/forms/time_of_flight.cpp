// The time of flight: fixed ("The time of flight is Q."), free between bounds ("The time of flight is
// free, between Q and Q.", "... is at most Q", "... must be between N and Q", "... is at least Q"), or
// free ("The time of flight is free."): for a minimum time, an upper bound the text leaves open is
// derived from the physics and said in the spec's notes (time.cpp).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const std::string kTimeOfFlight = "The (?:total )?(?:time of flight|flight time|transfer time)";

void fixed(Builder& b, const std::smatch& m) {
  const double tof = quantity(m, 1, Dimension::Time);
  b.check_value(detail::Field::Tof, tof, m[1].str() + " " + m[2].str());
  b.fixed_time_of_flight(tof);
}

// The lower end of "between N [UNIT] and Q": in its own unit, else the upper end's.
double lower_end(const std::smatch& m, std::size_t at) {
  return number(m[at].str()) * unit_factor(Dimension::Time, m[at + 1].matched ? m[at + 1].str() : m[at + 3].str());
}

void bounded(Builder& b, const std::smatch& m) {
  std::optional<double> lo, hi;
  if (m[1].matched) {
    const double q = quantity(m, 2, Dimension::Time);
    (lowercase(m[1].str()).find("least") != std::string::npos ? lo : hi) = q;
  }
  for (const std::size_t at : {4, 8})
    if (m[at].matched) {
      lo = lower_end(m, at);
      hi = quantity(m, at + 2, Dimension::Time);
    }
  b.bound_time_of_flight(lo, hi);
}

void free(Builder& b, const std::smatch&) {
  b.bound_time_of_flight(std::nullopt, std::nullopt);
}

}  // namespace

std::vector<Form> time_of_flight() {
  const std::string lo = "(" + kNum + ")(?: (" + kUnit + "))?";
  return {
      {"a bounded time of flight",
       70,
       kTimeOfFlight +
           " (?:is|must be|may be|can be)(?: free)?,? (?:(at most|no more than|not more than|up to|under|below|"
           "less than|at the most|at least|no less than|not less than) " +
           kQuantity + "|between " + lo + " and " + kQuantity + "|from " + lo + " to " + kQuantity + ")",
       bounded,
       {{"The time of flight is free, between 50 days and 600 days.", "planets -tof",
         R"~({"/time": {"t0_days": 0, "epoch_mjd2000": 400, "final_time": "free", "tof_min_days": 50,
                 "tof_max_days": 600}})~"},
        {"The time of flight is free, at most 2 years.", "planets -tof",
         R"~({"/time/tof_min_days": 0, "/time/tof_max_days": 730.5})~"},
        {"The time of flight is at most 2 days.", "earth -tof",
         R"~({"/time": {"t0_days": 0, "final_time": "free", "tof_min_days": 0, "tof_max_days": 2}})~"},
        {"The time of flight must be between 50 and 600 days.", "planets -tof",
         R"~({"/time/tof_min_days": 50, "/time/tof_max_days": 600})~"},
        {"The time of flight is at least 1 day.", "earth -tof",
         R"~({"/time/tof_min_days": 1, "/time/tof_max_days": 5.39138744212963})~"},
        {"The time of flight is free, between 600 days and 50 days.", "planets -tof",
         R"~({"error": "the time-of-flight window must satisfy 0 <= min < max"})~"}}},
      {"a free time of flight",
       71,
       kTimeOfFlight + " is (?:left )?free",
       free,
       {{"The time of flight is free.", "earth -tof",
         R"~({"/time": {"t0_days": 0, "final_time": "free", "tof_min_days": 0, "tof_max_days": 5.39138744212963},
                 "/notes": ["The text bounds no time of flight: HELIOS searches the minimum time up to 5.391387442 days, 95 % of the 5.675144676 days the engine at full thrust (60 N at 2000 s) takes to burn the whole initial mass (1500 kg)."]})~"},
        {"The time of flight is free.", "planets -tof",
         R"~({"error": "the time of flight is free with no upper bound, which only a minimum time leaves open"})~"}}},
      {"a fixed time of flight",
       120,
       R"(The (?:total )?time of flight is (?:fixed at )?)" + kQuantity,
       fixed,
       {{"The time of flight is 30135888 s.", "sun -tof",
         R"~({"/time": {"t0_days": 0, "final_time": "fixed", "tof_days": 348.795}})~"},
        {"The total time of flight is fixed at 2 years.", "sun -tof", R"~({"/time/tof_days": 730.5})~"},
        {"The time of flight is six weeks.", "sun -tof", R"~({"/time/tof_days": 42})~"},
        {"The time of flight is three hundred and twenty-five days.", "sun -tof", R"~({"/time/tof_days": 325})~"},
        {"The time of flight is -3 days.", "sun -tof", R"~({"error": "the time of flight must be positive"})~"},
        {"The time of flight is 1 day.", "earth -tof",
         R"~({"error": "the time of flight is fixed (1 d), so minimizing it minimizes a constant"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

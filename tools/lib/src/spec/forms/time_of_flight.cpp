// "The time of flight is Q." (fixed) and "The time of flight is free, between Q and Q." or "..., at
// most Q." (free, searched in that window).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void fixed(Builder& b, const std::smatch& m) {
  b.once(detail::Field::Tof);
  const double tof = quantity(m, 1, Dimension::Time);
  b.check_value(detail::Field::Tof, tof, m[1].str() + " " + m[2].str());
  b.time["tof_days"] = tof;
  b.time["final_time"] = "fixed";
}

void free(Builder& b, const std::smatch& m) {
  b.once(detail::Field::Tof);
  const double lo = m[1].matched ? 0.0 : quantity(m, 3, Dimension::Time);
  const double hi = m[1].matched ? quantity(m, 1, Dimension::Time) : quantity(m, 5, Dimension::Time);
  if (!(lo >= 0 && hi > lo)) throw sentence_error("the time-of-flight window must satisfy 0 <= min < max");
  b.time["final_time"] = "free";
  b.time["tof_min_days"] = lo;
  b.time["tof_max_days"] = hi;
}

}  // namespace

std::vector<Form> time_of_flight() {
  return {{"a free time of flight",
           70,
           R"(The (?:total )?time of flight is free,? (?:at most )" + kQuantity + "|between " + kQuantity + " and " +
               kQuantity + ")",
           free,
           {{"The time of flight is free, between 50 days and 600 days.", "planets -tof",
             R"~({"/time": {"t0_days": 0, "epoch_mjd2000": 400, "final_time": "free", "tof_min_days": 50,
                 "tof_max_days": 600}})~"},
            {"The time of flight is free, at most 2 years.", "planets -tof",
             R"~({"/time/tof_min_days": 0, "/time/tof_max_days": 730.5})~"},
            {"The time of flight is free, between 600 days and 50 days.", "planets -tof",
             R"~({"error": "the time-of-flight window must satisfy 0 <= min < max"})~"}}},
          {"a fixed time of flight",
           120,
           R"(The (?:total )?time of flight is (?:fixed at )?)" + kQuantity,
           fixed,
           {{"The time of flight is 30135888 s.", "sun -tof",
             R"~({"/time": {"t0_days": 0, "final_time": "fixed", "tof_days": 348.795}})~"},
            {"The total time of flight is fixed at 2 years.", "sun -tof", R"~({"/time/tof_days": 730.5})~"},
            {"The time of flight is -3 days.", "sun -tof", R"~({"error": "the time of flight must be positive"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

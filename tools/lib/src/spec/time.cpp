// Sentences about time: the time of flight (fixed or free), the departure, its epoch and its window.
#include "grammar.hpp"

#include <cmath>

namespace helios::spec::grammar {

void Builder::on_tof(const std::smatch& m) {
  once(detail::Field::Tof);
  const double tof = quantity(m, 1, Dimension::Time);
  check_value(detail::Field::Tof, tof, m[1].str() + " " + m[2].str());
  time["tof_days"] = tof;
  time["final_time"] = "fixed";
}

void Builder::on_free_tof(const std::smatch& m) {
  once(detail::Field::Tof);
  const double lo = m[1].matched ? 0.0 : quantity(m, 3, Dimension::Time);
  const double hi = m[1].matched ? quantity(m, 1, Dimension::Time) : quantity(m, 5, Dimension::Time);
  if (!(lo >= 0 && hi > lo)) throw sentence_error("the time-of-flight window must satisfy 0 <= min < max");
  time["final_time"] = "free";
  time["tof_min_days"] = lo;
  time["tof_max_days"] = hi;
}

void Builder::on_depart_from(const std::smatch& m) {
  depart(m[2].str(), m[1].str());
}

void Builder::on_depart(const std::smatch& m) {
  depart(m[1].matched ? m[1].str() : "", m[2].str());
}

void Builder::depart(const std::string& at, const std::string& target_text) {
  static const std::regex orbit_word = re(R"(.*\borbit\b.*)");
  if (std::regex_match(target_text, orbit_word)) return depart_from_orbit(at, target_text);
  json target;
  try {
    target = parse_target(target_text);
  } catch (const sentence_error& form) {
    // "departs from Earth on 2001-02-04": the facts in other words read what the form does not
    detail::SentenceFacts facts;
    try {
      facts = detail::read_facts(here.text, body_names());
    } catch (const detail::facts_error& e) {
      // a body named, then words the form does not take: the facts' reason is the one to give
      static const std::regex named_then_more = re(R"([A-Za-z][A-Za-z0-9_]* (?:on|at|in) .+)");
      if (std::regex_match(target_text, named_then_more)) throw sentence_error(e.what());
      throw form;
    }
    return apply_facts(facts);
  }
  once("the departure");
  if (!at.empty()) epoch(at);
  departure = Endpoint{here, target, "initial_state", std::nullopt};
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

void Builder::epoch(const std::string& phrase) {
  std::smatch m;
  static const std::regex t_re = re(R"(t\s*=\s*)" + kQuantity);
  static const std::regex mjd_re = re("(MJD2000|MJD) (" + kNum + ")");
  if (std::regex_match(phrase, m, t_re)) {
    once(detail::Field::T0);
    time["t0_days"] = quantity(m, 1, Dimension::Time);
    departure_at_t = true;
  } else if (std::regex_match(phrase, m, mjd_re)) {
    set_epoch(mjd2000_of(m[1].str(), m[2].str()));
  } else {
    throw sentence_error("departure time '" + phrase + "' must read 't = VALUE UNIT', 'MJD VALUE' or 'MJD2000 VALUE'");
  }
}

void Builder::on_free_dep(const std::smatch& m) {
  once("the departure window");
  const double a = quantity(m, 1, Dimension::Time), b = quantity(m, 4, Dimension::Time);
  if (a < 0 || b < 0) throw sentence_error("say 'N days before' or 'N days after' with N >= 0");
  const double lo = lowercase(m[3].str()) == "before" ? -a : a;
  const double hi = lowercase(m[6].str()) == "before" ? -b : b;
  if (!(hi > lo)) throw sentence_error("the departure window is empty: its start must come before its end");
  free_departure(lo, hi, mjd2000_of(m[7].str(), m[8].str()));
}

void Builder::on_free_dep_within(const std::smatch& m) {
  once("the departure window");
  const double a = quantity(m, 1, Dimension::Time);
  if (!(a > 0)) throw sentence_error("the departure window's half-width must be positive");
  free_departure(-a, a, mjd2000_of(m[3].str(), m[4].str()));
}

void Builder::free_departure(double lo, double hi, double mjd2000) {
  set_epoch(mjd2000);
  time["departure"] = "free";
  time["t0_window_days"] = json::array({lo, hi});
  free_departure_where = here;
}

}  // namespace helios::spec::grammar

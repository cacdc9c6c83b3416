// The fact reader's epochs: calendar dates and day numbers on named scales, on the time scale they
// are written in, as TDB MJD2000.
#include <cctype>
#include <cmath>
#include <map>
#include <regex>
#include <string>

#include "fact_scan.hpp"
#include "facts.hpp"
#include "helios/astro/constants.hpp"
#include "helios/spec/units.hpp"

namespace helios::spec::detail {
namespace {

// Days from 2000-01-01 to the civil date y-m-d (proleptic Gregorian calendar).
double days_from_2000(int y, int m, int d) {
  y -= m <= 2;
  const int era = (y >= 0 ? y : y - 399) / 400;
  const int yoe = y - era * 400;
  const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return static_cast<double>(era) * 146097.0 + doe - 719468.0 - 10957.0;
}

int month_of(const std::string& word) {
  static const std::map<std::string, int> months = {
      {"january", 1},  {"jan", 1},    {"february", 2},  {"feb", 2},       {"march", 3},     {"mar", 3},
      {"april", 4},    {"apr", 4},    {"may", 5},       {"june", 6},      {"jun", 6},       {"july", 7},
      {"jul", 7},      {"august", 8}, {"aug", 8},       {"september", 9}, {"sep", 9},       {"sept", 9},
      {"october", 10}, {"oct", 10},   {"november", 11}, {"nov", 11},      {"december", 12}, {"dec", 12}};
  const auto it = months.find(lowercase(word));
  return it == months.end() ? 0 : it->second;
}

// The first and the last day of the years an epoch may lie in, as MJD2000.
const double kFirstEpoch = days_from_2000(kFirstEpochYear, 1, 1);
const double kEndOfEpochs = days_from_2000(kLastEpochYear + 1, 1, 1);

double civil_date(const std::string& text, int y, int m, int d) {
  static const int days_in[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (m < 1 || m > 12 || d < 1 || d > days_in[m - 1] ||
      (m == 2 && d == 29 && !(y % 4 == 0 && (y % 100 != 0 || y % 400 == 0))))
    throw facts_error("the date " + text + " does not exist");
  if (y < kFirstEpochYear || y > kLastEpochYear)
    throw facts_error("the date " + text + " lies outside the years 1900 to 2200");
  return days_from_2000(y, m, d);
}

// TAI - UTC [s] from the first day of each month in which it changed (IERS Bulletin C); no leap
// second has been announced since 2017, so later dates take 37 s.
struct LeapStep {
  int y, m;
  double tai_minus_utc;
};
constexpr LeapStep kLeapSteps[] = {
    {1972, 1, 10}, {1972, 7, 11}, {1973, 1, 12}, {1974, 1, 13}, {1975, 1, 14}, {1976, 1, 15}, {1977, 1, 16},
    {1978, 1, 17}, {1979, 1, 18}, {1980, 1, 19}, {1981, 7, 20}, {1982, 7, 21}, {1983, 7, 22}, {1985, 7, 23},
    {1988, 1, 24}, {1990, 1, 25}, {1991, 1, 26}, {1992, 7, 27}, {1993, 7, 28}, {1994, 7, 29}, {1996, 1, 30},
    {1997, 7, 31}, {1999, 1, 32}, {2006, 1, 33}, {2009, 1, 34}, {2012, 7, 35}, {2015, 7, 36}, {2017, 1, 37}};
constexpr double kTtMinusTai = 32.184;  // s

// An epoch on the scale `scale` (UTC, UT, GMT, Z, TAI, TT, TDB; "" is TDB) as TDB, MJD2000. UT
// (UT1) is read as UTC, which it follows within 0.9 s.
double as_tdb(double mjd2000, const std::string& scale, const std::string& text) {
  const std::string k = lowercase(scale);
  if (k.empty() || k == "tdb") return mjd2000;
  double tt = mjd2000;
  if (k == "utc" || k == "ut" || k == "gmt" || k == "z") {
    if (mjd2000 < days_from_2000(1972, 1, 1))
      throw facts_error("the epoch " + text +
                        " is in UTC before 1972, when UTC had no whole-second offset from TDB: give it in TDB");
    double tai_minus_utc = 0;
    for (const auto& step : kLeapSteps)
      if (mjd2000 >= days_from_2000(step.y, step.m, 1)) tai_minus_utc = step.tai_minus_utc;
    tt = mjd2000 + (tai_minus_utc + kTtMinusTai) / astro::DAY_S;
  } else if (k == "tai") {
    tt = mjd2000 + kTtMinusTai / astro::DAY_S;
  }
  // TDB - TT, the leading periodic terms [s] (Explanatory Supplement to the Astronomical Almanac)
  const double g = (357.53 + 0.98560028 * (tt - 0.5)) * astro::DEG_TO_RAD;
  return tt + (0.001657 * std::sin(g) + 0.000014 * std::sin(2 * g)) / astro::DAY_S;
}

}  // namespace

double day_number_epoch(const std::string& scale, double value, const std::string& text) {
  const std::string k = lowercase(scale);
  const double v = k == "mjd2000" ? value
                   : k == "mjd"   ? value - astro::MJD_MINUS_MJD2000
                                  : value - astro::JD_OF_MJD2000;
  if (!(v >= kFirstEpoch && v < kEndOfEpochs)) {
    const int year = static_cast<int>(std::floor(2000 + v / astro::JULIAN_YEAR_DAYS));
    throw facts_error("the epoch " + text + " falls in the year " + std::to_string(year) +
                      "; epochs lie in the years 1900 to 2200 (MJD2000 = MJD - 51544 = JD - 2451544.5)");
  }
  return v;
}

// An epoch written at the start of `rest`: a calendar date (2025-03-01 [00:00 UTC], 15 January
// 2030, March 3, 2028) or a day number on a named scale (MJD 60000, 9000 MJD2000, 10000 (MJD2000),
// JD 2460676.5), each with an optional time scale (TDB when none). Fills `q` (its MJD2000 in TDB)
// and returns the characters read, 0 when none.
std::size_t read_date(const std::string& rest, Quantity& q) {
  static const std::string n = R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)";
  static const std::string scale = R"((?: ?(UTC|UT|GMT|TDB|TT|TAI|Z)\b)?)";
  static const std::string clock = R"((\d{1,2}):(\d{2})(?::(\d{2}(?:\.\d+)?))?)";
  static const std::regex iso(R"(^(\d{4})-(\d{1,2})-(\d{1,2})(?:(?:T| at | ))" + clock + ")?" + scale,
                              std::regex::icase);
  static const std::regex dmy(R"(^(\d{1,2})(?:st|nd|rd|th)? ([A-Za-z]+)\.?,? (\d{4})\b(?:,? (?:at )?)" + clock + ")?" +
                              scale);
  static const std::regex mdy(R"(^([A-Za-z]+)\.? (\d{1,2})(?:st|nd|rd|th)?,? (\d{4})\b(?:,? (?:at )?)" + clock + ")?" +
                              scale);
  static const std::regex before("^(MJD2000|MJD|JD)\\b ?(" + n + ")" + scale, std::regex::icase);
  static const std::regex after("^(" + n + R"() ?(?:\( ?(MJD2000|MJD|JD) ?\)|(MJD2000|MJD|JD)\b))" + scale,
                                std::regex::icase);
  std::smatch m;
  // matched at the start only, never searched along the rest of the sentence
  constexpr auto kAtStart = std::regex_constants::match_continuous;
  const auto found = [&](double mjd2000, std::size_t scale_group) {
    q.texts = {m.str(0)};
    q.nums = {as_tdb(mjd2000, m[scale_group].str(), m.str(0))};
    return static_cast<std::size_t>(m.length(0));
  };
  // A calendar date with its time of day in groups 4 to 6, if any.
  const auto dated = [&](int y, int mo, int d) {
    double v = civil_date(m.str(0), y, mo, d);
    if (m[4].matched) {
      const int hh = std::stoi(m[4]), mm = std::stoi(m[5]);
      const double ss = m[6].matched ? std::stod(m[6]) : 0.0;
      if (hh > 23 || mm > 59 || ss >= 60) throw facts_error("the time of day in " + m.str(0) + " does not exist");
      v += (hh * 3600.0 + mm * 60.0 + ss) / astro::DAY_S;
    }
    return found(v, 7);
  };
  const char c = rest[0];
  if (std::isdigit(static_cast<unsigned char>(c))) {
    if (std::regex_search(rest, m, iso, kAtStart)) return dated(std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]));
    if (std::regex_search(rest, m, dmy, kAtStart) && month_of(m[2]) != 0)
      return dated(std::stoi(m[3]), month_of(m[2]), std::stoi(m[1]));
  }
  if (std::isalpha(static_cast<unsigned char>(c)) && std::regex_search(rest, m, mdy, kAtStart) && month_of(m[1]) != 0)
    return dated(std::stoi(m[3]), month_of(m[1]), std::stoi(m[2]));
  if (std::regex_search(rest, m, before, kAtStart)) return found(day_number_epoch(m[1], number_of(m[2]), m.str(0)), 3);
  if (std::regex_search(rest, m, after, kAtStart))
    return found(day_number_epoch(m[2].matched ? m[2] : m[3], number_of(m[1]), m.str(0)), 4);
  return 0;
}

}  // namespace helios::spec::detail

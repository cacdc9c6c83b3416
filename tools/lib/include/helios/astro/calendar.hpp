// Epochs for people: an MJD2000 day number (TDB) as an ISO 8601 calendar date, and a duration in
// the unit a reader of the problem would use.
//
// MJD2000 counts days from 2000-01-01T00:00:00 (MJD2000 = MJD - 51544, constants.hpp's
// JD_OF_MJD2000), the convention of the parser's dates and of the OEM's epochs: J2000.0
// (2000-01-01T12:00:00 TDB) is MJD2000 0.5. The time scale is TDB throughout; the date names it.
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace helios::astro {

// Year, month and day of a day count since 2000-01-01 (proleptic Gregorian; H. Hinnant's
// civil_from_days, shifted to start at 2000-01-01).
inline void civil_from_days_since_2000(long long days, long long& y, int& m, int& d) {
  const long long z = days + 730425;  // days from 0000-03-01 to 2000-01-01
  const long long era = (z >= 0 ? z : z - 146096) / 146097;
  const long long doe = z - era * 146097;
  const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const long long mp = (5 * doy + 2) / 153;
  d = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  m = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  y = yoe + era * 400 + (m <= 2 ? 1 : 0);
}

// MJD2000 (TDB) as "YYYY-MM-DDThh:mm:ss" (ISO 8601, rounded to the second; the scale is TDB).
// Throws std::invalid_argument for an epoch that is not finite or outside the years 0001-9999.
inline std::string iso_date_tdb(double mjd2000) {
  if (!std::isfinite(mjd2000) || mjd2000 < -730119.0 || mjd2000 >= 2921940.0)
    throw std::invalid_argument("epoch MJD2000 " + std::to_string(mjd2000) + " is outside the years 0001-9999");
  const long long seconds = std::llround(static_cast<long double>(mjd2000) * 86400.0L);
  const long long days = seconds >= 0 ? seconds / 86400 : -((-seconds + 86399) / 86400);
  const long long rest = seconds - days * 86400;
  long long year = 0;
  int month = 0, day = 0;
  civil_from_days_since_2000(days, year, month, day);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04lld-%02d-%02dT%02lld:%02lld:%02lld", year, month, day, rest / 3600,
                (rest / 60) % 60, rest % 60);
  return buf;
}

// Below this many days a duration reads better in hours (a GTO-to-GEO transfer of 0.6 d is 14.8 h).
inline constexpr double kHoursBelowDays = 3.0;

// A duration in days as the reader of the problem would say it: "14.80 h" below kHoursBelowDays,
// "348.8 days" above (digits after the point).
inline std::string duration_text(double days, int digits = 2) {
  char buf[64];
  if (std::fabs(days) < kHoursBelowDays)
    std::snprintf(buf, sizeof buf, "%.*f h", digits, days * 24);
  else
    std::snprintf(buf, sizeof buf, "%.*f days", digits, days);
  return buf;
}

}  // namespace helios::astro

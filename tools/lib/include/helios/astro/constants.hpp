#pragma once
// Physical and time constants. Units are part of every name. Standard library only: this
// header is also compiled into the shooting runtime (templates/runtime/runtime.cpp).

namespace helios::astro {

inline constexpr double PI = 3.141592653589793238462643383279502884;
inline constexpr double TWO_PI = 2.0 * PI;
inline constexpr double DEG_TO_RAD = PI / 180.0;

inline constexpr double MU_SUN_KM3_S2 = 1.32712440018e11;
inline constexpr double AU_KM = 149597870.691;  // pykep's value, kept for cross-checks
inline constexpr double G0_M_S2 = 9.80665;

inline constexpr double DAY_S = 86400.0;
inline constexpr double JULIAN_YEAR_DAYS = 365.25;
inline constexpr double JULIAN_CENTURY_DAYS = 36525.0;
inline constexpr double MJD_MINUS_MJD2000 = 51544.0;  // MJD2000 = MJD - 51544.0
inline constexpr double JD_OF_MJD2000 = 2451544.5;    // JD at MJD2000 = 0 (2000-01-01 00:00)
inline constexpr double JD_J2000 = 2451545.0;         // JD of the J2000.0 epoch (2000-01-01 12:00)

inline constexpr double MU_EARTH_KM3_S2 = 398600.4418;
inline constexpr double J2_EARTH = 1.08262668e-3;
inline constexpr double R_EARTH_KM = 6378.137;
inline constexpr double MU_MARS_KM3_S2 = 42828.3;
inline constexpr double R_MARS_KM = 3389.9;

}  // namespace helios::astro

#pragma once
// Physical quantities in problem texts: a number with a unit, converted to the spec's named unit.
#include <string>

namespace helios::spec {

// Time is stored in days (epochs, times of flight); Duration in seconds (specific impulse).
enum class Dimension { Length, Speed, Force, Time, Duration, Mass, GravParam, Acceleration, Angle, Power, MassFlow };

// Name of the unit the spec stores a dimension in (km, km/s, N, days, s, kg, km^3/s^2, mm/s^2, deg, W,
// kg/s).
std::string spec_unit(Dimension d);

// `text` in lower case (units and body names are matched case-insensitively).
std::string lowercase(const std::string& text);

// Factor converting one `unit` into the spec unit of `d`; throws std::invalid_argument
// "unit 'X' is not a <dimension> unit (use ...)" if the unit is unknown for that dimension.
double to_spec_unit(Dimension d, const std::string& unit);

}  // namespace helios::spec

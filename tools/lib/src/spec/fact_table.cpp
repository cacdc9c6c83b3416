// The table of facts: for each fact a problem text may state, its name in messages, where the spec
// keeps it, its dimension, the controlled sentence that states it and the check of its value. Both
// routes of the parser, the "missing fact" messages and the suggestions read it.
#include <map>
#include <stdexcept>

#include "facts.hpp"

namespace helios::spec::detail {

const FactInfo& fact_info(Field f) {
  using D = Dimension;
  static const std::map<Field, FactInfo> table = [] {
    std::map<Field, FactInfo> t;
    const auto add = [&](FactInfo info) { t.emplace(info.field, std::move(info)); };
    add({Field::Thrust, "the maximum thrust", "/spacecraft/thrust_N", D::Force,
         "The spacecraft has a maximum thrust of {}.", Check::Positive});
    add({Field::Isp, "the specific impulse", "/spacecraft/isp_s", D::Duration,
         "The spacecraft has a specific impulse of {}.", Check::Positive});
    add({Field::InitialMass, "the initial mass", "/spacecraft/initial_mass_kg", D::Mass,
         "The spacecraft has an initial mass of {}.", Check::Positive});
    add({Field::FinalMass, "the final mass", "/spacecraft/final_mass_kg", D::Mass,
         "The spacecraft has a final mass of {}.", Check::Positive});
    add({Field::Tof, "the time of flight", "/time/tof_days", D::Time, "The time of flight is {}.", Check::Positive});
    add({Field::TofMin, "the shortest time of flight", "/time/tof_min_days", D::Time, "", Check::NonNegative});
    add({Field::TofMax, "the longest time of flight", "/time/tof_max_days", D::Time,
         "The time of flight is free, at most {}.", Check::Positive});
    add({Field::T0, "the departure time", "/time/t0_days", D::Time, "", Check::None});
    add({Field::Tf, "the arrival time", "", D::Time, "", Check::None});
    add({Field::Epoch, "the departure epoch", "/time/epoch_mjd2000", D::Time, "", Check::None});
    add({Field::Mu, "the gravitational parameter", "/central_body/mu_km3_s2", D::GravParam,
         "The central body is the Sun with gravitational parameter {}.", Check::Positive});
    add({Field::R0, "the initial position", "", D::Length, "", Check::None});
    add({Field::V0, "the initial velocity", "", D::Speed, "", Check::None});
    add({Field::Rf, "the final position", "", D::Length, "", Check::None});
    add({Field::Vf, "the final velocity", "", D::Speed, "", Check::None});
    add({Field::Window, "the event's window", "", D::Time, "", Check::None});
    add({Field::DepartureWindow, "the departure window", "", D::Time, "", Check::None});
    add({Field::Stay, "the stay", "", D::Time, "", Check::NonNegative});
    add({Field::Drop, "the lander's mass", "", D::Mass, "", Check::Positive});
    add({Field::Rmin, "the lowest periapsis radius", "", D::Length, "", Check::Positive});
    add({Field::J2, "the J2 coefficient", "/central_body/j2", std::nullopt, "", Check::None});
    add({Field::Radius, "the central body's radius", "/central_body/radius_km", D::Length, "", Check::Positive});
    add({Field::CharAccel, "the sail's characteristic acceleration", "", D::Acceleration, "", Check::Positive});
    add({Field::Lightness, "the sail's lightness number", "", std::nullopt, "", Check::Positive});
    add({Field::A, "the semi-major axis", "", D::Length, "", Check::None});
    add({Field::Ecc, "the eccentricity", "", std::nullopt, "", Check::None});
    add({Field::Inc, "the inclination", "", D::Angle, "", Check::None});
    add({Field::Raan, "the ascending node", "", D::Angle, "", Check::None});
    add({Field::Argp, "the argument of perihelion", "", D::Angle, "", Check::None});
    add({Field::MeanAnomaly, "the mean anomaly", "", D::Angle, "", Check::None});
    add({Field::TrueAnomaly, "the true anomaly", "", D::Angle, "", Check::None});
    add({Field::ElementsEpoch, "the epoch of the elements", "", D::Time, "", Check::None});
    return t;
  }();
  return table.at(f);
}

std::string field_name(Field f) {
  return fact_info(f).name;
}

std::string spec_key(Field f) {
  const std::string& p = fact_info(f).spec_pointer;
  if (p.empty()) throw std::logic_error("the spec keeps " + fact_info(f).name + " in no single field");
  return p.substr(p.rfind('/') + 1);
}

std::string controlled_form(Field f, const std::string& value) {
  std::string form = fact_info(f).form;
  const std::size_t at = form.find("{}");
  return at == std::string::npos ? "" : form.replace(at, 2, value);
}

void check_value(Field f, double v, const std::string& written) {
  const FactInfo& info = fact_info(f);
  if (info.check == Check::Positive && !(v > 0)) throw facts_error(info.name + " must be positive, got " + written);
  if (info.check == Check::NonNegative && !(v >= 0))
    throw facts_error(info.name + " must not be negative, got " + written);
}

}  // namespace helios::spec::detail

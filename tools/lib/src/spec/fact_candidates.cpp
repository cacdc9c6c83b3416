// The facts in other words: the facts a phrase may name, the quantities that fit them, and the
// controlled sentences an error suggests.
#include "fact_reader.hpp"

#include <iomanip>
#include <sstream>

namespace helios::spec::detail {

// The facts of an event on the way and of an orbit.
bool on_the_way(Field f) {
  return f == Field::Window || f == Field::Stay || f == Field::Drop || f == Field::Rmin;
}

bool of_orbit(Field f) {
  return f == Field::A || f == Field::Ecc || f == Field::Inc || f == Field::Raan || f == Field::Argp ||
         f == Field::MeanAnomaly || f == Field::TrueAnomaly || f == Field::ElementsEpoch;
}

// How a Slot::Fact field's quantity is written: its dimension, or a number without unit.
Candidate fact_candidate(Field f) {
  const auto& dim = fact_info(f).dim;
  Candidate c{f, dim.value_or(Dimension::Length), false, false};
  c.pure = !dim;  // an eccentricity, a J2 coefficient, a lightness number
  return c;
}

std::vector<Candidate> candidates(const Meaning& m, int role, const std::string& text) {
  const Slot s = m.slot;
  const auto need_role = [&](Field initial, Field final_, Dimension d) -> std::vector<Candidate> {
    if (role == kNoRole) throw facts_error("'" + text + "' does not say whether it is the initial or the final one");
    return {{role == kInitial ? initial : final_, d, true, false}};
  };
  switch (s) {
    case Slot::Thrust:
      return {{Field::Thrust, Dimension::Force, false, false}};
    case Slot::ThrustOrT0:  // "t = Q": the departure time, or the arrival time in a clause of the arrival
      return {{Field::Thrust, Dimension::Force, false, false},
              {role == kFinal ? Field::Tf : Field::T0, Dimension::Time, false, false}};
    case Slot::T0:
      return {{Field::T0, Dimension::Time, false, false}, {Field::Epoch, Dimension::Time, false, false, true}};
    case Slot::Epoch:  // "the arrival date": the arrival time as a date
      return {{role == kFinal ? Field::Tf : Field::Epoch, Dimension::Time, false, false, true}};
    case Slot::Isp:
      return {{Field::Isp, Dimension::Duration, false, false}};
    case Slot::ExhaustV:
      return {{Field::Isp, Dimension::Speed, false, true}};
    case Slot::Mass:
      return {{role == kFinal ? Field::FinalMass : Field::InitialMass, Dimension::Mass, false, false}};
    case Slot::InitialMass:
      return {{Field::InitialMass, Dimension::Mass, false, false}};
    case Slot::FinalMass:
      return {{Field::FinalMass, Dimension::Mass, false, false}};
    case Slot::Tof:
      return {{Field::Tof, Dimension::Time, false, false}};
    case Slot::Mu:
      return {{Field::Mu, Dimension::GravParam, false, false}};
    case Slot::Position:
      return need_role(Field::R0, Field::Rf, Dimension::Length);
    case Slot::Velocity:
      return need_role(Field::V0, Field::Vf, Dimension::Speed);
    case Slot::R0:
      return {{Field::R0, Dimension::Length, true, false}};
    case Slot::V0:
      return {{Field::V0, Dimension::Speed, true, false}};
    case Slot::Rf:
      return {{Field::Rf, Dimension::Length, true, false}};
    case Slot::Vf:
      return {{Field::Vf, Dimension::Speed, true, false}};
    case Slot::Fact:
      return {fact_candidate(m.field)};
    case Slot::None:
      break;
  }
  return {};
}

bool fits(const Candidate& c, const Quantity& q) {
  if (c.vector != q.vector || c.date != q.date || c.window != q.window || q.day) return false;
  if (q.range && c.field != Field::Tof) return false;  // a range bounds a free time of flight, nothing else
  if (q.date || q.window) return true;
  // t = 0 needs no unit; an eccentricity, a J2 coefficient or a lightness number has none
  if (c.pure || q.unit.empty()) return q.unit.empty() && (c.pure || (c.field == Field::T0 && q.nums[0] == 0));
  try {
    to_spec_unit(c.dim, q.unit);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

// The controlled-English sentence stating `f` with the user's number (and unit, else the spec's).
std::string suggestion(Field f, const Quantity& q, Dimension d) {
  std::string unit = q.unit;
  try {
    if (!unit.empty()) to_spec_unit(d, unit);
  } catch (const std::invalid_argument&) {
    unit.clear();
  }
  if (unit.empty()) unit = spec_unit(d);
  return controlled_form(f, q.texts[0] + " " + unit);
}

// suggests the orbit sentence with the user's own numbers.
void check_elements(const SentenceFacts& out) {
  std::map<Field, const Fact*> got;
  for (const auto& f : out.facts) got[f.field] = &f;
  if (got.count(Field::Ecc) && !(got[Field::Ecc]->value[0] >= 0 && got[Field::Ecc]->value[0] < 1))
    throw facts_error("the eccentricity must satisfy 0 <= e < 1, got " + got[Field::Ecc]->written);
  if (got.count(Field::MeanAnomaly) && got.count(Field::TrueAnomaly))
    throw facts_error("it gives both a mean and a true anomaly: which one?");
  const Field anomaly = got.count(Field::TrueAnomaly) ? Field::TrueAnomaly : Field::MeanAnomaly;
  std::string missing;
  for (Field f : {Field::A, Field::Ecc, Field::Inc, Field::Raan, Field::Argp, anomaly, Field::ElementsEpoch})
    if (!got.count(f)) missing += (missing.empty() ? "" : ", ") + field_name(f);
  if (out.orbit_of.empty()) missing += (missing.empty() ? "" : ", ") + std::string("the body's name");
  if (missing.empty()) return;
  const auto w = [&](Field f, const char* none) { return got.count(f) ? got[f]->written : std::string(none); };
  std::ostringstream epoch;
  if (got.count(Field::ElementsEpoch))
    epoch << "MJD2000 " << std::setprecision(10) << got[Field::ElementsEpoch]->value[0];
  else
    epoch << "MJD N";  // the controlled form's placeholder
  throw facts_error("the orbit lacks " + missing,
                    (out.orbit_of.empty() ? "NAME" : out.orbit_of) +
                        " moves on a Keplerian orbit about the central body with a = " + w(Field::A, "Q") +
                        ", e = " + w(Field::Ecc, "N") + ", i = " + w(Field::Inc, "Q") +
                        ", node = " + w(Field::Raan, "Q") + ", argument of perihelion = " + w(Field::Argp, "Q") +
                        " and " + (anomaly == Field::TrueAnomaly ? "true" : "mean") + " anomaly = " + w(anomaly, "Q") +
                        " at " + epoch.str() + ".");
}

// The controlled sentence of an event, with the body the user named.
std::string event_form(const std::string& kind, const std::string& body) {
  const std::string name = body.empty() ? "NAME" : body;
  if (kind == "gravity_assist")
    return "The spacecraft swings by " + name + " between day N and day N in an unpowered gravity assist.";
  if (kind == "rendezvous") return "The spacecraft rendezvouses with " + name + " between day N and day N.";
  return "The spacecraft flies by " + name + " between day N and day N.";
}

std::string objective_of(int verb, int noun, int role, const std::string& words) {
  if (noun == kMass) noun = role == kFinal ? kFinalMass : role == kInitial ? kInitialMass : kMass;
  const bool min = verb == kMinimize || verb == kMinimum;
  if (noun == kNoNoun) throw facts_error("it does not say what to " + std::string(min ? "minimize" : "maximize"));
  if (noun == kMass) throw facts_error("'" + words + "' does not say which mass, the initial or the final one");
  if (min && noun == kFuel) return "minimum_fuel";
  if (!min && noun == kFinalMass) return "minimum_fuel";
  if (min && noun == kTime) return "minimum_time";
  if (min && noun == kInitialMass) return "minimum_initial_mass";
  throw facts_error("'" + words +
                    "' is no objective HELIOS solves (minimize the fuel, the time of flight or the initial mass, or "
                    "maximize the final mass)");
}

}  // namespace helios::spec::detail

#pragma once
// Facts read from a sentence the controlled English does not cover (internal to tools/lib/src/spec).
// A quantity scanner finds numbers and vectors with their units; a table of fact rules (words and
// synonyms -> spec field, expected dimension) places each quantity on the fact its clause names.
// Whatever cannot be placed exactly once, and without a choice, is an error: never a guess.
#include <array>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/spec/units.hpp"

namespace helios::spec::detail {

// The facts a sentence may state. TofMin and TofMax bound a free time of flight. Tf is the arrival time: on the
// problem's clock ("arrives at t = Q") or a date ("arrives on 2030-12-27", absolute). DepartureWindow is when the
// spacecraft may depart. Window, Stay, Drop and Rmin belong to an event on the way (its window, a stay, a lander, a
// lowest periapsis); J2 and Radius to the central body; CharAccel and Lightness to a solar sail; A to ElementsEpoch to
// a body's orbital elements (a in km, angles in deg).
enum class Field {
  Thrust,
  Isp,
  InitialMass,
  FinalMass,
  Tof,
  TofMin,
  TofMax,
  T0,
  Tf,
  Epoch,
  Mu,
  R0,
  V0,
  Rf,
  Vf,
  Window,
  DepartureWindow,
  Stay,
  Drop,
  Rmin,
  J2,
  Radius,
  CharAccel,
  Lightness,
  A,
  Ecc,
  Inc,
  Raan,
  Argp,
  MeanAnomaly,
  TrueAnomaly,
  ElementsEpoch
};

struct Fact {
  Field field;
  std::vector<double> value;       // one number (an epoch as MJD2000), or three for a vector, in the spec's unit
  std::string written;             // as written, e.g. "0.5 N"
  std::array<bool, 2> absolute{};  // a window's bounds or a date: MJD2000 (true) or days after the epoch (false)
};

struct SentenceFacts {
  std::vector<Fact> facts;
  std::string objective;                     // a spec objective kind ("minimum_fuel", ...) or ""
  std::string central;                       // the central body named ("Sun", "Earth", "Mars") or ""
  std::string departure_body, arrival_body;  // a planet the spacecraft leaves or rendezvouses with, or ""
  std::string constants_of;                  // the body whose gravitational parameter, radius or J2 it gives, or ""
  bool j2 = false;                           // it includes the J2 perturbation
  bool sail = false;                         // the spacecraft is a solar sail
  std::string orbit_of;  // the body whose orbital elements it gives (all six and their epoch), or ""
  // An event on the way: "flyby", "gravity_assist" or "rendezvous" with its window, or "stay" for
  // a stay or lander at a rendezvous stated before; its body as written, or "" ("the asteroid").
  std::string event, event_body;
  bool small_body = false;  // it calls the body "the asteroid" or "the comet": no planet
};

// Why a sentence cannot be read as facts; `suggestion` is the nearest controlled-English sentence
// filled in with the user's own numbers, or "".
struct facts_error : std::runtime_error {
  facts_error(const std::string& why, std::string suggest = "")
      : std::runtime_error(why), suggestion(std::move(suggest)) {}
  std::string suggestion;
  bool modifies_fact = false;  // an unknown word qualifies a fact word ("dry mass")
};

// True when the sentence names no fact, no body of `names` (as read_facts) and holds no number: it
// is not an attempt to state one.
bool states_nothing(const std::string& sentence, const std::map<std::string, std::string>& names);

// The facts of `sentence` (final period removed); `names` maps the lower-case names of the bodies
// the text has given so far to their names as written. Throws facts_error.
SentenceFacts read_facts(const std::string& sentence, const std::map<std::string, std::string>& names = {});

// ---- the table of facts (fact_table.cpp) -------------------------------------------------------

enum class Check { None, Positive, NonNegative };

struct FactInfo {
  Field field;
  std::string name;              // in messages and in "given twice": "the maximum thrust"
  std::string spec_pointer;      // where the spec keeps it, "" when not in one field of its own
  std::optional<Dimension> dim;  // none: a number without unit
  std::string form;              // the controlled sentence stating it, "{}" for the value, or ""
  Check check;
};

const FactInfo& fact_info(Field f);
// "the maximum thrust", "the initial position", ...: the name errors and `once` use.
std::string field_name(Field f);
// The last key of the fact's spec pointer ("thrust_N").
std::string spec_key(Field f);
// The controlled sentence stating `f` with `value` ("0.5 N"), or "" when it has none.
std::string controlled_form(Field f, const std::string& value);
// Throws facts_error when `v` fails the fact's check.
void check_value(Field f, double v, const std::string& written);

}  // namespace helios::spec::detail

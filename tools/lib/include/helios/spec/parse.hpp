#pragma once
// The builtin backend of helios-parse: a controlled English read sentence by sentence.
// The grammar is documented in tools/lib/src/spec/LANGUAGE.md; every sentence must match one
// of its forms, and one that does not is an error quoting it (never silently dropped).
//
// Bodies, epochs and events (Q = number with unit, N = number, NAME = [A-Za-z][A-Za-z0-9_]*):
//   NAME moves on a Keplerian orbit about the Sun with a = Q, e = N, i = Q, node = Q,
//     argument of perihelion = Q and mean anomaly = Q at MJD N.      (or true anomaly; MJD2000 N)
//   | body | a [AU] | e | i [deg] | node [deg] | argument of perihelion [deg] | mean anomaly [deg] | epoch [MJD] |
//   | Nikko | 2.2375176 | 0.1052183 | 5.70117 | 71.94548 | 2.08462 | 287.3844555 | 56800 |
//     (a table: a line starting with '|'; columns fixed, units km/AU, deg/rad, MJD/MJD2000 and
//     'true anomaly' may replace those in the header; an optional rule line |---|; an optional
//     sentence "The following bodies move on Keplerian orbits about the Sun with these elements:"
//     right before the header)
//   The spacecraft departs from TARGET at MJD2000 N.                 (or "departs at ... from TARGET")
//   The departure epoch is free between Q before and Q after MJD2000 N.   (or "within Q of MJD N")
//   The total time of flight is Q.
//   The spacecraft rendezvouses with NAME between day N and day N[, stays there for Q | does not
//     stay][ and leaves a lander of Q].                              (or "between MJD2000 N and MJD2000 N")
//   It leaves a lander of Q at NAME.
//   The spacecraft flies by NAME between day N and day N.
//   The spacecraft swings by NAME between day N and day N in an unpowered gravity assist; NAME has
//     a gravitational parameter of Q and the periapsis radius must be at least Q.
//   At the final time the spacecraft rendezvouses with NAME.
// A NAME is looked up after the whole text: a body given by its orbit becomes a target
// {"kind": "orbit", ...}, else Earth, Mars, Venus or Jupiter use the JPL low-precision ephemeris;
// anything else is an error at the sentence naming it. Days count from the epoch. Events get the
// ids lowercase(NAME) (then NAME_2, ...), are written in the text's order, and their windows must
// not overlap and must lie inside the flight. Constraints are written departure, events, arrival.
#include <cstddef>
#include <string>

#include "helios/io/json_io.hpp"

namespace helios::spec {

// Variables a user-written perturbing acceleration may use: position x, y, z and its norm r [km],
// velocity vx, vy, vz [km/s], mass m [kg], time t [s since departure].
inline constexpr const char* kAccelerationVariables[] = {"x", "y", "z", "r", "vx", "vy", "vz", "m", "t"};

// Bounds of a problem text (README "Limits"): beyond them the text is refused with one line naming
// the file, the line and the limit, before any pattern is matched (std::regex recurses per
// character, so an unbounded sentence would overflow the stack).
inline constexpr std::size_t kMaxProblemBytes = 1 << 20;  // the whole text
inline constexpr std::size_t kMaxSentenceChars = 4096;    // one sentence or one table line

// Reads a problem text into a spec artifact (header included). `source` names the file in errors:
// "<source>:<line>: cannot use sentence \"...\": <why>". Throws input_error, also for a text that is
// not UTF-8, holds a NUL or another control byte (tab, CR and LF aside), or exceeds a bound above.
io::json parse_problem_text(const std::string& text, const std::string& source);

// The encoding and bound checks alone (for a tool that shows a problem text without reading it):
// throws input_error as parse_problem_text does for such a text.
void check_problem_text(const std::string& text, const std::string& source);

}  // namespace helios::spec

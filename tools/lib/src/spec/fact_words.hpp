#pragma once
// The words of the facts in other words (internal to tools/lib/src/spec): what each phrase of a
// sentence may name (a fact, a role, an objective's verb or noun, a body, an event, a bound), in one
// table assembled by concern (fact_words.cpp: the engine and the mass; times, epochs and states;
// objectives, bodies and bounds; events, J2, sails and orbital elements).
#include <map>
#include <set>
#include <string>

#include "facts.hpp"

namespace helios::spec::detail {

// What a phrase of the sentence may name. A slot is a fact whose field may depend on the role
// (initial or final) the clause gives it.
enum class Slot {
  None,
  Thrust,
  Isp,
  ExhaustV,
  Mass,
  InitialMass,
  FinalMass,
  Tof,
  ThrustOrT0,
  T0,
  Epoch,
  Mu,
  Position,
  Velocity,
  R0,
  V0,
  Rf,
  Vf,
  Fact  // one field whatever the clause (Meaning::field): an event's, an orbit's, J2, a sail's
};
enum Role { kNoRole = 0, kInitial = 1, kFinal = 2 };
enum Verb { kNoVerb = 0, kMinimize, kMaximize, kMinimum, kMaximum };
enum Noun { kNoNoun = 0, kFuel, kTime, kFinalMass, kInitialMass, kMass };

struct Meaning {
  Slot slot;
  int role, verb, noun;
  bool bound;        // "up to", "limited to", "available", "maximum": a bound, which only the thrust is
  std::string body;  // a body with a known gravitational parameter
  bool central;      // names the central body ("central body", "heliocentric")
  // A weak fact word ("the 1500 kg spacecraft", "a 0.4 N engine"): it takes a quantity only when
  // no other fact word of its clause does, and needs none.
  bool weak = false;
  std::string event;            // an event on the way it names: "flyby" or "gravity_assist"
  bool lower = false;           // "at least", "minimum periapsis radius": a lower bound, which only the periapsis is
  bool named = false;           // a body the text gives by name (`body`), met only on the way
  std::string model;            // a part of the model it names: "j2" (the perturbation) or "sail"
  Field field = Field::Thrust;  // of Slot::Fact
  bool none = false;            // "no stay": the fact, with the value 0
  bool negation = false;        // "not", "no": a fact negated, which HELIOS does not read
  Meaning(Slot s = Slot::None, int r = kNoRole, int v = kNoVerb, int n = kNoNoun, bool b = false, std::string bd = "",
          bool c = false)
      : slot(s), role(r), verb(v), noun(n), bound(b), body(std::move(bd)), central(c) {}
};

using PhraseTable = std::map<std::string, Meaning>;

// The fact rules: words and synonyms, lower case, hyphens read as spaces. Words not listed are
// errors; listed with an empty meaning they are fillers that state nothing.
const PhraseTable& phrases();
constexpr std::size_t kMaxPhraseWords = 6;  // "right ascension of the ascending node"
// Every word of the phrases: a word outside them may be a body's name.
const std::set<std::string>& phrase_words();

// The words by concern (fact_words.cpp), added in this order (a later one may refine a word).
void engine_and_state_words(PhraseTable& t);
void objective_and_body_words(PhraseTable& t);
void event_words(PhraseTable& t);
void model_words(PhraseTable& t);

}  // namespace helios::spec::detail

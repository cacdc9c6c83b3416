// Facts read from a sentence the controlled English does not cover: the scanner's quantities
// (fact_scan.cpp) placed by a table of fact rules. The rule: a quantity belongs to the one fact
// its clause names whose dimension fits; anything else (no fact, two facts, a word that fits
// nowhere) is an error.
#include "facts.hpp"
#include "fact_scan.hpp"

#include <cctype>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "helios/spec/units.hpp"

namespace helios::spec::detail {
namespace {

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

// The fact rules: words and synonyms, lower case, hyphens read as spaces. Words not listed are
// errors; listed with an empty meaning they are fillers that state nothing.
const std::map<std::string, Meaning>& phrases() {
  static const std::map<std::string, Meaning> table = [] {
    std::map<std::string, Meaning> t;
    // fillers: they state nothing
    std::istringstream fillers(
        "the a an is are be of to with at from by for in its it system electric ion has have must should can set fixed "
        "equal equals given taken as assumed constant total level magnitude consumption used consumed objective goal "
        "vector state conditions we want find optimize optimise trajectory transfer mission operate operates possible "
        "reach looking use motion problem on place our single trip exactly body runs run carries carry hall "
        "take all computed frame only match matches equipped located scheduled expended spent solve occurs occur "
        "achieved");
    for (std::string w; fillers >> w;) t[w] = {};
    const auto slot = [&](std::initializer_list<const char*> ws, Slot s, int noun = kNoNoun) {
      for (const char* w : ws) t[w] = {s, kNoRole, kNoVerb, noun};
    };
    const auto fact = [&](std::initializer_list<const char*> ws, Field f) {
      for (const char* w : ws) {
        t[w] = {Slot::Fact};
        t[w].field = f;
      }
    };
    slot({"thrust", "maximum thrust", "max thrust", "delivers", "deliver", "provides", "provide", "produces", "produce",
          "gives", "give", "tmax", "t_max", "thrust force", "rated", "capable", "thrusts"},
         Slot::Thrust);
    // A force said of the engine is its thrust; a mass said of the spacecraft is its mass.
    for (const char* w : {"engine", "engines", "thruster", "thrusters", "propulsion"}) {
      t[w] = {Slot::Thrust};
      t[w].weak = true;
    }
    for (const char* w : {"spacecraft", "probe", "vehicle", "starts with"}) {
      t[w] = {Slot::Mass, std::string(w) == "starts with" ? kInitial : kNoRole};
      t[w].weak = true;
    }
    slot({"t"}, Slot::ThrustOrT0);
    slot({"t0", "t_0"}, Slot::T0);
    t["takes place"] = {};
    t["low thrust"] = {};  // a kind of engine, not a thrust value
    t["two body"] = {};
    slot({"epoch", "date", "departure epoch", "departure date", "launch date", "launch epoch", "start date",
          "start epoch", "initial epoch", "epoch of departure", "date of departure"},
         Slot::Epoch);
    slot({"specific impulse", "isp", "i_sp"}, Slot::Isp);
    slot({"exhaust velocity", "effective exhaust velocity", "exhaust speed"}, Slot::ExhaustV);
    slot({"mass", "weighs", "weigh"}, Slot::Mass, kMass);
    slot({"initial mass", "wet mass", "launch mass", "starting mass", "m0", "m_0"}, Slot::InitialMass, kInitialMass);
    slot({"final mass"}, Slot::FinalMass, kFinalMass);
    slot({"time of flight", "flight time", "transfer time", "tof", "takes", "lasts", "duration", "transfer duration",
          "flight duration", "after departure", "after it departs", "after departing", "after launch",
          "after it leaves", "after leaving", "after the departure", "after the launch"},
         Slot::Tof, kTime);
    slot({"mu", "gm", "gravitational parameter", "gravitational constant"}, Slot::Mu);
    slot({"position", "location", "r"}, Slot::Position);
    slot({"velocity", "v"}, Slot::Velocity);
    slot({"r0", "r_0"}, Slot::R0);
    slot({"v0", "v_0"}, Slot::V0);
    slot({"rf", "r_f"}, Slot::Rf);
    slot({"vf", "v_f"}, Slot::Vf);
    for (const char* w : {"initial", "initially", "start", "starts", "starting", "begins", "departs", "departure",
                          "launch", "leaves", "launched", "time zero"})
      t[w] = {Slot::None, kInitial};
    for (const char* w : {"final", "arrives", "arrive", "arrival", "end", "ends", "terminal", "rendezvous",
                          "rendezvouses", "destination", "target"})
      t[w] = {Slot::None, kFinal};
    for (const char* w : {"minimize", "minimise", "minimized", "minimised", "cost", "cost function", "as little"})
      t[w] = {Slot::None, kNoRole, kMinimize};
    for (const char* w : {"maximize", "maximise", "maximized", "maximised", "as large as possible"})
      t[w] = {Slot::None, kNoRole, kMaximize};
    t["minimum"] = {Slot::None, kNoRole, kMinimum};
    t["maximum"] = t["max"] = {Slot::None, kNoRole, kMaximum, kNoNoun, true};
    for (const auto& [w, b] : std::map<std::string, std::string>{
             {"sun", "Sun"}, {"earth", "Earth"}, {"mars", "Mars"}, {"venus", "Venus"}, {"jupiter", "Jupiter"}})
      t[w].body = b;
    // the central body: what the spacecraft orbits, the one that attracts it
    for (const char* w : {"central body", "gravitational attractor", "attractor", "attracting body", "orbits"})
      t[w].central = true;
    for (const char* w : {"heliocentric", "sun centered", "sun centred"})
      t[w] = {Slot::None, kNoRole, kNoVerb, kNoNoun, false, "Sun", true};
    for (const char* w : {"geocentric", "earth centered", "earth centred", "eci"})
      t[w] = {Slot::None, kNoRole, kNoVerb, kNoNoun, false, "Earth", true};
    // a body's own gravitational parameter ("GM_sun = Q")
    for (const auto& [w, b] : std::map<std::string, std::string>{
             {"gm_sun", "Sun"}, {"mu_sun", "Sun"}, {"gm_earth", "Earth"}, {"mu_earth", "Earth"}})
      t[w] = {Slot::Mu, kNoRole, kNoVerb, kNoNoun, false, b};
    t["near earth asteroid"] = {};  // a kind of asteroid, not the Earth
    for (const char* w : {"up", "up to", "limited", "available", "most", "at most", "no more than", "not more than",
                          "not exceeding", "not to exceed", "no greater than", "not greater than", "at the most"})
      t[w] = {Slot::None, kNoRole, kNoVerb, kNoNoun, true};
    for (const char* w : {"fuel", "propellant", "fuel consumption", "propellant consumption", "fuel mass",
                          "propellant mass", "fuel use", "mass of propellant", "mass of fuel", "mass of the propellant",
                          "mass of the fuel", "propellant used", "fuel used"})
      t[w] = {Slot::None, kNoRole, kNoVerb, kFuel};
    for (const char* w : {"time", "final time"}) t[w] = {Slot::None, kNoRole, kNoVerb, kTime};
    for (const char* w : {"fuel optimal", "propellant optimal"}) t[w] = {Slot::None, kNoRole, kMinimize, kFuel};
    for (const char* w : {"time optimal", "fastest", "quickest", "as fast as possible", "as short as possible"})
      t[w] = {Slot::None, kNoRole, kMinimize, kTime};
    // events on the way: the event words, their stays, landers and periapsis bounds
    for (const char* w : {"flyby", "flybys", "fly by", "flies by", "fly past", "flies past", "passes", "pass"})
      t[w].event = "flyby";
    for (const char* w : {"gravity assist", "swing by", "swings by", "swingby", "unpowered"})
      t[w].event = "gravity_assist";
    for (const char* w : {"asteroid", "comet", "there", "then", "close", "planned", "somewhere", "required", "window",
                          "free", "uses", "include", "includes", "manoeuvre", "maneuver"})
      t[w] = {};
    fact({"stay", "stays", "stay time", "stay duration", "residence time", "remains", "remain", "waits", "wait",
          "spends", "spend", "surface stay"},
         Field::Stay);
    fact({"lander", "drops", "drop", "releases", "released", "release"}, Field::Drop);
    fact({"periapsis radius", "periapsis", "flyby radius", "pericenter radius", "pericentre radius", "closest approach",
          "rp"},
         Field::Rmin);
    for (const char* w : {"minimum periapsis radius", "minimum flyby radius", "min periapsis radius", "minimum radius",
                          "lowest periapsis radius"}) {
      fact({w}, Field::Rmin);
      t[w].lower = true;
    }
    for (const char* w : {"least", "at least", "no less than", "not less than", "no fewer than"}) t[w].lower = true;
    fact({"no stay", "does not stay"}, Field::Stay);
    t["no stay"].none = t["does not stay"].none = true;
    t["immediately"] = {};
    // a negation the phrases above do not hold ("no stay", "no more than") negates a fact
    for (const char* w : {"not", "no", "never", "without", "neither", "nor", "cannot", "doesn't", "don't", "isn't"})
      t[w].negation = true;
    // the J2 perturbation ("j2" alone with a number is the coefficient), the central body's radius
    for (const char* w : {"j2 perturbation", "j2 term", "j2 effect", "oblateness", "zonal harmonic j2",
                          "zonal harmonic", "j2 zonal harmonic"})
      t[w].model = "j2";
    fact({"j2 coefficient", "j2"}, Field::J2);
    t["j2"].weak = true;
    fact({"radius", "equatorial radius"}, Field::Radius);
    for (const char* w : {"solar sail", "sail", "solar sails"}) t[w].model = "sail";
    fact({"characteristic acceleration", "a_c", "ac"}, Field::CharAccel);
    fact({"lightness number", "lightness", "lightness parameter"}, Field::Lightness);
    for (const char* w : {"included", "dynamics", "plus", "account", "into", "model", "force", "propelled", "ideal",
                          "flat", "perfectly", "reflecting", "instead"})
      t[w] = {};
    // orbital elements ("a = Q", "e = N", "i = Q", "M = Q", "nu = Q", "Omega = Q", "omega = Q" too: scan())
    fact({"semi major axis", "semimajor axis"}, Field::A);
    fact({"eccentricity"}, Field::Ecc);
    fact({"inclination"}, Field::Inc);
    fact({"raan", "node", "ascending node", "longitude of the ascending node", "right ascension of the ascending node"},
         Field::Raan);
    fact(
        {"argp", "argument of perihelion", "argument of periapsis", "argument of pericenter", "argument of pericentre"},
        Field::Argp);
    fact({"mean anomaly"}, Field::MeanAnomaly);
    fact({"true anomaly"}, Field::TrueAnomaly);
    for (const char* w : {"elements", "orbital elements", "keplerian", "orbit", "orbital", "defined"}) t[w] = {};
    return t;
  }();
  return table;
}

constexpr std::size_t kMaxPhraseWords = 6;  // "right ascension of the ascending node"

// A candidate reading of a quantity: a field, the dimension it takes, whether it is a vector.
struct Candidate {
  Field field;
  Dimension dim;
  bool vector;
  bool exhaust;         // an exhaust velocity, stored as the specific impulse
  bool date = false;    // takes an epoch
  bool window = false;  // takes a window
  bool pure = false;    // takes a number without unit
};

constexpr double kG0 = 9.80665;  // m/s^2, exhaust velocity = Isp * g0

// A phrase found in a clause, with the words as written.
struct Mention {
  Meaning meaning;
  std::string text;
  bool on_quantity = false;  // a bound word written just before a quantity: it bounds that quantity
};

facts_error negation_error(const std::string& word) {
  return facts_error("'" + word +
                     "' negates what follows it: HELIOS reads facts stated as they are, never their negation");
}

// A word that states nothing ("the", "of", "to").
bool filler(const Meaning& m) {
  return m.slot == Slot::None && m.role == kNoRole && m.verb == kNoVerb && m.noun == kNoNoun && !m.bound &&
         m.body.empty() && !m.central && m.event.empty() && !m.lower && !m.named && m.model.empty() && !m.negation;
}

// A bound word ("at most", "up to", "at least") with only fillers between it and the quantity
// after it bounds that quantity.
void mark_bound(std::vector<Mention>& mentions, std::size_t from, Quantity& q) {
  for (std::size_t k = mentions.size(); k > from; --k) {
    Mention& m = mentions[k - 1];
    if (filler(m.meaning)) continue;
    if (m.meaning.bound || m.meaning.lower) {
      m.on_quantity = true;
      q.at_most = m.meaning.bound;
      q.at_least = m.meaning.lower;
      q.bound_words = m.text;
    }
    return;
  }
}

struct Clause {
  std::vector<Mention> mentions;
  std::vector<Quantity> quantities;
};

// Words into the longest phrases of the table; an unknown word is an error.
std::vector<Clause> clauses_of(const std::vector<Token>& tokens, const std::map<std::string, std::string>& names) {
  std::vector<Clause> out(1);
  std::vector<std::string> words;
  bool after_bare_number = false;  // the words follow a number without a unit
  std::size_t flushed_from = 0;    // the first mention of the words flushed last
  const auto flush = [&] {
    const auto& table = phrases();
    flushed_from = out.back().mentions.size();
    for (std::size_t i = 0; i < words.size();) {
      std::size_t len = std::min(kMaxPhraseWords, words.size() - i);
      for (; len > 0; --len) {
        std::string phrase = words[i];
        for (std::size_t k = 1; k < len; ++k) phrase += " " + words[i + k];
        const auto it = table.find(phrase);
        if (it != table.end()) {
          out.back().mentions.push_back({it->second, phrase});
          break;
        }
      }
      if (len == 0 && names.count(words[i])) {  // a body the text gives by name
        Meaning m;
        m.body = names.at(words[i]);
        m.named = true;
        out.back().mentions.push_back({m, words[i]});
        ++i;
        continue;
      }
      if (len == 0) {
        if (i == 0 && after_bare_number)
          throw facts_error("'" + words[i] + "' after " + out.back().quantities.back().written +
                            " is no unit HELIOS knows and no fact word");
        // a word before a fact word modifies it ("dry mass"): no form can be suggested
        bool modifies = false;
        for (std::size_t len2 = 1; i + len2 < words.size() && len2 <= kMaxPhraseWords && !modifies; ++len2) {
          std::string next = words[i + 1];
          for (std::size_t k = 1; k < len2; ++k) next += " " + words[i + 1 + k];
          const auto it = table.find(next);
          modifies = it != table.end() && it->second.slot != Slot::None;
        }
        facts_error e("cannot place the word '" + words[i] + "'");
        e.modifies_fact = modifies;
        throw e;
      }
      i += len;
    }
    words.clear();
  };
  for (const auto& t : tokens) {
    if (t.kind == Token::Word) {
      words.push_back(t.word);
      continue;
    }
    flush();
    after_bare_number = t.kind == Token::Value && t.q.unit.empty();
    if (t.kind == Token::Value) {
      out.back().quantities.push_back(t.q);
      mark_bound(out.back().mentions, flushed_from, out.back().quantities.back());
    }
    if (t.kind == Token::Separator && (!out.back().mentions.empty() || !out.back().quantities.empty()))
      out.emplace_back();
  }
  flush();
  if (out.back().mentions.empty() && out.back().quantities.empty()) out.pop_back();
  return out;
}

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

// Every word of the fact rules' phrases: a word outside them may be a body's name.
const std::set<std::string>& phrase_words() {
  static const std::set<std::string> words = [] {
    std::set<std::string> w;
    for (const auto& [phrase, _] : phrases()) {
      std::istringstream in(phrase);
      for (std::string x; in >> x;) w.insert(x);
    }
    return w;
  }();
  return words;
}

// A body's orbital elements are all six, one anomaly, their epoch and the body; else the error
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

}  // namespace

bool states_nothing(const std::string& sentence, const std::map<std::string, std::string>& names) {
  static const std::regex digit("[0-9]");
  if (std::regex_search(sentence, digit)) return false;
  std::vector<Token> tokens;
  try {
    tokens = scan(sentence);
  } catch (const facts_error&) {
    return true;
  }
  const auto& table = phrases();
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i].kind != Token::Word) continue;
    if (names.count(tokens[i].word)) return false;
    std::string phrase;
    for (std::size_t k = i; k < tokens.size() && k < i + kMaxPhraseWords && tokens[k].kind == Token::Word; ++k) {
      phrase += (k == i ? "" : " ") + tokens[k].word;
      const auto it = table.find(phrase);
      const Meaning& mean = it == table.end() ? Meaning{} : it->second;
      if ((mean.slot != Slot::None && !mean.weak) || mean.verb != kNoVerb || !mean.body.empty() || mean.central ||
          !mean.event.empty() || !mean.model.empty() || mean.negation)
        return false;
    }
  }
  return true;
}

// For a sentence with a word that fits nowhere: the controlled form of its one scalar fact, if the
// sentence names exactly one and holds exactly one number.
std::string rough_suggestion(const std::vector<Token>& tokens) {
  std::set<Field> fields;
  std::vector<Candidate> cands;
  const Quantity* number = nullptr;
  int numbers = 0;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    if (tokens[i].kind == Token::Value) {
      ++numbers;
      const Quantity& q = tokens[i].q;
      if (!q.vector && !q.date && !q.day && !q.window) number = &q;  // a plain number only
    }
    if (tokens[i].kind != Token::Word) continue;
    std::string phrase;
    for (std::size_t len = 1; len <= kMaxPhraseWords && i + len <= tokens.size(); ++len) {
      if (tokens[i + len - 1].kind != Token::Word) break;
      phrase += (len == 1 ? "" : " ") + tokens[i + len - 1].word;
      const auto it = phrases().find(phrase);
      if (it == phrases().end()) continue;
      const Slot sl = it->second.slot;
      const bool named_fact = sl == Slot::Thrust || sl == Slot::Isp || sl == Slot::Mass || sl == Slot::InitialMass ||
                              sl == Slot::FinalMass || sl == Slot::Tof || sl == Slot::Mu;
      if (named_fact && !it->second.weak)  // "spacecraft" or "engine" alone suggests nothing
        for (const auto& c : candidates(it->second, kNoRole, phrase))
          if (fields.insert(c.field).second) cands.push_back(c);
    }
  }
  if (cands.size() != 1 || numbers != 1 || !number) return "";
  if (cands[0].exhaust) return "";
  return suggestion(cands[0].field, *number, cands[0].dim);
}

namespace {

// A fact word of a clause, the facts it may name and whether a quantity took it.
struct Named {
  std::vector<Candidate> cands;
  std::string text;
  bool weak;
  bool bound = false;
  bool none = false;
};

// What a clause's words say besides its quantities: its role (from the clause, else the
// sentence), the role of its own words, an objective's verb and nouns, and the words as read.
struct ClauseWords {
  int role = kNoRole, clause_role = kNoRole, verb = kNoVerb;
  std::set<int> nouns;
  std::string words;
};

// One sentence read as facts, stage by stage: its clauses, the kind of sentence, the bodies it
// names, each clause's facts, then the checks of the whole.
class SentenceReader {
 public:
  SentenceReader(const std::string& sentence, const std::map<std::string, std::string>& known_names)
      : names(known_names), tokens(scan(sentence)) {}

  SentenceFacts read() {
    read_clauses();
    find_kind();
    place_bodies();
    place_role_bodies();
    for (const auto& c : clauses) read_clause(c);
    check_kind();
    check_values();
    return out;
  }

 private:
  const std::map<std::string, std::string>& names;
  std::vector<Token> tokens;
  std::vector<Clause> clauses;
  SentenceFacts out;
  std::set<int> sentence_roles;
  std::set<std::string> bodies;
  bool elements = false, central_named = false, central_unnamed = false, event_sentence = false,
       rendezvous_word = false;
  std::string event_kind, unplaced, objective_words;

  void add(const Fact& fact) {
    for (const auto& f : out.facts)
      if (f.field == fact.field)
        throw facts_error(field_name(fact.field) + " is stated twice: " + f.written + " and " + fact.written);
    out.facts.push_back(fact);
  }

  // The clauses, with a body named for the first time by orbital elements or an event's window.
  void read_clauses() {
    // Orbital elements, and an event with its window, may name their body for the first time, as the
    // one word written with a capital that is no fact word ("Nikko's orbital elements ...").
    bool window = false;
    for (const auto& t : tokens) {
      const auto it = phrases().find(t.word);
      elements = elements || (t.kind == Token::Word && it != phrases().end() &&
                              ((it->second.slot == Slot::Fact && of_orbit(it->second.field)) || t.word == "elements"));
      window = window || (t.kind == Token::Value && t.q.window);
    }
    std::map<std::string, std::string> known = names;
    if (elements || window) {
      std::set<std::string> fresh;
      for (const auto& t : tokens)
        if (t.kind == Token::Word && std::isupper(static_cast<unsigned char>(t.text[0])) && !phrases().count(t.word) &&
            !phrase_words().count(t.word) && !names.count(t.word))
          fresh.insert(t.text);
      if (fresh.size() == 1) known[lowercase(*fresh.begin())] = *fresh.begin();
    }
    try {
      clauses = clauses_of(tokens, known);
    } catch (const facts_error& e) {
      // a word it cannot place beside a negation: the negation is the reason
      for (const auto& t : tokens) {
        const auto it = phrases().find(t.word);
        if (t.kind == Token::Word && it != phrases().end() && it->second.negation) throw negation_error(t.text);
      }
      throw facts_error(e.what(), e.modifies_fact ? "" : rough_suggestion(tokens));
    }
    for (const auto& c : clauses)
      for (const auto& m : c.mentions)
        if (m.meaning.negation) throw negation_error(m.text);
  }

  // Which roles, bodies and events the sentence speaks of.
  void find_kind() {
    for (const auto& c : clauses)
      for (const auto& m : c.mentions)
        if (m.meaning.role != kNoRole) sentence_roles.insert(m.meaning.role);
    // The central body: a known body and a word saying it is the central one, once in the sentence.
    for (const auto& c : clauses)
      for (const auto& m : c.mentions) {
        if (!m.meaning.body.empty()) bodies.insert(m.meaning.body);
        central_named = central_named || m.meaning.central;
      }
    // An event on the way: its words, a stay, a lander, a periapsis bound, a day or a window. Its body
    // is the one body the sentence names, if any ("the asteroid"); a body named without them is left
    // or reached, like a planet.
    for (const auto& c : clauses) {
      for (const auto& m : c.mentions) {
        if (!m.meaning.event.empty() && event_kind != "gravity_assist") event_kind = m.meaning.event;
        event_sentence =
            event_sentence || !m.meaning.event.empty() || (m.meaning.slot == Slot::Fact && on_the_way(m.meaning.field));
        rendezvous_word = rendezvous_word || m.text == "rendezvous" || m.text == "rendezvouses" ||
                          m.text == "arrives" || m.text == "arrive";
        out.small_body = out.small_body || m.text == "asteroid" || m.text == "comet";
      }
      for (const auto& q : c.quantities) event_sentence = event_sentence || q.window || q.day;
    }
  }

  // The body of orbital elements or of an event on the way.
  void place_bodies() {
    if (elements && event_sentence)
      throw facts_error("it gives orbital elements and an event on the way: state the event in a sentence of its own");
    if (elements) {  // the body orbiting, and the Sun it orbits (which must be the central body)
      if (bodies.count("Sun")) out.constants_of = "Sun";
      bodies.erase("Sun");
      if (bodies.size() > 1)
        throw facts_error("it names " + *bodies.begin() + " and " + *bodies.rbegin() + ": whose elements are these?");
      if (!bodies.empty()) out.orbit_of = *bodies.begin();
      bodies.clear();
    }
    if (event_sentence) {
      if (central_named) throw facts_error("it names the central body and an event on the way: state them apart");
      if (bodies.size() > 1)
        throw facts_error("it names " + *bodies.begin() + " and " + *bodies.rbegin() + ": which one is the event at?");
      if (bodies.count("Sun")) throw facts_error("the Sun is the central body, not a body to visit on the way");
      if (!bodies.empty()) out.event_body = *bodies.begin();
      bodies.clear();
    }
  }

  // A planet left or reached, else the central body or the one whose constants it gives.
  void place_role_bodies() {
    // Else a planet in a clause that says the spacecraft leaves or arrives is the body it departs
    // from or rendezvouses with ("Departure from Earth.", "Rendezvous with Mars.").
    if (!bodies.empty() && !central_named && !sentence_roles.empty() && !event_sentence) {
      for (const auto& c : clauses)
        for (const auto& m : c.mentions)
          if (m.text == "orbit" || m.text == "orbital")
            throw facts_error(
                "it names an orbit, not the body on it: HELIOS reads a departure from or a rendezvous "
                "with a body ('At the final time the spacecraft rendezvouses with " +
                *bodies.begin() + ".'); a target that is a whole orbit is not a fact it reads yet");
      for (const auto& c : clauses) {
        std::set<int> roles;
        for (const auto& m : c.mentions)
          if (m.meaning.role != kNoRole) roles.insert(m.meaning.role);
        if (roles.empty() && sentence_roles.size() == 1) roles = sentence_roles;
        for (const auto& m : c.mentions) {
          const std::string& b = m.meaning.body;
          if (b.empty()) continue;
          if (roles.size() != 1)
            throw facts_error("'" + b + "' could be the departure or the arrival body: say which in its clause");
          if (b == "Sun")
            throw facts_error("the spacecraft cannot " + std::string(*roles.begin() == kInitial ? "leave" : "reach") +
                              " the Sun; the central body reads 'The central body is the Sun.'");
          std::string& slot = *roles.begin() == kInitial ? out.departure_body : out.arrival_body;
          const char* which = *roles.begin() == kInitial ? "departure" : "arrival";
          if (!slot.empty() && slot != b)
            throw facts_error("it names " + slot + " and " + b + " as the " + which + " body: which one?");
          slot = b;
        }
      }
      bodies.clear();
    }
    if (bodies.size() > 1)
      throw facts_error("it names " + *bodies.begin() + " and " + *bodies.rbegin() +
                        ": which one is the central body?");
    // A body named with no word saying it is the central one: its gravitational parameter, if the
    // sentence gives one ("The Sun's gravitational parameter is Q"), checked below.
    unplaced = !bodies.empty() && !central_named ? *bodies.begin() : "";
    // "The gravitational parameter of the central body is Q": a constant of the central body named elsewhere
    central_unnamed = bodies.empty() && central_named && !elements;
    if (!bodies.empty() && central_named) out.central = *bodies.begin();
  }

  ClauseWords words_of(const Clause& c) const {
    ClauseWords w;
    std::set<int> roles;
    for (const auto& m : c.mentions) {
      if (m.meaning.role != kNoRole) roles.insert(m.meaning.role);
      if (m.meaning.verb != kNoVerb) w.verb = m.meaning.verb;
      if (m.meaning.noun != kNoNoun) w.nouns.insert(m.meaning.noun);
      w.words += (w.words.empty() ? "" : " ") + m.text;
    }
    if (roles.size() > 1) throw facts_error("'" + w.words + "' names both the initial and the final state");
    w.role = roles.empty() ? kNoRole : *roles.begin();
    // "At t = 0 the spacecraft is at position ...": the time 0 makes the clause the departure's
    if (w.role == kNoRole && sentence_roles.empty()) {
      bool time_mention = false;
      for (const auto& m : c.mentions)
        time_mention = time_mention || m.meaning.slot == Slot::ThrustOrT0 || m.meaning.slot == Slot::T0;
      for (const auto& q : c.quantities)
        if (time_mention && !q.vector && !q.date && !q.window && q.nums[0] == 0 &&
            (q.unit.empty() || fits({Field::T0, Dimension::Time, false, false}, q)))
          w.role = kInitial;
    }
    w.clause_role = w.role;
    if (w.role == kNoRole && sentence_roles.size() == 1) w.role = *sentence_roles.begin();
    return w;
  }

  // An objective: a verb and what it applies to, no quantity. False when the clause is none.
  bool read_objective(const Clause& c, const ClauseWords& w) {
    if (!c.quantities.empty() || w.verb == kNoVerb) return false;
    for (const auto& m : c.mentions)
      if (m.meaning.slot != Slot::None && m.meaning.noun == kNoNoun && !m.meaning.weak)
        throw facts_error("'" + m.text +
                          "' cannot be an objective (minimize the fuel, the time of flight or the "
                          "initial mass, or maximize the final mass)");
    if (w.nouns.size() > 1) throw facts_error("'" + w.words + "' names more than one thing to optimize");
    const std::string kind = objective_of(w.verb, w.nouns.empty() ? kNoNoun : *w.nouns.begin(), w.clause_role, w.words);
    if (!out.objective.empty())
      throw facts_error("it states two objectives (" + objective_words + "; " + w.words + "): choose one");
    out.objective = kind;
    objective_words = w.words;
    return true;
  }

  // Bound words that make a fact word a bound, not a value; a periapsis radius that is one.
  void check_bounds(const Clause& c, const ClauseWords& w) const {
    if (w.verb == kMinimum || w.verb == kMinimize || w.verb == kMaximize)
      throw facts_error("'" + w.words + "' mixes an objective with a value");
    // A bound on the thrust is the maximum thrust; a bound on anything else is not a value.
    for (const auto& m : c.mentions)
      for (const auto& n : c.mentions)
        if (m.meaning.bound && !m.on_quantity && n.meaning.slot != Slot::None && n.meaning.slot != Slot::Thrust &&
            !n.meaning.weak)
          throw facts_error("'" + m.text + "' makes '" + n.text + "' a bound, not a value" +
                            (n.meaning.slot == Slot::Tof
                                 ? " (a bounded time of flight reads 'The time of flight is free, at most Q.')"
                                 : ""));
    // The periapsis radius is a lower bound, and only it is.
    bool lower = false, rmin = false;
    for (const auto& m : c.mentions) {
      lower = lower || m.meaning.lower;
      const auto is_rmin = [](const Meaning& x) { return x.slot == Slot::Fact && x.field == Field::Rmin; };
      rmin = rmin || is_rmin(m.meaning);
      if (m.meaning.lower && !m.on_quantity && !is_rmin(m.meaning))
        for (const auto& n : c.mentions)
          if (n.meaning.slot != Slot::None && !is_rmin(n.meaning) && !n.meaning.weak)
            throw facts_error("'" + m.text + "' makes '" + n.text + "' a lower bound, not a value");
    }
    if (rmin && !lower)
      throw facts_error("'" + w.words +
                        "' gives a periapsis radius, which HELIOS takes as a lower bound: say 'a minimum periapsis "
                        "radius of Q' or 'the periapsis radius is at least Q'");
  }

  void check_time_of_flight(const Clause& c, const ClauseWords& w) const {
    // A time of flight is the flight's: not the engine's or the propellant's life, and counted from
    // the departure.
    for (const auto& m : c.mentions) {
      if (m.meaning.slot != Slot::Tof || event_sentence) continue;
      for (const auto& n : c.mentions) {
        if ((n.meaning.weak && n.meaning.slot == Slot::Thrust) || n.meaning.noun == kFuel)
          throw facts_error("'" + m.text + "' is said of the '" + n.text +
                            "', not of the flight: the time of flight reads 'The time of flight is Q.'");
        if (n.text == "window")
          throw facts_error("'" + w.words +
                            "' counts the time from the departure window, not from the departure: HELIOS reads the "
                            "time of flight from the departure ('The time of flight is Q.')");
      }
    }
  }

  // The clause's fact words with what each may name: a date and a window named by the clause.
  std::vector<Named> fact_words(const Clause& c, const ClauseWords& w) const {
    std::vector<Named> named;
    for (const auto& m : c.mentions)
      if (m.meaning.slot != Slot::None) {
        const Slot s = m.meaning.slot;
        // on the way, "epoch" and "date" name the event's, "lasts" and "takes" the stay's length
        if (event_sentence && (s == Slot::Epoch || (s == Slot::Tof && (m.text == "lasts" || m.text == "takes"))))
          continue;
        if (elements && s == Slot::Epoch) continue;  // the epoch of the elements
        // the mass and a state take their role from their own clause, a state also from the sentence
        const int r = s == Slot::Mass ? w.clause_role : w.role;
        if ((s == Slot::Position || s == Slot::Velocity) && w.role == kNoRole && sentence_roles.size() > 1)
          throw facts_error("'" + m.text + "' could be the initial or the final one: say which in its clause");
        named.push_back({candidates(m.meaning, r, m.text), m.text, m.meaning.weak});
        named.back().none = m.meaning.none;
      }
    // A date in a clause that says the spacecraft starts ("Launch is on 2025-03-01") is the
    // departure epoch; in one that says it arrives it is no fact HELIOS takes.
    bool date_here = false, epoch_named = false;
    for (const auto& q : c.quantities) date_here = date_here || q.date;
    for (const auto& n : named)
      for (const auto& x : n.cands) epoch_named = epoch_named || x.date;
    if (date_here && elements)
      named.push_back({{{Field::ElementsEpoch, Dimension::Time, false, false, true}}, w.words, false});
    else if (date_here && event_sentence)
      throw facts_error(
          "'" + w.words + "' dates an event on the way: HELIOS takes its window and chooses the date in it",
          event_form(event_kind, out.event_body));
    else if (date_here && !epoch_named && w.role == kFinal)
      named.push_back({{{Field::Tf, Dimension::Time, false, false, true}}, w.words, false});
    else if (date_here && !epoch_named && w.role == kInitial)
      named.push_back({{{Field::Epoch, Dimension::Time, false, false, true}}, w.words, false});
    for (const auto& q : c.quantities)
      if (q.window) {
        Candidate window{Field::Window, Dimension::Time, false, false};
        window.window = true;
        named.push_back({{window}, w.words, false});
        break;
      }
    return named;
  }

  // The facts of one clause: an objective, or each quantity placed on its fact.
  void read_clause(const Clause& c) {
    const ClauseWords w = words_of(c);
    if (read_objective(c, w)) return;
    check_bounds(c, w);
    check_time_of_flight(c, w);
    std::vector<Named> named = fact_words(c, w);
    // "The spacecraft has 200 kg of propellant": a weak word never takes what another noun qualifies.
    bool qualified = false;
    for (const auto& m : c.mentions) qualified = qualified || m.meaning.noun == kFuel || m.meaning.noun == kTime;
    // "The engine has a mass of 50 kg": a mass said of the engine is not the spacecraft's.
    for (const auto& m : c.mentions)
      for (const auto& n : c.mentions)
        if (m.meaning.weak && m.meaning.slot == Slot::Thrust &&
            (n.meaning.slot == Slot::Mass || n.meaning.slot == Slot::InitialMass) && !n.meaning.weak)
          throw facts_error("'" + n.text + "' is said of the '" + m.text +
                            "', not of the spacecraft: state the spacecraft's mass in a clause of its own");
    std::map<Field, std::string> bound_here;
    for (const auto& q : c.quantities) place(q, named, qualified, bound_here);
    for (auto& n : named)
      if (!n.bound && n.none) {
        add({n.cands.front().field, {0.0}, n.text});
        n.bound = true;
      }
    for (const auto& n : named)
      out.j2 = out.j2 || (!n.bound && n.text == "j2");  // "plus J2": the perturbation, not its coefficient
    for (const auto& n : named)
      if (!n.bound && !n.weak) {
        const Candidate& want = n.cands.front();
        throw facts_error("'" + n.text + "' has no value: give " + field_name(want.field) +
                          (want.pure ? " (a number without unit)" : " with its unit (" + spec_unit(want.dim) + ")"));
      }
  }

  // The facts a quantity fits: strong fact words first, a weak one only when none fits.
  std::vector<std::pair<Candidate, std::size_t>> fits_of(const Quantity& q, const std::vector<Named>& named,
                                                         bool qualified) const {
    std::vector<std::pair<Candidate, std::size_t>> fit;
    for (const bool weak : {false, true}) {  // a weak fact word only when no other fits
      if (weak && (!fit.empty() || qualified)) break;
      for (std::size_t k = 0; k < named.size(); ++k)
        if (named[k].weak == weak)
          for (const auto& cand : named[k].cands)
            if (fits(cand, q)) {
              bool dup = false;
              for (const auto& [f, _] : fit) dup = dup || f.field == cand.field;
              if (!dup) fit.push_back({cand, k});
            }
    }
    return fit;
  }

  // Why a quantity fits no fact word of its clause.
  [[noreturn]] void no_fit(const Quantity& q, const std::vector<Named>& named) const {
    if (q.date)
      throw facts_error("nothing in its clause says the date " + q.written + " is the departure epoch",
                        "The departure epoch is " + q.written + ".");
    {
      std::vector<const Named*> strong;
      for (const auto& n : named)
        if (!n.weak) strong.push_back(&n);
      if (strong.empty())
        throw facts_error(q.vector ? "the vector " + q.written +
                                         " has no role: say whether it is the initial or "
                                         "final position or velocity"
                                   : "nothing in its clause says what " + q.written + " is");
      const Candidate& want = strong.front()->cands.front();
      const bool plain = !q.vector && !q.date && !q.day && !q.window;
      const std::string sug = strong.size() == 1 && plain && !want.exhaust ? suggestion(want.field, q, want.dim) : "";
      if (q.unit.empty())
        throw facts_error(
            q.written + " has no unit, and " + field_name(want.field) + " needs one (" + spec_unit(want.dim) + ")",
            sug);
      std::string why = field_name(want.field) + " is a number without unit";
      if (!want.pure) {
        try {
          to_spec_unit(want.dim, q.unit);
          why = q.vector ? "a vector cannot be " + field_name(want.field)
                         : "a single number cannot be " + field_name(want.field);
        } catch (const std::invalid_argument& e) {
          why = e.what();
        }
      }
      throw facts_error(q.written + " cannot be " + field_name(want.field) + ": " + why, sug);
    }
  }

  // Places a quantity on the one fact it fits.
  void place(const Quantity& q, std::vector<Named>& named, bool qualified, std::map<Field, std::string>& bound_here) {
    const auto fit = fits_of(q, named, qualified);
    if (fit.empty()) no_fit(q, named);
    // Ambiguity: a number that fits two facts is an error, whatever the order.
    if (fit.size() > 1) {
      std::string names;
      for (const auto& f : fit) names += (names.empty() ? "" : " or ") + field_name(f.first.field);
      throw facts_error(q.written + " could be " + names + ": state one fact per clause");
    }
    const Candidate& cand = fit.front().first;
    if ((q.at_most && cand.field != Field::Thrust) || (q.at_least && cand.field != Field::Rmin))
      throw facts_error("'" + q.bound_words + " " + q.written + "' is " + (q.at_most ? "an upper" : "a lower") +
                        " bound on " + field_name(cand.field) + ", not its value" +
                        (cand.field == Field::Tof ? " (a bounded time of flight reads 'The time of flight is free, "
                                                    "at most Q.')"
                                                  : ""));
    if (bound_here.count(cand.field))
      throw facts_error("two values for " + field_name(cand.field) + ": " + bound_here[cand.field] + " and " +
                        q.written);
    bound_here[cand.field] = q.written;
    for (auto& n : named)
      for (const auto& x : n.cands)
        if (x.field == cand.field) {
          if (n.none)
            throw facts_error("'" + n.text + "' negates " + field_name(x.field) + ", so " + q.written +
                              " is not its value: state the " + field_name(x.field).substr(4) +
                              " HELIOS should use, or none");
          n.bound = true;
        }
    Fact fact{cand.field, {}, q.written, q.absolute};
    if (q.date) fact.absolute = {true, true};  // an epoch, MJD2000
    const double factor = q.unit.empty() ? 1.0 : to_spec_unit(cand.dim, q.unit);
    for (double v : q.nums) fact.value.push_back(cand.exhaust ? v * factor * 1000.0 / kG0 : v * factor);
    add(fact);
  }

  // An event's, an orbit's, a sail's and the central body's sentence hold what they need and no more.
  void check_kind() {
    // An event's or an orbit's sentence states nothing else: a gravitational parameter or a radius
    // beside it would be the body's, not the central body's.
    for (const auto& f : out.facts)
      if ((event_sentence && !on_the_way(f.field)) || (elements && !of_orbit(f.field)))
        throw facts_error(field_name(f.field) + " " + f.written + " stands beside " +
                          (elements ? "orbital elements" : "an event on the way") +
                          ": state it in a sentence of its own");
    if (elements) check_elements(out);
    if (event_sentence) {
      bool has_window = false;
      for (const auto& f : out.facts) has_window = has_window || f.field == Field::Window;
      if (event_kind.empty() && rendezvous_word && has_window) event_kind = "rendezvous";
      if (event_kind.empty() && has_window)
        throw facts_error("it gives a window but no event: a rendezvous, a flyby or a swing-by",
                          event_form("flyby", out.event_body));
      if (!event_kind.empty() && !has_window)
        throw facts_error("the " + std::string(event_kind == "flyby" ? "flyby" : "swing-by") +
                              " needs its window: HELIOS chooses the date inside it",
                          event_form(event_kind, out.event_body));
      if (!event_kind.empty() && out.event_body.empty())
        throw facts_error("it does not name the body of the " + event_kind);
      out.event = event_kind.empty() ? "stay" : event_kind;
    }
    for (const auto& c : clauses)
      for (const auto& m : c.mentions) {
        out.j2 = out.j2 || m.meaning.model == "j2";
        out.sail = out.sail || m.meaning.model == "sail";
      }
    bool sail_value = false, central_value = false;
    for (const auto& f : out.facts) {
      sail_value = sail_value || f.field == Field::CharAccel || f.field == Field::Lightness;
      central_value = central_value || f.field == Field::Mu || f.field == Field::J2 || f.field == Field::Radius;
    }
    if (central_unnamed && !central_value)
      throw facts_error("it does not name the central body (Sun, Earth or Mars: 'The central body is the Sun.')");
    if (out.sail && !sail_value)
      throw facts_error(
          "the solar sail needs its characteristic acceleration (at 1 AU) or lightness number",
          "The spacecraft is an ideal flat solar sail with a characteristic acceleration of 1 mm/s^2 at 1 "
          "AU.");
    out.sail = sail_value;
    if (!unplaced.empty()) {
      if (!central_value && !out.j2)
        throw facts_error("it does not say what " + unplaced +
                          " is here (the central body reads 'The central body is " +
                          (unplaced == "Mars" ? "" : "the ") + unplaced + ".')");
      out.constants_of = unplaced;
    }
  }

  // A sentence states something; a body's state is its ephemeris; values are positive.
  void check_values() const {
    if (out.facts.empty() && out.objective.empty() && out.central.empty() && out.departure_body.empty() &&
        out.arrival_body.empty() && out.event.empty() && !out.j2)
      throw facts_error("it states no fact HELIOS reads");
    for (const auto& f : out.facts) {
      // a body's state is its ephemeris, a gravitational parameter here would be the body's, not the central one's
      const bool initial_state = f.field == Field::R0 || f.field == Field::V0;
      const bool final_state = f.field == Field::Rf || f.field == Field::Vf;
      if ((!out.departure_body.empty() && initial_state) || (!out.arrival_body.empty() && final_state))
        throw facts_error("it gives both a body and " + field_name(f.field) + ": the body's ephemeris is the state");
      if ((!out.departure_body.empty() || !out.arrival_body.empty()) && f.field == Field::Mu)
        throw facts_error("the gravitational parameter " + f.written +
                          " stands beside a departure or arrival body: the central body's reads 'The central body is "
                          "the Sun with mu = Q.'");
    }
    for (const auto& f : out.facts) check_value(f.field, f.value[0], f.written);
  }
};

}  // namespace

SentenceFacts read_facts(const std::string& sentence, const std::map<std::string, std::string>& names) {
  return SentenceReader(sentence, names).read();
}

}  // namespace helios::spec::detail

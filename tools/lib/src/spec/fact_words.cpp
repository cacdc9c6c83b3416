// The words of the facts in other words, by concern (fact_words.hpp).
#include "fact_words.hpp"

#include <sstream>

namespace helios::spec::detail {
namespace {

void slot(PhraseTable& t, std::initializer_list<const char*> words, Slot s, int noun = kNoNoun) {
  for (const char* w : words) t[w] = {s, kNoRole, kNoVerb, noun};
}

void fact(PhraseTable& t, std::initializer_list<const char*> words, Field f) {
  for (const char* w : words) {
    t[w] = {Slot::Fact};
    t[w].field = f;
  }
}

}  // namespace

const PhraseTable& phrases() {
  static const PhraseTable table = [] {
    PhraseTable t;
    engine_and_state_words(t);
    objective_and_body_words(t);
    event_words(t);
    model_words(t);
    return t;
  }();
  return table;
}

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

// Fillers; the engine, the mass and the specific impulse; times, epochs, gravitational parameters
// and states.
void engine_and_state_words(PhraseTable& t) {
  // fillers: they state nothing
  std::istringstream fillers(
      "the a an is are be of to with at from by for in its it system electric ion has have must should can set fixed "
      "equal equals given taken as assumed constant total level magnitude consumption used consumed objective goal "
      "vector state conditions we want find optimize optimise trajectory transfer mission operate operates possible "
      "reach looking use motion problem on place our single trip exactly body runs run carries carry hall "
      "take all computed frame only match matches equipped located scheduled expended spent solve occurs occur "
      "achieved flight may anywhere");
  for (std::string w; fillers >> w;) t[w] = {};
  slot(t,
       {"thrust", "maximum thrust", "max thrust", "delivers", "deliver", "provides", "provide", "produces", "produce",
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
  slot(t, {"t"}, Slot::ThrustOrT0);
  slot(t, {"t0", "t_0"}, Slot::T0);
  t["takes place"] = {};
  t["low thrust"] = {};  // a kind of engine, not a thrust value
  t["two body"] = {};
  slot(t,
       {"epoch", "date", "departure epoch", "departure date", "launch date", "launch epoch", "start date",
        "start epoch", "initial epoch", "epoch of departure", "date of departure"},
       Slot::Epoch);
  slot(t, {"specific impulse", "isp", "i_sp"}, Slot::Isp);
  slot(t, {"exhaust velocity", "effective exhaust velocity", "exhaust speed"}, Slot::ExhaustV);
  slot(t, {"mass", "weighs", "weigh"}, Slot::Mass, kMass);
  slot(t, {"initial mass", "wet mass", "launch mass", "starting mass", "m0", "m_0"}, Slot::InitialMass, kInitialMass);
  slot(t, {"final mass"}, Slot::FinalMass, kFinalMass);
  slot(t,
       {"time of flight", "flight time", "transfer time", "tof", "takes", "lasts", "last", "duration",
        "transfer duration", "flight duration", "after departure", "after it departs", "after departing",
        "after launch", "after it leaves", "after leaving", "after the departure", "after the launch"},
       Slot::Tof, kTime);
  slot(t, {"mu", "gm", "gravitational parameter", "gravitational constant"}, Slot::Mu);
  slot(t, {"position", "location", "r"}, Slot::Position);
  slot(t, {"velocity", "v"}, Slot::Velocity);
  slot(t, {"r0", "r_0"}, Slot::R0);
  slot(t, {"v0", "v_0"}, Slot::V0);
  slot(t, {"rf", "r_f"}, Slot::Rf);
  slot(t, {"vf", "v_f"}, Slot::Vf);
}

// The roles (initial, final), objectives, bodies and the central body, bounds.
void objective_and_body_words(PhraseTable& t) {
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
  // a duration's upper bound, said of the time of flight
  for (const char* w : {"no longer than", "not longer than", "not take longer than", "not last longer than"})
    t[w] = {Slot::Tof, kNoRole, kNoVerb, kTime, true};
  for (const char* w : {"fuel", "propellant", "fuel consumption", "propellant consumption", "fuel mass",
                        "propellant mass", "fuel use", "mass of propellant", "mass of fuel", "mass of the propellant",
                        "mass of the fuel", "propellant used", "fuel used"})
    t[w] = {Slot::None, kNoRole, kNoVerb, kFuel};
  for (const char* w : {"time", "final time"}) t[w] = {Slot::None, kNoRole, kNoVerb, kTime};
  for (const char* w : {"fuel optimal", "propellant optimal"}) t[w] = {Slot::None, kNoRole, kMinimize, kFuel};
  for (const char* w : {"time optimal", "fastest", "quickest", "as fast as possible", "as short as possible",
                        "as early as possible", "as soon as possible"})
    t[w] = {Slot::None, kNoRole, kMinimize, kTime};
}

// Events on the way: the event words, their stays, landers and periapsis bounds; negations.
void event_words(PhraseTable& t) {
  for (const char* w : {"flyby", "flybys", "fly by", "flies by", "fly past", "flies past", "passes", "pass"})
    t[w].event = "flyby";
  for (const char* w : {"gravity assist", "swing by", "swings by", "swingby", "unpowered"})
    t[w].event = "gravity_assist";
  for (const char* w : {"asteroid", "comet", "there", "then", "close", "planned", "somewhere", "required", "window",
                        "free", "uses", "include", "includes", "manoeuvre", "maneuver"})
    t[w] = {};
  fact(t,
       {"stay", "stays", "stay time", "stay duration", "residence time", "remains", "remain", "waits", "wait", "spends",
        "spend", "surface stay"},
       Field::Stay);
  fact(t, {"lander", "drops", "drop", "releases", "released", "release"}, Field::Drop);
  fact(t,
       {"periapsis radius", "periapsis", "flyby radius", "pericenter radius", "pericentre radius", "closest approach",
        "rp"},
       Field::Rmin);
  for (const char* w : {"minimum periapsis radius", "minimum flyby radius", "min periapsis radius", "minimum radius",
                        "lowest periapsis radius"}) {
    fact(t, {w}, Field::Rmin);
    t[w].lower = true;
  }
  for (const char* w : {"least", "at least", "no less than", "not less than", "no fewer than"}) t[w].lower = true;
  fact(t, {"no stay", "does not stay"}, Field::Stay);
  t["no stay"].none = t["does not stay"].none = true;
  t["immediately"] = {};
  // a negation the phrases above do not hold ("no stay", "no more than") negates a fact
  for (const char* w : {"not", "no", "never", "without", "neither", "nor", "cannot", "doesn't", "don't", "isn't"})
    t[w].negation = true;
}

// The J2 perturbation and the central body's radius, solar sails, orbital elements.
void model_words(PhraseTable& t) {
  // the J2 perturbation ("j2" alone with a number is the coefficient), the central body's radius
  for (const char* w : {"j2 perturbation", "j2 term", "j2 effect", "oblateness", "zonal harmonic j2", "zonal harmonic",
                        "j2 zonal harmonic"})
    t[w].model = "j2";
  fact(t, {"j2 coefficient", "j2"}, Field::J2);
  t["j2"].weak = true;
  fact(t, {"radius", "equatorial radius"}, Field::Radius);
  for (const char* w : {"solar sail", "sail", "solar sails"}) t[w].model = "sail";
  fact(t, {"characteristic acceleration", "a_c", "ac"}, Field::CharAccel);
  fact(t, {"lightness number", "lightness", "lightness parameter"}, Field::Lightness);
  for (const char* w : {"modelled", "modeled", "through", "considered", "get there", "gets there"}) t[w] = {};
  for (const char* w : {"included", "dynamics", "plus", "account", "into", "model", "force", "propelled", "ideal",
                        "flat", "perfectly", "reflecting", "instead"})
    t[w] = {};
  // orbital elements ("a = Q", "e = N", "i = Q", "M = Q", "nu = Q", "Omega = Q", "omega = Q" too: scan())
  fact(t, {"semi major axis", "semimajor axis"}, Field::A);
  fact(t, {"eccentricity"}, Field::Ecc);
  fact(t, {"inclination"}, Field::Inc);
  fact(t,
       {"raan", "node", "ascending node", "longitude of the ascending node", "right ascension of the ascending node"},
       Field::Raan);
  fact(t,
       {"argp", "argument of perihelion", "argument of periapsis", "argument of pericenter", "argument of pericentre"},
       Field::Argp);
  fact(t, {"mean anomaly"}, Field::MeanAnomaly);
  fact(t, {"true anomaly"}, Field::TrueAnomaly);
  for (const char* w : {"elements", "orbital elements", "keplerian", "orbit", "orbital", "defined"}) t[w] = {};
}

}  // namespace helios::spec::detail

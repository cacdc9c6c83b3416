// An event on the way: "The spacecraft rendezvouses with NAME between day N and day N[, stays there for
// Q | and does not stay][ and leaves a lander of Q].", "The spacecraft flies by NAME between day N and day
// N[, and the relative speed must be at most Q].", "The spacecraft swings by NAME between day N and day N
// in an unpowered gravity assist; NAME has a gravitational parameter of Q and the periapsis radius must
// be at least Q." (windows also in MJD or MJD2000). "The spacecraft must rendezvous with NAME." without
// a window is the final rendezvous.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

// The body a clause names ("at NAME", "NAME has ...") must be the event's.
void same_body(const Event& e, const std::string& phrase) {
  const std::string named = body_name(phrase);
  if (lowercase(named) != lowercase(e.body) && lowercase(named) != "it")
    throw sentence_error("the clause names " + named + " but the event is at " + e.body);
}

void clause(Event& e, const std::string& part) {
  static const std::regex stay_re = re(R"(stays(?: there| at (.+?))? for )" + kQuantity);
  static const std::regex no_stay_re = re(R"(does not stay(?: there)?)");
  static const std::regex lander_re = re(R"((?:leaves|drops|releases) (?:a|an) (?:lander|probe|payload|package) of )" +
                                         kQuantity + R"((?: there| at (.+))?)");
  static const std::regex mu_re = re(R"((.+?) has a gravitational parameter of )" + kQuantity);
  static const std::regex rmin_re = re(
      R"((?:(?:the )?(?:periapsis|pericenter|pericentre|closest approach) radius (?:must be|is) at least |(?:the )?(?:minimum|lowest) (?:periapsis|pericenter|pericentre) radius is ))" +
      kQuantity);
  static const std::regex speed_re =
      re(R"((?:(?:the )?relative speed (?:must be|is) at most |with a relative speed of at most ))" + kQuantity);
  std::smatch m;
  const auto set = [&](std::optional<double>& slot, double value, const std::string& what) {
    if (slot) throw sentence_error(what + " at " + e.body + " is given twice");
    slot = value;
  };
  if (e.kind == "rendezvous" && std::regex_match(part, m, stay_re)) {
    if (m[1].matched) same_body(e, m[1].str());
    const double stay = quantity(m, 2, Dimension::Time);
    if (stay < 0) throw sentence_error("the stay must not be negative, got " + m[2].str() + " " + m[3].str());
    set(e.stay, stay, "the stay");
  } else if (e.kind == "rendezvous" && std::regex_match(part, m, no_stay_re)) {
    set(e.stay, 0.0, "the stay");
  } else if (e.kind == "rendezvous" && std::regex_match(part, m, lander_re)) {
    if (m[3].matched) same_body(e, m[3].str());
    const double drop = quantity(m, 1, Dimension::Mass);
    if (!(drop > 0)) throw sentence_error("the lander's mass must be positive, got " + m[1].str() + " " + m[2].str());
    set(e.drop, drop, "the lander");
  } else if (e.kind == "gravity_assist" && std::regex_match(part, m, mu_re)) {
    same_body(e, m[1].str());
    const double mu = quantity(m, 2, Dimension::GravParam);
    if (!(mu > 0)) throw sentence_error("the gravitational parameter must be positive");
    set(e.mu, mu, "the gravitational parameter");
  } else if (e.kind == "flyby" && std::regex_match(part, m, speed_re)) {
    const double v = quantity(m, 1, Dimension::Speed);
    if (!(v > 0)) throw sentence_error("the relative speed bound must be positive");
    set(e.max_speed, v, "the relative speed bound");
  } else if (e.kind == "gravity_assist" && std::regex_match(part, m, rmin_re)) {
    const double r = quantity(m, 1, Dimension::Length);
    if (!(r > 0)) throw sentence_error("the periapsis radius must be positive");
    set(e.rmin, r, "the lowest periapsis radius");
  } else {
    throw sentence_error("cannot read '" + part + "': " + Builder::clause_forms(e.kind));
  }
}

// "<verb> NAME between day N and day N[ in an unpowered gravity assist][, CLAUSE[ and CLAUSE]]".
void read_event(Builder& b, const std::string& kind, const std::string& rest) {
  static const std::regex window_re =
      re(R"((.+?) between (day|MJD2000|MJD) ()" + kNum + R"() and (day|MJD2000|MJD) ()" + kNum + R"()(.*))");
  std::smatch m;
  if (!std::regex_match(rest, m, window_re)) {
    if (rest.find(" between ") != std::string::npos)
      throw sentence_error(
          "the window must read 'between day N and day N' (days after the epoch) or 'between "
          "MJD2000 N and MJD2000 N'");
    // "The spacecraft must rendezvous with Mars.": with no window, the rendezvous that ends the flight
    if (kind == "rendezvous" && rest.find_first_of("[,;") == std::string::npos) {
      b.once("the final rendezvous");
      b.arrival = Endpoint{b.here, {{"ref", body_name(rest)}}, "rendezvous", std::nullopt};
      b.windowless_rendezvous = b.here;
      return;
    }
    throw sentence_error(
        "an event on the way needs its window ('... between day N and day N'); a rendezvous at "
        "the end reads 'At the final time the spacecraft rendezvouses with NAME'");
  }
  Event e;
  e.where = b.here;
  e.kind = kind;
  e.body = body_name(m[1].str());
  e.lo = Builder::epoch_ref(m[2].str(), m[3].str());
  e.hi = Builder::epoch_ref(m[4].str(), m[5].str());
  std::string tail = m[6].str();
  if (kind == "gravity_assist") {
    static const std::regex ga_re = re(R"(\s*(?:in|as|for) an? (?:unpowered )?gravity assist(.*))");
    std::smatch g;
    if (std::regex_match(tail, g, ga_re)) tail = g[1].str();
  }
  if (!trimmed(tail).empty()) {
    static const std::regex lead = re(R"(\s*(?:[;,]\s*(?:and\s+)?|and\s+)(.+))");
    std::smatch l;
    if (!std::regex_match(tail, l, lead))
      throw sentence_error("cannot read '" + trimmed(tail) + "' after the window: " + Builder::clause_forms(kind));
    for (const auto& part : clauses_of(l[1].str())) clause(e, part);
  }
  b.add_event(std::move(e));
}

void read(Builder& b, const std::smatch& m) {
  const std::string verb = lowercase(m[1].str());
  read_event(b,
             verb.find("rendezvous") != std::string::npos ? "rendezvous"
             : verb.find("fl") != std::string::npos       ? "flyby"
                                                          : "gravity_assist",
             m[2].str());
}

}  // namespace

std::vector<Form> event() {
  return {
      {"an event on the way",
       270,
       R"(The spacecraft (rendezvouses with|must rendezvous with|flies by|must fly by|swings by|must swing by) (.+))",
       read,
       {{"The spacecraft rendezvouses with Nikko between day 100 and day 200, stays there for 30 days and leaves a "
         "lander of 50 kg.",
         "planets +nikko",
         R"~({"/constraints/1": {"id": "nikko", "kind": "rendezvous", "at": "interior", "target": {"kind": "orbit",
                 "body": "Nikko", "elements": {"epoch_mjd2000": 5256, "a_AU": 2.2375176, "e": 0.1052183,
                 "i_deg": 5.70117, "raan_deg": 71.94548, "argp_deg": 2.08462, "mean_anomaly_deg": 287.3844555}},
                 "window_days": [100, 200], "stay_days": 30, "mass_drop_kg": 50}})~"},
        {"The spacecraft swings by Venus between day 100 and day 200 in an unpowered gravity assist; Venus has a "
         "gravitational parameter of 324859 km^3/s^2 and the periapsis radius must be at least 6351.8 km.",
         "planets",
         R"~({"/constraints/1": {"id": "venus", "kind": "gravity_assist", "at": "interior", "target": {
                 "kind": "body", "body": "Venus", "ephemeris": "jpl_lp"}, "window_days": [100, 200],
                 "body_mu_km3_s2": 324859, "min_periapsis_radius_km": 6351.8}})~"},
        {"The spacecraft flies by Venus between MJD2000 500 and MJD2000 600, and the relative speed must be at most "
         "5 km/s.",
         "planets", R"~({"/constraints/1/window_days": [100, 200], "/constraints/1/max_relative_speed_km_s": 5})~"},
        {"The spacecraft must rendezvous with Mars.", "planets -arrival", R"~({"/arrival/target/body": "Mars"})~"},
        {"The spacecraft flies by Venus.", "planets", R"~({"error": "an event on the way needs its window"})~"}}}};
}

}  // namespace helios::spec::grammar::forms

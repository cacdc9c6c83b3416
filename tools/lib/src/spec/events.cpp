// Where the spacecraft goes: targets, the final condition, events on the way (rendezvous with stays
// and landers, flybys, gravity assists), the checks that need the whole text, and the constraints.
#include "grammar.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "helios/derivation/names.hpp"

namespace helios::spec::grammar {

// "position [..] km with velocity [..] km/s", "a coasting target starting from position .. with
// velocity .." (its state at t0; it then moves unpowered) or a body's name, kept as {"ref": NAME}
// and looked up once the whole text is read (a body given by its orbit, else a planet).
json parse_target(const std::string& phrase) {
  std::smatch m;
  static const std::regex state = re("(a coasting target starting from )?(?:position " + kVector + " and velocity " +
                                     kVector + "|position " + kVector + " with velocity " + kVector + ")");
  if (std::regex_match(phrase, m, state)) {
    const std::size_t base = m[2].matched ? 2 : 10;
    return {{"kind", m[1].matched ? "coasting" : "fixed_state"},
            {"position_km", vector3(m, base, Dimension::Length)},
            {"velocity_km_s", vector3(m, base + 4, Dimension::Speed)},
            {"length_unit", m[base + 3].str()}};
  }
  if (phrase.find('[') == std::string::npos) {
    try {
      return {{"ref", body_name(phrase)}};
    } catch (const sentence_error& e) {
      throw sentence_error(std::string(e.what()) +
                           "; a state reads 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT'");
    }
  }
  throw sentence_error(
      "expected 'position [x, y, z] UNIT with velocity [vx, vy, vz] UNIT', 'a coasting target starting from position "
      "... with velocity ...' or a body's name");
}

EpochRef Builder::epoch_ref(const std::string& scale, const std::string& value) {
  if (lowercase(scale) == "day") return {number(value), false};
  return {mjd2000_of(scale, value), true};
}

// An event stated whole: a gravity assist takes the known mu of its body unless it states one.
void Builder::add_event(Event e) {
  if (e.kind == "gravity_assist" && !e.mu) {
    const std::string key = lowercase(e.body);
    const auto mu = key == "sun" ? std::nullopt : known_mu(e.body);
    if (!mu)
      throw sentence_error("the gravitational parameter of " + e.body + " is not known: add '; " + e.body +
                           " has a gravitational parameter of Q km^3/s^2'");
    e.mu = *mu;
  }
  const auto surface = surface_radius(e.body);
  if (e.rmin && surface && !(*e.rmin > *surface))
    throw sentence_error("the lowest periapsis radius at " + e.body + ", " + io::short_number(*e.rmin) +
                         " km, is not above its surface (radius " + io::short_number(*surface) +
                         " km): a periapsis radius counts from the body's centre");
  if (e.drop) e.drop_where = here;
  events.push_back(e);
}

std::string Builder::clause_forms(const std::string& kind) {
  if (kind == "rendezvous") return "a rendezvous takes 'stays there for Q', 'does not stay' and 'leaves a lander of Q'";
  if (kind == "flyby") return "a flyby matches the position only and takes 'the relative speed must be at most Q'";
  return "a gravity assist takes 'NAME has a gravitational parameter of Q' and 'the periapsis radius must be at "
         "least Q'";
}

// The one interior rendezvous with NAME stated before ("" = the one rendezvous, whatever its body).
Event& Builder::rendezvous_of(const std::string& name) {
  std::vector<Event*> found;
  int others = 0;
  std::string names;
  for (auto& e : events) {
    if (!name.empty() && lowercase(e.body) != lowercase(name)) continue;
    if (e.kind != "rendezvous") {
      ++others;
      continue;
    }
    names += (found.empty() ? "" : " and ") + e.body;
    found.push_back(&e);
  }
  if (found.empty())
    throw sentence_error(name.empty() ? "no rendezvous on the way is stated before this sentence"
                         : others
                             ? "only a rendezvous can leave a lander or stay, and the spacecraft only passes " + name
                             : "no rendezvous with " + name + " is stated before this sentence");
  if (found.size() > 1 && !name.empty())
    throw sentence_error("the spacecraft rendezvouses with " + name + " " + std::to_string(found.size()) +
                         " times: put the clause in the rendezvous sentence meant");
  if (found.size() > 1)
    throw sentence_error("the spacecraft rendezvouses with " + names + " on the way: say which one");
  return *found.front();
}

// A target's {"ref": NAME} as the body given by its orbit, else a planet with an ephemeris.
json Builder::resolve(const json& target, const Where& w) {
  if (!target.contains("ref")) return target;
  const std::string name = target["ref"];
  for (auto& o : orbits)
    if (lowercase(o.name) == lowercase(name)) {
      o.used = true;
      return {{"kind", "orbit"}, {"body", o.name}, {"elements", o.elements}};
    }
  if (is_planet(lowercase(name))) {
    std::string body = lowercase(name);
    body[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(body[0])));
    return {{"kind", "body"}, {"body", body}, {"ephemeris", "jpl_lp"}};
  }
  fail(w, "unknown body '" + name + "': state its orbit ('" + name +
              " moves on a Keplerian orbit about the Sun with a = Q, e = N, i = Q, node = Q, argument of "
              "perihelion = Q and mean anomaly = Q at MJD N') or name a planet with an ephemeris (Earth, Mars, "
              "Venus, Jupiter)");
}

// The targets once the whole text is read: names looked up, orbits resolved, epochs checked.
void Builder::resolve_targets() {
  const std::string central = central_body.value("name", "");
  for (const auto& o : orbits) {
    static const std::regex the = re(R"((?:the )?(.+))");
    std::smatch m;
    std::regex_match(o.about, m, the);
    const std::string about = lowercase(m[1].str());
    if (!o.about.empty() && about != "central body" && about != lowercase(central))
      fail(o.where, "the orbit is about " + m[1].str() + " but the central body is " + central);
  }
  const bool has_epoch = time.contains("epoch_mjd2000");
  const auto needs_epoch = [&](const json& target, const Where& w) {
    if (has_epoch || (target["kind"] != "body" && target["kind"] != "orbit")) return;
    fail(w, target["body"].get<std::string>() +
                " moves with time, so the text needs a calendar epoch: depart 'at MJD2000 N' (or 'at MJD N') or "
                "state 'The departure epoch is free between Q before and Q after MJD2000 N'");
  };
  departure->target = resolve_orbit(resolve(departure->target, departure->where), departure->where);
  needs_epoch(departure->target, departure->where);
  for (auto& e : events) {
    e.target = e.kind == "orbit_insertion" ? resolve_orbit(e.target, e.where) : resolve(json{{"ref", e.body}}, e.where);
    needs_epoch(e.target, e.where);
  }
  arrival->target = resolve_orbit(resolve(arrival->target, arrival->where), arrival->where);
  needs_epoch(arrival->target, arrival->where);
  for (const auto& o : orbits)
    if (!o.used)
      fail(o.where, "no sentence sends the spacecraft to " + o.name + ": remove its orbit or state the event");
}

// Checks that need the whole text: a free departure, windows, landers.
void Builder::finish_events() {
  const bool has_epoch = time.contains("epoch_mjd2000");
  const bool free_dep = time.value("departure", "") == "free";
  if (free_dep && departure_at_t)
    fail(departure->where,
         "with a free departure epoch the departure reads 'from TARGET' or 'at MJD2000 N', "
         "not 't = Q'");
  if (free_dep && time["final_time"] == "free")
    fail(free_departure_where,
         "a free departure epoch needs a fixed total time of flight ('The total time of "
         "flight is Q.')");

  // Windows in days after the epoch, inside the flight, in order and apart.
  const double epoch = has_epoch ? time["epoch_mjd2000"].get<double>() : 0.0;
  const double start = free_dep ? time["t0_window_days"][0].get<double>() : 0.0;
  const double tof =
      time["final_time"] == "fixed" ? time["tof_days"].get<double>() : time["tof_max_days"].get<double>();
  const double end = (free_dep ? time["t0_window_days"][1].get<double>() : 0.0) + tof;
  const Event* previous = nullptr;
  for (auto& e : events) {
    if ((e.lo.absolute || e.hi.absolute) && !has_epoch)
      fail(e.where,
           "its window is given as dates, but the text gives no calendar epoch to count the flight from: "
           "state the departure's ('The spacecraft departs at MJD2000 N ...') or give the window in days "
           "after the departure ('between day N and day N')");
    e.window_lo = e.lo.absolute ? e.lo.value - epoch : e.lo.value;
    e.window_hi = e.hi.absolute ? e.hi.value - epoch : e.hi.value;
    const std::string window = "day " + io::short_number(e.window_lo) + " to day " + io::short_number(e.window_hi);
    if (!(e.window_hi > e.window_lo)) fail(e.where, "its window, " + window + ", is empty");
    if (!(e.window_lo > start && e.window_hi < end))
      fail(e.where, "its window, " + window + ", must lie inside the flight: after day " + io::short_number(start) +
                        " and before day " + io::short_number(end) + " (days count from the epoch)");
    if (previous && e.window_lo < previous->window_hi)
      fail(e.where, "its window, " + window + ", starts before the window of the event at " + previous->place() +
                        " (day " + io::short_number(previous->window_lo) + " to day " +
                        io::short_number(previous->window_hi) +
                        ") ends: state the events in the order they happen, with windows that do not overlap");
    if (previous && previous->stay && !(e.window_hi > previous->window_lo + *previous->stay))
      fail(e.where, "its window, " + window + ", ends before the stay at " + previous->body + " can end (day " +
                        io::short_number(previous->window_lo + *previous->stay) +
                        " at the earliest): widen or move the windows");
    previous = &e;
  }
  if (previous && previous->stay && !(end > previous->window_lo + *previous->stay))
    fail(previous->where,
         "the stay at " + previous->body + " cannot end before the final time (day " + io::short_number(end) + ")");
  double dropped = 0;
  for (const auto& e : events) {
    if (!e.drop) continue;
    if (propulsion == "solar_sail") fail(e.drop_where, "a solar sail has no mass to leave behind");
    dropped += *e.drop;
    if (spacecraft.contains("initial_mass_kg") && !(dropped < spacecraft["initial_mass_kg"].get<double>()))
      fail(e.drop_where, "the landers weigh " + io::short_number(dropped) + " kg, not less than the initial mass");
  }
}

// The derivation names its symbols after the constraints' ids: "t_<id>", "t_<id>_frac",
// "<id>_rx" (a body's ephemeris), "<x>_<id>_m", "nu_<id>_<k>", beside the costates "l_<x>". An id
// that is one of those prefixes, or another id followed by "_" and a word, would give two symbols
// one name: such a body name is refused.
void Builder::check_event_ids(const std::vector<std::string>& ids) const {
  static const std::set<std::string> reserved = {"l",    "t",    "h",    "nu",    "psi",   "mu",           "drop",
                                                 "rmin", "vmax", "jump", "time",  "delta", "stationarity", "phi",
                                                 "eps",  "u",    "c",    "alone", "rx",    "ry",           "rz",
                                                 "vx",   "vy",   "vz",   "m",     "tf",    "t0",           "lambda0"};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::string& id = ids[k];
    if (reserved.count(id) || derivation::names::is_costate(id) || id.rfind("departure_", 0) == 0 ||
        id.rfind("arrival_", 0) == 0)
      fail(events[k].where, "the body name '" + events[k].body + "' would name a symbol of the derivation ('" + id +
                                "_rx', 'l_...' or 'arrival_...'): choose another name, e.g. '" + events[k].body +
                                "_body'");
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const std::string& other = ids[j];
      if (j == k || id.size() <= other.size() + 1 || id.compare(0, other.size() + 1, other + "_") != 0) continue;
      const std::string suffix = id.substr(other.size() + 1);
      if (suffix.find_first_not_of("0123456789") != std::string::npos)
        fail(events[k].where, "the body names '" + events[j].body + "' and '" + events[k].body +
                                  "' would give two symbols one name ('" + derivation::names::event_time(id) +
                                  "' would be both the time of " + events[k].body + " and '" +
                                  derivation::names::event_time(other) + "' of " + events[j].body + " followed by '_" +
                                  suffix + "'): rename one so that neither is the other followed by '_'");
    }
  }
}

// A target as the spec keeps it: without the unit its length was written in, kept for messages.
json spec_target(json target) {
  target.erase("length_unit");
  return target;
}

json Builder::constraints() {
  json out = json::array();
  out.push_back(
      {{"id", "departure"}, {"kind", "initial_state"}, {"at", "t0"}, {"target", spec_target(departure->target)}});
  std::map<std::string, int> visits;
  std::vector<std::string> ids;
  for (const auto& e : events) {
    const std::string base = e.kind == "orbit_insertion" ? "orbit" : lowercase(e.body);
    int& n = visits[base];
    std::string id = ++n == 1 ? base : base + "_" + std::to_string(n);
    while (std::find(ids.begin(), ids.end(), id) != ids.end()) id = base + "_" + std::to_string(++n);
    ids.push_back(id);
  }
  check_event_ids(ids);
  for (std::size_t k = 0; k < events.size(); ++k) {
    const Event& e = events[k];
    const std::string& id = ids[k];
    json c = {{"id", id},
              {"kind", e.kind},
              {"at", "interior"},
              {"target", spec_target(e.target)},
              {"window_days", json::array({e.window_lo, e.window_hi})}};
    if (e.stay) c["stay_days"] = *e.stay;
    if (e.drop) c["mass_drop_kg"] = *e.drop;
    if (e.mu) c["body_mu_km3_s2"] = *e.mu;
    if (e.rmin) c["min_periapsis_radius_km"] = *e.rmin;
    if (e.max_speed) c["max_relative_speed_km_s"] = *e.max_speed;
    out.push_back(c);
  }
  json last = {{"id", "arrival"}, {"kind", arrival->kind}, {"at", "tf"}, {"target", spec_target(arrival->target)}};
  if (arrival->max_speed) last["max_relative_speed_km_s"] = *arrival->max_speed;
  out.push_back(last);
  return out;
}

}  // namespace helios::spec::grammar

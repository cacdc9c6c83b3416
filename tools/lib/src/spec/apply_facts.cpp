// Facts stated in other words (read by facts.cpp) applied to the spec being built.
#include "grammar.hpp"

#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {

// The bodies met so far, which other words may name ("The spacecraft stays 30 days at Nikko."):
// lower case to as written.
std::map<std::string, std::string> Builder::body_names() const {
  std::map<std::string, std::string> names;
  for (const auto& o : orbits) names[lowercase(o.name)] = o.name;
  for (const auto& e : events)
    if (!e.body.empty()) names[lowercase(e.body)] = e.body;
  return names;
}

detail::SentenceFacts Builder::facts_of(const std::string& s) const {
  try {
    return detail::read_facts(s, body_names());
  } catch (const detail::facts_error& e) {
    throw sentence_error(std::string(e.what()) +
                         (e.suggestion.empty() ? "" : "; did you mean \"" + e.suggestion + "\"?"));
  }
}

void Builder::apply_facts(const detail::SentenceFacts& f) {
  using detail::Field;
  if (!f.central.empty()) {
    once("the central body");
    central(f.central, "");
  }
  const std::string central_name = central_body.is_object() ? central_body.value("name", "") : "";
  if (!f.constants_of.empty()) {
    // HELIOS takes the central body's constants and J2 here: the body must be that one.
    if (!central_name.empty() && lowercase(central_name) != lowercase(f.constants_of))
      throw sentence_error("it is about " + f.constants_of + " as the central body, but the central body is " +
                           central_name + " (a swing-by body's gravitational parameter reads '; " + f.constants_of +
                           " has a gravitational parameter of Q')");
    constants_body = {f.constants_of, here};
  }
  if (f.j2) {
    once("the J2 perturbation");
    perturbations.push_back({{"kind", "j2"}});
  }
  if (!f.departure_body.empty()) {
    once("the departure");
    departure = Endpoint{here, {{"ref", f.departure_body}}, "initial_state", std::nullopt};
  }
  if (!f.arrival_body.empty()) {
    once("the final rendezvous");
    arrival = Endpoint{here, {{"ref", f.arrival_body}}, "rendezvous", std::nullopt};
  }
  for (const auto& fact : f.facts) apply_fact(fact);
  if (!f.orbit_of.empty()) apply_orbit(f);
  if (!f.event.empty()) apply_event(f);
  if (!f.objective.empty()) {
    once("the objective");
    objective = {{"kind", f.objective}};
    objective_where = here;
  }
}

// The central body's J2 coefficient and radius: stated after it, once (a known radius is replaced).
void Builder::set_central_value(const char* key, double v, bool stated) {
  if (!central_body.is_object() || central_body.value("name", "").empty())
    throw sentence_error("state the central body before its J2 coefficient or radius");
  if (stated) throw sentence_error(std::string("the central body's ") + key + " is given twice");
  central_body[key] = v;
  constant_where[key] = here;
}

void Builder::set_engine(detail::Field field, double v) {
  once(field);
  ++seen["the spacecraft's engine"];
  spacecraft[detail::spec_key(field)] = v;
}

// A state vector stated alone: the first of the departure's or the final rendezvous's makes it.
void Builder::set_state(std::optional<json>& slot, detail::Field field, bool initial, const json& v) {
  once(field);
  if (initial && !r0 && !v0) {
    once("the departure");
    initial_where = here;
  }
  if (!initial && !rf && !vf) {
    once("the final rendezvous");
    final_where = here;
  }
  slot = v;
}

// One fact of a sentence in other words, into the spec being built.
void Builder::apply_fact(const detail::Fact& fact) {
  using detail::Field;
  const double v = fact.value[0];
  const json vec = fact.value.size() == 3 ? json(fact.value) : json();
  switch (fact.field) {
    case Field::Thrust:
    case Field::Isp:
    case Field::InitialMass:
    case Field::FinalMass:
      set_engine(fact.field, v);
      break;
    case Field::Tof:
      fixed_time_of_flight(v);
      break;
    case Field::TofMin:
      bound_time_of_flight(v, std::nullopt);
      break;
    case Field::TofMax:
      bound_time_of_flight(std::nullopt, v);
      break;
    case Field::T0:
      once(fact.field);
      time["t0_days"] = v;
      departure_at_t = true;
      break;
    case Field::Tf:
      once(fact.field);
      arrival_time = ArrivalTime{v, fact.absolute[0], here};
      break;
    case Field::Epoch:
      once(fact.field);
      if (time.value("t0_days", 0.0) != 0.0)
        throw sentence_error("the departure epoch " + fact.written +
                             " is the time 0 of the problem, but the departure time was stated as t = " +
                             io::short_number(time["t0_days"].get<double>()) + " days");
      set_epoch(v);
      break;
    case Field::Mu:
      set_mu(v);
      break;
    case Field::R0:
      set_state(r0, fact.field, true, vec);
      break;
    case Field::V0:
      set_state(v0, fact.field, true, vec);
      break;
    case Field::Rf:
      set_state(rf, fact.field, false, vec);
      break;
    case Field::Vf:
      set_state(vf, fact.field, false, vec);
      break;
    case Field::J2:
      set_central_value("j2", v, central_body.contains("j2"));
      break;
    case Field::Radius:
      set_central_value("radius_km", v, radius_stated);
      radius_stated = true;
      break;
    case Field::CharAccel:
      sail(v, 1.0);  // a characteristic acceleration is the one at 1 AU
      break;
    case Field::Lightness:  // the ratio of the sail's acceleration to the Sun's gravity, here at 1 AU
      sail(v * astro::MU_SUN_KM3_S2 / (astro::AU_KM * astro::AU_KM) * 1e6, 1.0);
      break;
    case Field::DepartureWindow:
      once("the departure window");
      if (!fact.absolute[0] || !fact.absolute[1])
        throw sentence_error(
            "a departure window reads in dates ('between 2030-01-01 and 2030-03-01'): days count "
            "from the departure, which the window makes free");
      departure_window_dates(fact.value[0], fact.value[1]);
      break;
    case Field::Window:
    case Field::Stay:
    case Field::Drop:
    case Field::Rmin:
      break;  // the event's (apply_event)
    case Field::A:
    case Field::Ecc:
    case Field::Inc:
    case Field::Raan:
    case Field::Argp:
    case Field::MeanAnomaly:
    case Field::TrueAnomaly:
    case Field::ElementsEpoch:
      break;  // the orbit's, below
  }
}

// A body's orbital elements given in other words.
void Builder::apply_orbit(const detail::SentenceFacts& f) {
  using detail::Field;
  static const std::map<Field, const char*> keys = {{Field::Ecc, "e"},
                                                    {Field::Inc, "i"},
                                                    {Field::Raan, "raan"},
                                                    {Field::Argp, "argp"},
                                                    {Field::MeanAnomaly, "mean"},
                                                    {Field::TrueAnomaly, "true"}};
  std::map<std::string, double> v;
  double epoch = 0;
  for (const auto& fact : f.facts) {
    if (fact.field == Field::A) v["a"] = fact.value[0] / astro::AU_KM;
    if (fact.field == Field::ElementsEpoch) epoch = fact.value[0];
    if (keys.count(fact.field)) v[keys.at(fact.field)] = fact.value[0];
  }
  define_orbit(f.orbit_of, "", elements_json(epoch, v));
}

// An event on the way in other words: a new one with its window, or a stay or lander at the
// rendezvous stated before.
void Builder::apply_event(const detail::SentenceFacts& f) {
  using detail::Field;
  std::optional<double> stay, drop, rmin;
  const detail::Fact* window = nullptr;
  for (const auto& fact : f.facts) {
    if (fact.field == Field::Window) window = &fact;
    if (fact.field == Field::Stay) stay = fact.value[0];
    if (fact.field == Field::Drop) drop = fact.value[0];
    if (fact.field == Field::Rmin) rmin = fact.value[0];
  }
  if (f.event == "stay") {
    if (rmin)
      throw sentence_error("a periapsis bound belongs to a swing-by ('" + clause_forms("gravity_assist") + "')");
    Event& e = rendezvous_of(f.event_body);
    if (f.small_body && is_planet(lowercase(e.body)))
      throw sentence_error("it speaks of an asteroid or comet, but the rendezvous stated before is with " + e.body);
    const auto set = [&](std::optional<double>& slot, const std::optional<double>& v, const char* what) {
      if (!v) return;
      if (slot) throw sentence_error(std::string(what) + " at " + e.body + " is given twice");
      slot = v;
    };
    set(e.stay, stay, "the stay");
    set(e.drop, drop, "the lander");
    if (drop) e.drop_where = here;
    return;
  }
  Event e;
  e.where = here;
  e.kind = f.event;
  e.body = body_name(f.event_body);
  if (f.small_body && is_planet(lowercase(e.body)))
    throw sentence_error("it speaks of an asteroid or comet, but " + e.body + " is a planet");
  const auto ref = [&](int k) { return EpochRef{window->value[k], window->absolute[k]}; };
  e.lo = ref(0);
  e.hi = ref(1);
  if ((stay || drop) && e.kind != "rendezvous") throw sentence_error("cannot read it: " + clause_forms(e.kind));
  if (rmin && e.kind != "gravity_assist") throw sentence_error("cannot read it: " + clause_forms(e.kind));
  e.stay = stay;
  e.drop = drop;
  e.rmin = rmin;
  // a body's own gravitational parameter is stated only in the controlled form
  if (e.kind == "gravity_assist" && !known_mu(e.body))
    throw sentence_error("the gravitational parameter of " + e.body +
                         " is not known; did you mean \"The spacecraft swings by " + e.body +
                         " between day N and day N in an unpowered gravity assist; " + e.body +
                         " has a gravitational parameter of Q km^3/s^2.\"?");
  add_event(std::move(e));
}

// The departure and the final state from vectors stated one by one.
void Builder::finish_facts() {
  const auto endpoint = [&](const std::optional<json>& r, const std::optional<json>& v, const Where& w,
                            const char* which, std::optional<Endpoint>& out, const char* kind) {
    if (!r && !v) return;
    if (!r || !v)
      fail(w, std::string("it gives the ") + which + (r ? " position" : " velocity") + " but no sentence gives the " +
                  which + (r ? " velocity" : " position"));
    out = Endpoint{w, {{"kind", "fixed_state"}, {"position_km", *r}, {"velocity_km_s", *v}}, kind, std::nullopt};
  };
  if (arrival_time) {  // the time of flight from the departure to the arrival
    const auto& [tf, date, w] = *arrival_time;
    const std::string what = date ? "the arrival date MJD2000 " + io::short_number(tf)
                                  : "the arrival time t = " + io::short_number(tf) + " days";
    if (time.contains("final_time")) fail(w, "it gives " + what + ", and the time of flight is stated too");
    if (date && !time.contains("epoch_mjd2000"))
      fail(w, "it gives " + what + " but the text gives no departure epoch to count the time of flight from");
    if (date && time.value("departure", "") == "free")
      fail(w,
           "it gives " + what +
               ", but the departure is free in its window: HELIOS reads a time of flight, not an arrival date, then");
    const double t0 = date ? time["epoch_mjd2000"].get<double>() : time.value("t0_days", 0.0);
    if (!(tf > t0)) fail(w, what + " is not after the departure");
    time["tof_days"] = tf - t0;
    time["final_time"] = "fixed";
  }
  endpoint(r0, v0, initial_where, "initial", departure, "initial_state");
  endpoint(rf, vf, final_where, "final", arrival, "rendezvous");
}

}  // namespace helios::spec::grammar

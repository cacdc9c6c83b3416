// The facts in other words, read stage by stage (fact_reader.hpp): each clause's facts, a quantity
// placed on the one fact it fits, and the checks of the whole sentence.
#include "fact_reader.hpp"

namespace helios::spec::detail {

// Bound words that make a fact word a bound, not a value; a periapsis radius that is one.
void SentenceReader::check_bounds(const Clause& c, const ClauseWords& w) const {
  if (w.verb == kMinimum || w.verb == kMinimize || w.verb == kMaximize)
    throw facts_error("'" + w.words + "' mixes an objective with a value");
  // A bound on the thrust is the maximum thrust, one on the time of flight its longest (read_clause); a
  // bound on anything else is not a value.
  for (const auto& m : c.mentions)
    for (const auto& n : c.mentions)
      if (m.meaning.bound && !m.on_quantity && n.meaning.slot != Slot::None && n.meaning.slot != Slot::Thrust &&
          n.meaning.slot != Slot::Tof && !n.meaning.weak)
        throw facts_error("'" + m.text + "' makes '" + n.text + "' a bound, not a value");
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

void SentenceReader::check_time_of_flight(const Clause& c, const ClauseWords& w) const {
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
std::vector<Named> SentenceReader::fact_words(const Clause& c, const ClauseWords& w) const {
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
    throw facts_error("'" + w.words + "' dates an event on the way: HELIOS takes its window and chooses the date in it",
                      event_form(event_kind, out.event_body));
  else if (date_here && !epoch_named && w.role == kFinal)
    named.push_back({{{Field::Tf, Dimension::Time, false, false, true}}, w.words, false});
  else if (date_here && !epoch_named && w.role == kInitial)
    named.push_back({{{Field::Epoch, Dimension::Time, false, false, true}}, w.words, false});
  for (const auto& q : c.quantities)
    if (q.window) {
      Candidate window{departure_window ? Field::DepartureWindow : Field::Window, Dimension::Time, false, false};
      window.window = true;
      named.push_back({{window}, w.words, false});
      break;
    }
  return named;
}

// The facts of one clause: an objective, or each quantity placed on its fact.
void SentenceReader::read_clause(const Clause& c) {
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
  // "The maximum time of flight is Q": the bound word qualifies the time of flight, not the quantity.
  bool tof_bound = false;
  for (const auto& m : c.mentions)
    for (const auto& n : c.mentions) tof_bound = tof_bound || (m.meaning.bound && n.meaning.slot == Slot::Tof);
  std::map<Field, std::string> bound_here;
  for (Quantity q : c.quantities) {
    q.at_most = q.at_most || (tof_bound && !q.range);
    place(q, named, qualified, bound_here);
  }
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
std::vector<std::pair<Candidate, std::size_t>> SentenceReader::fits_of(const Quantity& q,
                                                                       const std::vector<Named>& named,
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
void SentenceReader::no_fit(const Quantity& q, const std::vector<Named>& named) const {
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
    const bool plain = !q.vector && !q.date && !q.day && !q.window && !q.range;
    const std::string sug = strong.size() == 1 && plain && !want.exhaust ? suggestion(want.field, q, want.dim) : "";
    if (q.unit.empty())
      throw facts_error(
          q.written + " has no unit, and " + field_name(want.field) + " needs one (" + spec_unit(want.dim) + ")", sug);
    std::string why = field_name(want.field) + " is a number without unit";
    if (!want.pure) {
      try {
        to_spec_unit(want.dim, q.unit);
        why = q.vector  ? "a vector cannot be " + field_name(want.field)
              : q.range ? "a range is no value of " + field_name(want.field) + ": give one"
                        : "a single number cannot be " + field_name(want.field);
      } catch (const std::invalid_argument& e) {
        why = e.what();
      }
    }
    throw facts_error(q.written + " cannot be " + field_name(want.field) + ": " + why, sug);
  }
}

// Places a quantity on the one fact it fits.
void SentenceReader::place(const Quantity& q, std::vector<Named>& named, bool qualified,
                           std::map<Field, std::string>& bound_here) {
  const auto fit = fits_of(q, named, qualified);
  if (fit.empty()) no_fit(q, named);
  // Ambiguity: a number that fits two facts is an error, whatever the order.
  if (fit.size() > 1) {
    std::string names;
    for (const auto& f : fit) names += (names.empty() ? "" : " or ") + field_name(f.first.field);
    throw facts_error(q.written + " could be " + names + ": state one fact per clause");
  }
  const Candidate& cand = fit.front().first;
  // A time of flight with a bound or a range is a free one, searched between its bounds.
  if (cand.field == Field::Tof && (q.at_most || q.at_least || q.range)) return place_bounds(q, named, bound_here);
  if ((q.at_most && cand.field != Field::Thrust) || (q.at_least && cand.field != Field::Rmin))
    throw facts_error("'" + q.bound_words + " " + q.written + "' is " + (q.at_most ? "an upper" : "a lower") +
                      " bound on " + field_name(cand.field) + ", not its value");
  if (bound_here.count(cand.field))
    throw facts_error("two values for " + field_name(cand.field) + ": " + bound_here[cand.field] + " and " + q.written);
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

// "at most Q", "at least Q", "between N and Q": the bounds of a free time of flight.
void SentenceReader::place_bounds(const Quantity& q, std::vector<Named>& named,
                                  std::map<Field, std::string>& bound_here) {
  const double factor = to_spec_unit(Dimension::Time, q.unit);
  std::vector<std::pair<Field, double>> bounds;
  if (q.range) bounds = {{Field::TofMin, q.nums[0] * factor}, {Field::TofMax, q.nums[1] * factor}};
  if (q.at_most) bounds = {{Field::TofMax, q.nums[0] * factor}};
  if (q.at_least) bounds = {{Field::TofMin, q.nums[0] * factor}};
  for (const auto& [field, value] : bounds) {
    if (bound_here.count(field))
      throw facts_error("two values for " + field_name(field) + ": " + bound_here[field] + " and " + q.written);
    bound_here[field] = q.written;
    add({field, {value}, q.written});
  }
  for (auto& n : named)
    for (const auto& x : n.cands) n.bound = n.bound || x.field == Field::Tof;
}

// An event's, an orbit's, a sail's and the central body's sentence hold what they need and no more.
void SentenceReader::check_kind() {
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
    throw facts_error("the solar sail needs its characteristic acceleration (at 1 AU) or lightness number",
                      "The spacecraft is an ideal flat solar sail with a characteristic acceleration of 1 mm/s^2 at 1 "
                      "AU.");
  out.sail = sail_value;
  if (!unplaced.empty()) {
    if (!central_value && !out.j2)
      throw facts_error("it does not say what " + unplaced + " is here (the central body reads 'The central body is " +
                        (unplaced == "Mars" ? "" : "the ") + unplaced + ".')");
    out.constants_of = unplaced;
  }
}

// A sentence states something; a body's state is its ephemeris; values are positive.
void SentenceReader::check_values() const {
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

}  // namespace helios::spec::detail

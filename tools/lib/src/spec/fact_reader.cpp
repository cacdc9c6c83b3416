// The facts in other words, read stage by stage (fact_reader.hpp): the clauses, the kind of sentence
// and the bodies it names.
#include "fact_reader.hpp"

#include <cctype>

namespace helios::spec::detail {

void SentenceReader::add(const Fact& fact) {
  for (const auto& f : out.facts)
    if (f.field == fact.field)
      throw facts_error(field_name(fact.field) + " is stated twice: " + f.written + " and " + fact.written);
  out.facts.push_back(fact);
}

// The clauses, with a body named for the first time by orbital elements or an event's window.
void SentenceReader::read_clauses() {
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
void SentenceReader::find_kind() {
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
      rendezvous_word = rendezvous_word || m.text == "rendezvous" || m.text == "rendezvouses" || m.text == "arrives" ||
                        m.text == "arrive";
      out.small_body = out.small_body || m.text == "asteroid" || m.text == "comet";
    }
    for (const auto& q : c.quantities) event_sentence = event_sentence || q.window || q.day;
  }
  // "The spacecraft leaves Earth between 2032-01-10 and 2032-02-20": a window of the departure alone,
  // no event on the way.
  bool window = false, day = false;
  for (const auto& c : clauses)
    for (const auto& q : c.quantities) {
      window = window || q.window;
      day = day || q.day;
    }
  departure_window =
      window && !day && event_kind.empty() && !rendezvous_word && sentence_roles == std::set<int>{kInitial};
  for (const auto& c : clauses)
    for (const auto& m : c.mentions)
      departure_window = departure_window && !(m.meaning.slot == Slot::Fact && on_the_way(m.meaning.field));
  if (departure_window) event_sentence = false;
}

// The body of orbital elements or of an event on the way.
void SentenceReader::place_bodies() {
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
void SentenceReader::place_role_bodies() {
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
    throw facts_error("it names " + *bodies.begin() + " and " + *bodies.rbegin() + ": which one is the central body?");
  // A body named with no word saying it is the central one: its gravitational parameter, if the
  // sentence gives one ("The Sun's gravitational parameter is Q"), checked below.
  unplaced = !bodies.empty() && !central_named ? *bodies.begin() : "";
  // "The gravitational parameter of the central body is Q": a constant of the central body named elsewhere
  central_unnamed = bodies.empty() && central_named && !elements;
  if (!bodies.empty() && central_named) out.central = *bodies.begin();
}

ClauseWords SentenceReader::words_of(const Clause& c) const {
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
bool SentenceReader::read_objective(const Clause& c, const ClauseWords& w) {
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

SentenceFacts read_facts(const std::string& sentence, const std::map<std::string, std::string>& names) {
  return SentenceReader(sentence, names).read();
}

}  // namespace helios::spec::detail

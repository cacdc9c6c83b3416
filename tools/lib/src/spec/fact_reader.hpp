#pragma once
// The reader of facts in other words (internal to tools/lib/src/spec): a sentence's words into
// clauses of phrases and quantities (fact_clauses.cpp), the facts a phrase may name and the
// quantities that fit them (fact_candidates.cpp), and the SentenceReader that places each quantity
// on the one fact its clause names, stage by stage (fact_reader.cpp: the clauses, the kind of
// sentence, its bodies; fact_place.cpp: each clause's facts and the checks of the whole).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "fact_scan.hpp"
#include "fact_words.hpp"
#include "facts.hpp"

namespace helios::spec::detail {

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

struct Clause {
  std::vector<Mention> mentions;
  std::vector<Quantity> quantities;
};

// ---- clauses (fact_clauses.cpp) ----
facts_error negation_error(const std::string& word);
// A word that states nothing ("the", "of", "to").
bool filler(const Meaning& m);
// Words into the longest phrases of the table; an unknown word is an error.
std::vector<Clause> clauses_of(const std::vector<Token>& tokens, const std::map<std::string, std::string>& names);
// For a sentence with a word that fits nowhere: the controlled form of its one scalar fact, if the
// sentence names exactly one and holds exactly one number.
std::string rough_suggestion(const std::vector<Token>& tokens);

// ---- the facts a phrase may name (fact_candidates.cpp) ----
// The facts of an event on the way and of an orbit.
bool on_the_way(Field f);
bool of_orbit(Field f);
std::vector<Candidate> candidates(const Meaning& m, int role, const std::string& text);
bool fits(const Candidate& c, const Quantity& q);
// The controlled-English sentence stating `f` with the user's number (and unit, else the spec's).
std::string suggestion(Field f, const Quantity& q, Dimension d);
// A body's orbital elements are all six, one anomaly, their epoch and the body; else the error
// suggests the orbit sentence with the user's own numbers.
void check_elements(const SentenceFacts& out);
// The controlled sentence of an event, with the body the user named.
std::string event_form(const std::string& kind, const std::string& body);
std::string objective_of(int verb, int noun, int role, const std::string& words);

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
  bool departure_window = false;  // a window in a sentence about the departure alone: when it may depart
  std::string event_kind, unplaced, objective_words;

  // ---- the clauses, the kind of sentence, its bodies (fact_reader.cpp) ----
  void add(const Fact& fact);
  // The clauses, with a body named for the first time by orbital elements or an event's window.
  void read_clauses();
  // Which roles, bodies and events the sentence speaks of.
  void find_kind();
  // The body of orbital elements or of an event on the way.
  void place_bodies();
  // A planet left or reached, else the central body or the one whose constants it gives.
  void place_role_bodies();
  ClauseWords words_of(const Clause& c) const;
  // An objective: a verb and what it applies to, no quantity. False when the clause is none.
  bool read_objective(const Clause& c, const ClauseWords& w);

  // ---- each clause's facts, the checks of the whole (fact_place.cpp) ----
  // Bound words that make a fact word a bound, not a value; a periapsis radius that is one.
  void check_bounds(const Clause& c, const ClauseWords& w) const;
  void check_time_of_flight(const Clause& c, const ClauseWords& w) const;
  // The clause's fact words with what each may name: a date and a window named by the clause.
  std::vector<Named> fact_words(const Clause& c, const ClauseWords& w) const;
  // The facts of one clause: an objective, or each quantity placed on its fact.
  void read_clause(const Clause& c);
  // The facts a quantity fits: strong fact words first, a weak one only when none fits.
  std::vector<std::pair<Candidate, std::size_t>> fits_of(const Quantity& q, const std::vector<Named>& named,
                                                         bool qualified) const;
  // Why a quantity fits no fact word of its clause.
  [[noreturn]] void no_fit(const Quantity& q, const std::vector<Named>& named) const;
  // Places a quantity on the one fact it fits.
  void place(const Quantity& q, std::vector<Named>& named, bool qualified, std::map<Field, std::string>& bound_here);
  void place_bounds(const Quantity& q, std::vector<Named>& named, std::map<Field, std::string>& bound_here);
  // An event's, an orbit's, a sail's and the central body's sentence hold what they need and no more.
  void check_kind();
  // A sentence states something; a body's state is its ephemeris; values are positive.
  void check_values() const;
};

}  // namespace helios::spec::detail

// The sentence forms in the order they are tried, the rule that picks a sentence's form, and the
// problems the forms' examples are read in.
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "form.hpp"
#include "grammar.hpp"

namespace helios::spec::grammar {

const std::vector<CompiledForm>& compiled_forms() {
  static const std::vector<Form> all = [] {
    std::vector<Form> f = forms::all_forms();
    std::sort(f.begin(), f.end(), [](const Form& a, const Form& b) { return a.order < b.order; });
    for (std::size_t k = 1; k < f.size(); ++k)
      if (f[k].order == f[k - 1].order)
        throw std::logic_error("the forms '" + f[k - 1].name + "' and '" + f[k].name + "' have one order");
    return f;
  }();
  static const std::vector<CompiledForm> compiled = [] {
    std::vector<CompiledForm> c;
    for (const Form& f : all) c.push_back({&f, re(f.pattern)});
    return c;
  }();
  return compiled;
}

const Form* form_of(const std::string& sentence) {
  std::smatch m;
  for (const auto& f : compiled_forms())
    if (std::regex_match(sentence, m, f.pattern)) return f.form;
  return nullptr;
}

// A sentence of the controlled English: the first form whose pattern matches it whole reads it; a
// sentence no form matches is read as facts in other words (apply_facts.cpp).
void Builder::handle(const std::string& s) {
  std::smatch m;
  for (const auto& f : compiled_forms())
    if (std::regex_match(s, m, f.pattern)) return f.form->read(*this, m);
  if (detail::states_nothing(s, body_names()))
    throw sentence_error("it matches no form of the controlled English (see tools/lib/src/spec/LANGUAGE.md)");
  apply_facts(facts_of(s));
}

namespace {

using Groups = std::vector<std::pair<std::string, std::string>>;

// The problems an example is read in, one group of facts a line: S01's ("sun"), an Earth orbit
// ending on the geostationary one ("earth", S14's), and S02's planets ("planets").
const std::map<std::string, Groups>& contexts() {
  static const std::map<std::string, Groups> c = {
      {"sun",
       {{"name", "Problem T01: a form's example."},
        {"central", "The central body is the Sun."},
        {"engine",
         "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg."},
        {"departure",
         "The spacecraft departs at t = 0 days from position [-140699693, -51614428, 980] km with velocity "
         "[9.774596, -28.07828, 4.337725e-4] km/s."},
        {"tof", "The time of flight is 348.795 days."},
        {"arrival",
         "At the final time the spacecraft rendezvouses with position [-172682023, 176959469, 7948912] km and "
         "velocity [-16.427384, -14.860506, 9.21486e-2] km/s."},
        {"objective", "Minimize the fuel consumption."}}},
      {"earth",
       {{"name", "Problem T02: a form's example about the Earth."},
        {"central", "The central body is the Earth."},
        {"engine",
         "The spacecraft has a maximum thrust of 60 N, a specific impulse of 2000 s and an initial mass of 1500 kg."},
        {"departure",
         "The spacecraft departs at t = 0 days from position [-46500, 0, 0] km with velocity [0, -1.4529784332509441, "
         "-0.17851317059960614] km/s."},
        {"tof", "The time of flight is free, at most 2 days."},
        {"arrival", "At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km."},
        {"objective", "Minimize the time of flight."}}},
      {"planets",
       {{"name", "Problem T03: a form's example between the planets."},
        {"central", "The central body is the Sun."},
        {"engine",
         "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and an initial mass of 1000 kg."},
        {"departure", "The spacecraft departs at MJD2000 400 from Earth."},
        {"tof", "The time of flight is 900 days."},
        {"arrival", "At the final time the spacecraft rendezvouses with Mars."},
        {"objective", "Minimize the fuel consumption."}}},
  };
  return c;
}

// Sentences an example may add before its own ("+nikko").
const std::map<std::string, std::string>& extras() {
  static const std::map<std::string, std::string> e = {
      {"nikko",
       "Nikko moves on a Keplerian orbit about the Sun with a = 2.2375176 AU, e = 0.1052183, i = 5.70117 deg, node "
       "= 71.94548 deg, argument of perihelion = 2.08462 deg and mean anomaly = 287.3844555 deg at MJD 56800."},
      {"visit", "The spacecraft rendezvouses with Nikko between day 100 and day 200."},
      {"sail", "The spacecraft is an ideal flat solar sail with a characteristic acceleration of 1.0 mm/s^2 at 1 AU."},
      {"min_time", "The time of flight is free, between 100 days and 1000 days.\nMinimize the time of flight."},
      {"final_mass",
       "The spacecraft has a maximum thrust of 0.5 N, a specific impulse of 2000 s and a final mass of 800 kg."},
      {"free_end", "The time of flight is 1 day.\nAt the final time the spacecraft is on a circular orbit."},
      {"to_azusa", "At the final time the spacecraft rendezvouses with Azusa."},
      {"scaled_orbits",
       "The spacecraft departs at t = 0 days from position [2, 0, 0] km with velocity [0, 0.7, 0] km/s.\n"
       "At the final time the spacecraft is on the circular equatorial orbit of radius 3 km."},
      {"window_epoch", "The spacecraft departs at MJD2000 11100 from Earth."},
      {"from_earth", "The spacecraft departs from Earth."},
      {"earth_j2", "The central body is the Earth with J2 coefficient 1.08262668e-3."},
  };
  return e;
}

}  // namespace

std::string example_text(const FormExample& example) {
  std::istringstream words(example.context);
  std::string base, word;
  words >> base;
  if (!contexts().count(base)) throw std::logic_error("an example names the unknown context '" + base + "'");
  std::set<std::string> omit;
  std::string added;
  while (words >> word) {
    const std::string name = word.substr(1);
    if (word[0] == '-')
      omit.insert(name);
    else if (word[0] == '+' && extras().count(name))
      added += extras().at(name) + "\n";
    else
      throw std::logic_error("an example's context has the word '" + word + "'");
  }
  std::string text;
  for (const auto& [group, line] : contexts().at(base))
    if (!omit.erase(group)) text += line + "\n";
  if (!omit.empty()) throw std::logic_error("an example omits '" + *omit.begin() + "', no group of " + base);
  return text + added + example.sentence + "\n";
}

}  // namespace helios::spec::grammar

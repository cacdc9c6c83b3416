// The pieces every sentence form uses: numbers with units, vectors, names and clause lists.
#include "grammar.hpp"
#include "fact_scan.hpp"

#include <cctype>
#include <cstdio>
#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {

double number(const std::string& s) {
  try {
    return std::stod(s);
  } catch (const std::out_of_range&) {
    throw sentence_error("the number " + s + " is outside the range of a double (magnitudes 2.2e-308 to 1.8e308)");
  }
}

double quantity(const std::smatch& m, std::size_t idx, Dimension d) {
  try {
    return number(m[idx].str()) * to_spec_unit(d, m[idx + 1].str());
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
}

json vector3(const std::smatch& m, std::size_t idx, Dimension d) {
  double f = 0;
  try {
    f = to_spec_unit(d, m[idx + 3].str());
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
  return json::array({number(m[idx].str()) * f, number(m[idx + 1].str()) * f, number(m[idx + 2].str()) * f});
}

std::regex re(const std::string& pattern) {
  return std::regex("^" + pattern + "$", std::regex::icase);
}

// Known gravitational parameters [km^3/s^2] for a central body named without one.
std::optional<double> known_mu(const std::string& body) {
  using namespace helios::astro;
  const std::string key = lowercase(body);
  if (key == "sun") return MU_SUN_KM3_S2;
  if (key == "earth") return MU_EARTH_KM3_S2;
  if (key == "mars") return MU_MARS_KM3_S2;
  return std::nullopt;
}

std::optional<double> known_radius(const std::string& body) {
  const std::string key = lowercase(body);
  if (key == "earth") return helios::astro::R_EARTH_KM;
  if (key == "mars") return helios::astro::R_MARS_KM;
  return std::nullopt;
}

std::optional<double> surface_radius(const std::string& body) {
  constexpr double kSunRadiusKm = 695700.0;  // IAU 2015 nominal solar radius
  if (lowercase(body) == "sun") return kSunRadiusKm;
  return known_radius(body);
}

namespace {

// The value of a number word ("six", "twenty"), or -1.
int number_word(const std::string& word) {
  static const std::map<std::string, int> values = {
      {"zero", 0},      {"one", 1},       {"two", 2},       {"three", 3},    {"four", 4},      {"five", 5},
      {"six", 6},       {"seven", 7},     {"eight", 8},     {"nine", 9},     {"ten", 10},      {"eleven", 11},
      {"twelve", 12},   {"thirteen", 13}, {"fourteen", 14}, {"fifteen", 15}, {"sixteen", 16},  {"seventeen", 17},
      {"eighteen", 18}, {"nineteen", 19}, {"twenty", 20},   {"thirty", 30},  {"forty", 40},    {"fifty", 50},
      {"sixty", 60},    {"seventy", 70},  {"eighty", 80},   {"ninety", 90},  {"hundred", 100}, {"thousand", 1000}};
  const auto it = values.find(lowercase(word));
  return it == values.end() ? -1 : it->second;
}

bool is_unit(const std::string& word) {
  for (Dimension d : {Dimension::Length, Dimension::Speed, Dimension::Force, Dimension::Time, Dimension::Mass,
                      Dimension::GravParam, Dimension::Acceleration, Dimension::Angle}) {
    try {
      to_spec_unit(d, word);
      return true;
    } catch (const std::invalid_argument&) {
    }
  }
  return false;
}

}  // namespace

std::string with_digits(const std::string& sentence) {
  struct Word {
    std::size_t begin, end;
    std::string text;
  };
  std::vector<Word> words;
  static const std::regex letters("[A-Za-z]+");
  for (std::sregex_iterator it(sentence.begin(), sentence.end(), letters), end; it != end; ++it)
    words.push_back(
        {static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->position() + it->length()), it->str()});
  // Words joined by a space or a hyphen only.
  const auto joined = [&](std::size_t k) {
    const std::string between = sentence.substr(words[k - 1].end, words[k].begin - words[k - 1].end);
    return between == " " || between == "-";
  };
  std::string out = sentence;
  for (std::size_t u = words.size(); u-- > 1;) {
    if (!is_unit(words[u].text) || number_word(words[u - 1].text) < 0 || !joined(u)) continue;
    std::size_t first = u - 1;  // back over number words, and "and" between two of them
    while (first > 0 && joined(first) &&
           (number_word(words[first - 1].text) >= 0 || (lowercase(words[first - 1].text) == "and" && first > 1 &&
                                                        joined(first - 1) && number_word(words[first - 2].text) >= 0)))
      --first;
    long total = 0, current = 0;
    for (std::size_t k = first; k < u; ++k) {
      const int v = number_word(words[k].text);
      if (v == 100)
        current = std::max(current, 1L) * 100;
      else if (v == 1000)
        total += std::max(current, 1L) * 1000, current = 0;
      else if (v > 0)
        current += v;
    }
    out.replace(words[first].begin, words[u - 1].end - words[first].begin, std::to_string(total + current));
    u = first + 1;
  }
  return out;
}

// Splits "a, b, c" at the commas outside parentheses.
std::vector<std::string> top_level_items(const std::string& list) {
  std::vector<std::string> items(1);
  int depth = 0;
  for (char c : list) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (c == ',' && depth == 0) {
      items.emplace_back();
      continue;
    }
    items.back() += c;
  }
  for (auto& s : items) {
    s.erase(0, s.find_first_not_of(' '));
    s.erase(s.find_last_not_of(' ') + 1);
  }
  return items;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(' ') - b + 1);
}

// Factor converting `unit` into the spec unit of `d`, as a sentence error when unknown.
double unit_factor(Dimension d, const std::string& unit) {
  try {
    return to_spec_unit(d, unit);
  } catch (const std::invalid_argument& e) {
    throw sentence_error(e.what());
  }
}

// Splits a clause list at ';', ',', ', and' and ' and '.
std::vector<std::string> clauses_of(const std::string& list) {
  static const std::regex split(R"(\s*(?:;\s*|,\s*and\s+|,\s*|\s+and\s+)\s*)", std::regex::icase);
  std::vector<std::string> out;
  for (std::sregex_token_iterator it(list.begin(), list.end(), split, -1), end; it != end; ++it) out.push_back(*it);
  return out;
}

bool is_planet(const std::string& key) {
  return key == "earth" || key == "mars" || key == "venus" || key == "jupiter";
}

// A body's name as written: letters, digits and underscores, starting with a letter. It becomes a
// constraint id (in lower case) and a string inside the generated C++, so nothing else is accepted.
std::string body_name(const std::string& phrase) {
  static const std::regex the = re(R"(the (.+))");
  static const std::regex ok("[A-Za-z][A-Za-z0-9_]*");
  std::smatch m;
  const std::string name = std::regex_match(phrase, m, the) ? m[1].str() : phrase;
  if (!std::regex_match(name, ok))
    throw sentence_error("'" + phrase +
                         "' is not a body name: use letters, digits and underscores, starting with a letter (e.g. "
                         "Rock_1423)");
  const std::string key = lowercase(name);
  if (key == "departure" || key == "arrival")
    throw sentence_error("'" + name + "' cannot name a body: '" + key + "' is the id of the " + key + " constraint");
  return name;
}

// "MJD N" or "MJD2000 N" as MJD2000.
double mjd2000_of(const std::string& scale, const std::string& value) {
  try {
    return detail::day_number_epoch(scale, number(value), scale + " " + value);
  } catch (const detail::facts_error& e) {
    throw sentence_error(e.what());
  }
}

}  // namespace helios::spec::grammar

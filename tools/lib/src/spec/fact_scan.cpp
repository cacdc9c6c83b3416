// The fact reader's quantity scanner: words, numbers, vectors with their units, epochs (read by
// fact_dates.cpp) and windows.
#include "fact_scan.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "facts.hpp"
#include "helios/spec/units.hpp"

namespace helios::spec::detail {

double number_of(const std::string& s) {
  try {
    return std::stod(s);
  } catch (const std::out_of_range&) {
    throw facts_error("the number " + s + " is outside the range of a double (magnitudes 2.2e-308 to 1.8e308)");
  }
}

namespace {

bool known_unit(const std::string& unit) {
  for (Dimension d : {Dimension::Length, Dimension::Speed, Dimension::Force, Dimension::Time, Dimension::Duration,
                      Dimension::Mass, Dimension::GravParam, Dimension::Acceleration, Dimension::Angle}) {
    try {
      to_spec_unit(d, unit);
      return true;
    } catch (const std::invalid_argument&) {
    }
  }
  return false;
}

bool word_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

// The unit after a quantity, starting at `i` (spaces skipped); "" and `i` unchanged when none.
std::string read_unit(const std::string& s, std::size_t& i) {
  std::size_t j = i;
  while (j < s.size() && s[j] == ' ') ++j;
  if (j == i && j < s.size() && s[j] == '-') ++j;  // a 30-day stay
  std::size_t k = j;
  while (k < s.size() && (word_char(s[k]) || s[k] == '^' || s[k] == '/')) ++k;
  if (k == j || !std::isalpha(static_cast<unsigned char>(s[j]))) return "";
  std::string unit = s.substr(j, k - j);
  if (lowercase(unit) == "metric") {  // "metric tons"
    std::size_t m = k;
    while (m < s.size() && s[m] == ' ') ++m;
    std::size_t n = m;
    while (n < s.size() && word_char(s[n])) ++n;
    const std::string next = lowercase(s.substr(m, n - m));
    if (next == "ton" || next == "tons" || next == "tonne" || next == "tonnes") {
      i = n;
      return "t";
    }
  }
  static const std::regex per_s2(R"(^ s\^-2\b)");  // "km^3 s^-2"
  std::smatch m;
  const std::string rest = s.substr(k);
  if ((lowercase(unit) == "km^3" || lowercase(unit) == "m^3") && std::regex_search(rest, m, per_s2)) {
    k += m.length(0);
    unit += "/s^2";
  }
  if (!known_unit(unit)) return "";
  i = k;
  return unit;
}

// "(a, b, c)": a '(' followed by a number-like character, with a comma before its ')'.
bool paren_vector(const std::string& s, std::size_t i) {
  std::size_t j = i + 1;
  while (j < s.size() && s[j] == ' ') ++j;
  if (j == s.size() || !(std::isdigit(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == '+' || s[j] == '.'))
    return false;
  const std::size_t close = s.find_first_of("()", j);
  return close != std::string::npos && s[close] == ')' && s.find(',', j) < close;
}

// Parentheses around words only ("Thrust (max): 0.8 N", "the central body (Earth)") qualify the
// words before them, so they do not cut the clause; with a number inside they still do.
std::string unwrap_word_parens(std::string s) {
  for (std::size_t open = s.find('('); open != std::string::npos; open = s.find('(', open + 1)) {
    const std::size_t close = s.find_first_of("()", open + 1);
    if (close == std::string::npos || s[close] != ')') continue;
    const std::string inside = s.substr(open + 1, close - open - 1);
    if (inside.find_first_of("0123456789[]") != std::string::npos) continue;
    s[open] = s[close] = ' ';
  }
  return s;
}

// "between E and E", "from E to E" and "E to E" (E a date or "day N") as one window; two plain numbers
// so joined, the second with a unit the first has too or lacks ("between 50 and 600 days"), as a range.
std::vector<Token> windows_of(const std::vector<Token>& in) {
  const auto epoch = [&](std::size_t k) {
    return k < in.size() && in[k].kind == Token::Value && (in[k].q.date || in[k].q.day);
  };
  const auto plain = [&](std::size_t k) {
    return k < in.size() && in[k].kind == Token::Value && !in[k].q.vector && !in[k].q.date && !in[k].q.day;
  };
  std::vector<Token> out;
  for (std::size_t k = 0; k < in.size(); ++k) {
    const bool between = !out.empty() && out.back().kind == Token::Word && out.back().word == "between";
    const bool joined =
        k + 1 < in.size() && ((between && in[k + 1].kind == Token::Separator && in[k + 1].word == "and") ||
                              (in[k + 1].kind == Token::Word && in[k + 1].word == "to"));
    const bool window = joined && epoch(k) && epoch(k + 2);
    const bool range = joined && plain(k) && plain(k + 2) && !in[k + 2].q.unit.empty() &&
                       (in[k].q.unit.empty() || in[k].q.unit == in[k + 2].q.unit);
    if (!window && !range) {
      out.push_back(in[k]);
      continue;
    }
    if (!out.empty() && out.back().kind == Token::Word && (between || out.back().word == "from")) out.pop_back();
    Token t{Token::Value, "", {}};
    t.q.window = window;
    t.q.range = range;
    t.q.nums = {in[k].q.nums[0], in[k + 2].q.nums[0]};
    t.q.absolute = {in[k].q.date, in[k + 2].q.date};
    t.q.unit = range ? in[k + 2].q.unit : "";
    t.q.texts = {in[k].q.texts[0], in[k + 2].q.texts[0]};
    t.q.written = in[k].q.written + (between ? " and " : " to ") + in[k + 2].q.written;
    out.push_back(t);
    k += 2;
  }
  return out;
}

const std::regex& number_pattern() {
  static const std::regex num(R"(^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)");
  return num;
}

// "[a, b, c] UNIT" or "(a, b, c) UNIT" at s[i]: a vector with its unit; i moves past it.
Quantity read_vector(const std::string& s, std::size_t& i) {
  const char open = s[i], close = open == '[' ? ']' : ')';
  const std::size_t end = s.find(close, i);
  if (end == std::string::npos) throw facts_error(std::string("a '") + open + "' has no closing '" + close + "'");
  const std::string body = s.substr(i + 1, end - i - 1);
  Quantity q;
  q.vector = true;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = body.find(',', from);
    std::string item = body.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    std::smatch n;
    if (!std::regex_match(item, n, number_pattern()) || n.length(0) != static_cast<std::ptrdiff_t>(item.size()))
      throw facts_error("the vector " + s.substr(i, end - i + 1) + " has a component '" + item +
                        "' that is not a number");
    q.nums.push_back(number_of(item));
    q.texts.push_back(item);
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (q.nums.size() != 3)
    throw facts_error("the vector " + s.substr(i, end - i + 1) + " has " + std::to_string(q.nums.size()) +
                      " components; a position or velocity has 3");
  i = end + 1;
  q.unit = read_unit(s, i);
  q.written = "[" + q.texts[0] + ", " + q.texts[1] + ", " + q.texts[2] + "]" + (q.unit.empty() ? "" : " " + q.unit);
  return q;
}

// The number `text` (its first characters matched as one) at s[i], with its unit; i moves past them.
Quantity read_number(const std::string& s, std::size_t& i, std::string text) {
  // thousands written with commas: "3,100 s", "1,600,000 kg"
  static const std::regex thousands(R"(^\d{1,3}(?:,\d{3})+(?:\.\d+)?(?![\d,]))");
  std::smatch t;
  const std::string rest = s.substr(i);
  if (std::regex_search(rest, t, thousands)) text = t.str(0);
  Quantity q;
  q.texts = {text};
  std::string plain = text;
  plain.erase(std::remove(plain.begin(), plain.end(), ','), plain.end());
  q.nums = {number_of(plain)};
  i += text.size();
  q.unit = read_unit(s, i);
  q.written = q.texts[0] + (q.unit.empty() ? "" : " " + q.unit);
  return q;
}

// "400 days after 1 January 2000", "2 weeks before MJD 60000": a duration `q` just read, then
// "after" or "before" and a date, as that date; i moves past it. False when no date follows.
bool relative_date(const std::string& s, std::size_t& i, Quantity& q) {
  static const std::regex side(R"(^ (after|before) )", std::regex::icase);
  std::smatch m;
  const std::string rest = s.substr(i);
  Quantity date;
  std::size_t length = 0;
  if (q.unit.empty() || !std::regex_search(rest, m, side) || !(length = read_date(rest.substr(m.length(0)), date)))
    return false;
  double days = 0;
  try {
    days = q.nums[0] * to_spec_unit(Dimension::Time, q.unit);
  } catch (const std::invalid_argument&) {
    return false;  // "5 km after ...": no duration
  }
  q.date = true;
  q.nums = {date.nums[0] + (lowercase(m[1].str()) == "after" ? days : -days)};
  q.written = q.written + " " + m[1].str() + " " + date.texts[0];
  q.texts = {q.written};
  q.unit.clear();
  i += m.length(0) + length;
  return true;
}

// The word at s[i] (a possessive "'s" dropped), or "day N" as a day counted from the epoch; i moves
// past it, and past a hyphen joining it to the next word.
Token read_word(const std::string& s, std::size_t& i) {
  std::size_t k = i;
  while (k < s.size() && (word_char(s[k]) || s[k] == '\'')) ++k;
  std::string text = s.substr(i, k - i);
  if (text.size() > 2 && text.compare(text.size() - 2, 2, "'s") == 0) text.resize(text.size() - 2);
  std::string w = lowercase(text);
  i = k;
  // an element's symbol before '=' ("a = 1.2 AU", "Omega = 80 deg" the node, "omega" the argument)
  static const std::map<std::string, std::string> symbols = {
      {"a", "semi major axis"}, {"e", "eccentricity"}, {"i", "inclination"}, {"M", "mean anomaly"},
      {"nu", "true anomaly"},   {"Omega", "raan"},     {"omega", "argp"},    {"w", "argp"}};
  const std::size_t eq = s.find_first_not_of(' ', i);
  if (eq != std::string::npos && s[eq] == '=' && symbols.count(text)) w = symbols.at(text);
  std::smatch d;
  const std::string after = i < s.size() && s[i] == ' ' ? s.substr(i + 1) : "";
  if (w == "day" && std::regex_search(after, d, number_pattern())) {
    Quantity q;  // "day 120": a day counted from the epoch
    q.day = true;
    q.texts = {d.str(0)};
    q.nums = {number_of(d.str(0))};
    q.written = "day " + d.str(0);
    i += 1 + d.length(0);
    return {Token::Value, "", q};
  }
  if (i < s.size() && s[i] == '-' && i + 1 < s.size() && std::isalpha(static_cast<unsigned char>(s[i + 1]))) ++i;
  if (w == "and") return {Token::Separator, w, {}};
  return {Token::Word, w, {}, text};
}

}  // namespace

std::optional<double> epoch_of(const std::string& text) {
  const std::vector<Token> tokens = scan(text);
  if (tokens.size() != 1 || tokens[0].kind != Token::Value || !tokens[0].q.date) return std::nullopt;
  return tokens[0].q.nums[0];
}

std::vector<Token> scan(const std::string& sentence) {
  // Superscripts as written in many texts: km³/s² is km^3/s^2.
  // Ω and ω are the node and the argument of periapsis, ° is deg.
  std::string raw = replace_all(replace_all(sentence, "\xC2\xB3", "^3"), "\xC2\xB2", "^2");
  raw = replace_all(replace_all(replace_all(raw, "\xCE\xA9", "RAAN"), "\xCF\x89", "argp"), "\xC2\xB0", " deg");
  raw = replace_all(raw, "\xCE\xBD", "nu");  // ν, the true anomaly
  const std::string s = unwrap_word_parens(raw);
  std::vector<Token> out;
  std::size_t i = 0;
  const auto prev_word = [&] { return i > 0 && word_char(s[i - 1]); };
  while (i < s.size()) {
    const char c = s[i];
    std::smatch m;
    const std::string rest = s.substr(i);
    Quantity date;
    std::size_t date_len = 0;
    if (c == ' ' || c == ':' || c == '=') {
      ++i;
    } else if (!prev_word() && std::isalnum(static_cast<unsigned char>(c)) && (date_len = read_date(rest, date)) > 0) {
      i += date_len;
      date.date = true;
      date.written = date.texts[0];
      out.push_back({Token::Value, "", date});
    } else if (c == '[' || (c == '(' && paren_vector(s, i))) {
      out.push_back({Token::Value, "", read_vector(s, i)});
    } else if (!prev_word() && (std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+') &&
               std::regex_search(rest, m, number_pattern())) {
      Quantity q = read_number(s, i, m.str(0));
      relative_date(s, i, q);
      out.push_back({Token::Value, "", q});
    } else if (c == ',' || c == ';' || c == '(' || c == ')') {
      out.push_back({Token::Separator, "", {}});
      ++i;
    } else if (word_char(c)) {
      out.push_back(read_word(s, i));
    } else {
      if (static_cast<unsigned char>(c) >= 0x80) throw facts_error("cannot read a non-ASCII character here");
      throw facts_error(std::string("cannot read the character '") + c + "' here");
    }
  }
  return windows_of(out);
}

}  // namespace helios::spec::detail

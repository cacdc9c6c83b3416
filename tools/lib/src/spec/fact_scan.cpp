// The fact reader's quantity scanner: words, numbers, vectors with their units, epochs and windows.
#include "fact_scan.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "facts.hpp"
#include "helios/astro/constants.hpp"
#include "helios/spec/units.hpp"

namespace helios::spec::detail {
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

double number_of(const std::string& s) {
  try {
    return std::stod(s);
  } catch (const std::out_of_range&) {
    throw facts_error("the number " + s + " is outside the range of a double (magnitudes 2.2e-308 to 1.8e308)");
  }
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

// Days from 2000-01-01 to the civil date y-m-d (proleptic Gregorian calendar).
double days_from_2000(int y, int m, int d) {
  y -= m <= 2;
  const int era = (y >= 0 ? y : y - 399) / 400;
  const int yoe = y - era * 400;
  const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return static_cast<double>(era) * 146097.0 + doe - 719468.0 - 10957.0;
}

int month_of(const std::string& word) {
  static const std::map<std::string, int> months = {
      {"january", 1},  {"jan", 1},    {"february", 2},  {"feb", 2},       {"march", 3},     {"mar", 3},
      {"april", 4},    {"apr", 4},    {"may", 5},       {"june", 6},      {"jun", 6},       {"july", 7},
      {"jul", 7},      {"august", 8}, {"aug", 8},       {"september", 9}, {"sep", 9},       {"sept", 9},
      {"october", 10}, {"oct", 10},   {"november", 11}, {"nov", 11},      {"december", 12}, {"dec", 12}};
  const auto it = months.find(lowercase(word));
  return it == months.end() ? 0 : it->second;
}

// The first and the last day of the years an epoch may lie in, as MJD2000.
const double kFirstEpoch = days_from_2000(kFirstEpochYear, 1, 1);
const double kEndOfEpochs = days_from_2000(kLastEpochYear + 1, 1, 1);

double civil_date(const std::string& text, int y, int m, int d) {
  static const int days_in[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (m < 1 || m > 12 || d < 1 || d > days_in[m - 1] ||
      (m == 2 && d == 29 && !(y % 4 == 0 && (y % 100 != 0 || y % 400 == 0))))
    throw facts_error("the date " + text + " does not exist");
  if (y < kFirstEpochYear || y > kLastEpochYear)
    throw facts_error("the date " + text + " lies outside the years 1900 to 2200");
  return days_from_2000(y, m, d);
}

// TAI - UTC [s] from the first day of each month in which it changed (IERS Bulletin C); no leap
// second has been announced since 2017, so later dates take 37 s.
struct LeapStep {
  int y, m;
  double tai_minus_utc;
};
constexpr LeapStep kLeapSteps[] = {
    {1972, 1, 10}, {1972, 7, 11}, {1973, 1, 12}, {1974, 1, 13}, {1975, 1, 14}, {1976, 1, 15}, {1977, 1, 16},
    {1978, 1, 17}, {1979, 1, 18}, {1980, 1, 19}, {1981, 7, 20}, {1982, 7, 21}, {1983, 7, 22}, {1985, 7, 23},
    {1988, 1, 24}, {1990, 1, 25}, {1991, 1, 26}, {1992, 7, 27}, {1993, 7, 28}, {1994, 7, 29}, {1996, 1, 30},
    {1997, 7, 31}, {1999, 1, 32}, {2006, 1, 33}, {2009, 1, 34}, {2012, 7, 35}, {2015, 7, 36}, {2017, 1, 37}};
constexpr double kTtMinusTai = 32.184;  // s

// An epoch on the scale `scale` (UTC, UT, GMT, Z, TAI, TT, TDB; "" is TDB) as TDB, MJD2000. UT
// (UT1) is read as UTC, which it follows within 0.9 s.
double as_tdb(double mjd2000, const std::string& scale, const std::string& text) {
  const std::string k = lowercase(scale);
  if (k.empty() || k == "tdb") return mjd2000;
  double tt = mjd2000;
  if (k == "utc" || k == "ut" || k == "gmt" || k == "z") {
    if (mjd2000 < days_from_2000(1972, 1, 1))
      throw facts_error("the epoch " + text +
                        " is in UTC before 1972, when UTC had no whole-second offset from TDB: give it in TDB");
    double tai_minus_utc = 0;
    for (const auto& step : kLeapSteps)
      if (mjd2000 >= days_from_2000(step.y, step.m, 1)) tai_minus_utc = step.tai_minus_utc;
    tt = mjd2000 + (tai_minus_utc + kTtMinusTai) / astro::DAY_S;
  } else if (k == "tai") {
    tt = mjd2000 + kTtMinusTai / astro::DAY_S;
  }
  // TDB - TT, the leading periodic terms [s] (Explanatory Supplement to the Astronomical Almanac)
  const double g = (357.53 + 0.98560028 * (tt - 0.5)) * astro::DEG_TO_RAD;
  return tt + (0.001657 * std::sin(g) + 0.000014 * std::sin(2 * g)) / astro::DAY_S;
}

}  // namespace

double day_number_epoch(const std::string& scale, double value, const std::string& text) {
  const std::string k = lowercase(scale);
  const double v = k == "mjd2000" ? value
                   : k == "mjd"   ? value - astro::MJD_MINUS_MJD2000
                                  : value - astro::JD_OF_MJD2000;
  if (!(v >= kFirstEpoch && v < kEndOfEpochs)) {
    const int year = static_cast<int>(std::floor(2000 + v / astro::JULIAN_YEAR_DAYS));
    throw facts_error("the epoch " + text + " falls in the year " + std::to_string(year) +
                      "; epochs lie in the years 1900 to 2200 (MJD2000 = MJD - 51544 = JD - 2451544.5)");
  }
  return v;
}

namespace {

// An epoch written at the start of `rest`: a calendar date (2025-03-01 [00:00 UTC], 15 January
// 2030, March 3, 2028) or a day number on a named scale (MJD 60000, 9000 MJD2000, 10000 (MJD2000),
// JD 2460676.5), each with an optional time scale (TDB when none). Fills `q` (its MJD2000 in TDB)
// and returns the characters read, 0 when none.
std::size_t read_date(const std::string& rest, Quantity& q) {
  static const std::string n = R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)";
  static const std::string scale = R"((?: ?(UTC|UT|GMT|TDB|TT|TAI|Z)\b)?)";
  static const std::string clock = R"((\d{1,2}):(\d{2})(?::(\d{2}(?:\.\d+)?))?)";
  static const std::regex iso(R"(^(\d{4})-(\d{1,2})-(\d{1,2})(?:(?:T| at | ))" + clock + ")?" + scale,
                              std::regex::icase);
  static const std::regex dmy(R"(^(\d{1,2})(?:st|nd|rd|th)? ([A-Za-z]+)\.?,? (\d{4})\b(?:,? (?:at )?)" + clock + ")?" +
                              scale);
  static const std::regex mdy(R"(^([A-Za-z]+)\.? (\d{1,2})(?:st|nd|rd|th)?,? (\d{4})\b(?:,? (?:at )?)" + clock + ")?" +
                              scale);
  static const std::regex before("^(MJD2000|MJD|JD)\\b ?(" + n + ")" + scale, std::regex::icase);
  static const std::regex after("^(" + n + R"() ?(?:\( ?(MJD2000|MJD|JD) ?\)|(MJD2000|MJD|JD)\b))" + scale,
                                std::regex::icase);
  std::smatch m;
  // matched at the start only, never searched along the rest of the sentence
  constexpr auto kAtStart = std::regex_constants::match_continuous;
  const auto found = [&](double mjd2000, std::size_t scale_group) {
    q.texts = {m.str(0)};
    q.nums = {as_tdb(mjd2000, m[scale_group].str(), m.str(0))};
    return static_cast<std::size_t>(m.length(0));
  };
  // A calendar date with its time of day in groups 4 to 6, if any.
  const auto dated = [&](int y, int mo, int d) {
    double v = civil_date(m.str(0), y, mo, d);
    if (m[4].matched) {
      const int hh = std::stoi(m[4]), mm = std::stoi(m[5]);
      const double ss = m[6].matched ? std::stod(m[6]) : 0.0;
      if (hh > 23 || mm > 59 || ss >= 60) throw facts_error("the time of day in " + m.str(0) + " does not exist");
      v += (hh * 3600.0 + mm * 60.0 + ss) / astro::DAY_S;
    }
    return found(v, 7);
  };
  const char c = rest[0];
  if (std::isdigit(static_cast<unsigned char>(c))) {
    if (std::regex_search(rest, m, iso, kAtStart)) return dated(std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]));
    if (std::regex_search(rest, m, dmy, kAtStart) && month_of(m[2]) != 0)
      return dated(std::stoi(m[3]), month_of(m[2]), std::stoi(m[1]));
  }
  if (std::isalpha(static_cast<unsigned char>(c)) && std::regex_search(rest, m, mdy, kAtStart) && month_of(m[1]) != 0)
    return dated(std::stoi(m[3]), month_of(m[1]), std::stoi(m[2]));
  if (std::regex_search(rest, m, before, kAtStart)) return found(day_number_epoch(m[1], number_of(m[2]), m.str(0)), 3);
  if (std::regex_search(rest, m, after, kAtStart))
    return found(day_number_epoch(m[2].matched ? m[2] : m[3], number_of(m[1]), m.str(0)), 4);
  return 0;
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

}  // namespace

namespace {

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

#pragma once
// The fact reader's quantity scanner (internal to tools/lib/src/spec): a sentence into words and
// quantities: numbers and vectors with the unit written after them, epochs (calendar dates, MJD,
// MJD2000, JD) and windows between two of them.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace helios::spec::detail {

// A number or a vector, with the unit written after it ("" when none).
struct Quantity {
  std::vector<double> nums;
  std::vector<std::string> texts;
  std::string unit, written;
  bool vector = false;
  bool date = false;               // an epoch: nums holds its MJD2000
  bool day = false;                // "day N": N days after the epoch
  bool window = false;             // "between E and E", "from E to E": nums holds both bounds
  bool range = false;              // "between N and Q", "from N to Q": two numbers, one unit (the second's)
  std::array<bool, 2> absolute{};  // a window's bounds: MJD2000 (a date) or days after the epoch
  // A bound written just before it ("at most 0.5 N", "at least 300 km"), with its words.
  bool at_most = false, at_least = false;
  std::string bound_words;
};

struct Token {
  enum Kind { Word, Value, Separator } kind;
  std::string word;
  Quantity q;
  std::string text = "";  // a word as written
};

// Epochs lie in these years: a day number outside them is a misread scale, not a date.
constexpr int kFirstEpochYear = 1900;
constexpr int kLastEpochYear = 2200;

// A day number on the scale "MJD2000", "MJD" or "JD" as MJD2000; throws facts_error naming `text`
// when it falls outside the years above.
double day_number_epoch(const std::string& scale, double value, const std::string& text);

// The number written `s`; throws facts_error beyond the range of a double.
double number_of(const std::string& s);

// An epoch written at the start of `rest` (fact_dates.cpp): fills `q` with its MJD2000 in TDB and
// returns the characters read, 0 when none starts there.
std::size_t read_date(const std::string& rest, Quantity& q);

// The tokens of `sentence`; throws facts_error on a character, date or unit it cannot read.
std::vector<Token> scan(const std::string& sentence);

// `text` read whole as one date (a calendar date, a day number on a named scale, "N days after
// DATE"), as MJD2000; none when it is not one date. Throws facts_error as scan does.
std::optional<double> epoch_of(const std::string& text);

}  // namespace helios::spec::detail

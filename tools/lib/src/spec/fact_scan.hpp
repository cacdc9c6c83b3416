#pragma once
// The fact reader's quantity scanner (internal to tools/lib/src/spec): a sentence into words and
// quantities: numbers and vectors with the unit written after them, epochs (calendar dates, MJD,
// MJD2000, JD) and windows between two of them.
#include <array>
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
  std::array<bool, 2> absolute{};  // a window's bounds: MJD2000 (a date) or days after the epoch
};

struct Token {
  enum Kind { Word, Value, Separator } kind;
  std::string word;
  Quantity q;
  std::string text = "";  // a word as written
};

// The tokens of `sentence`; throws facts_error on a character, date or unit it cannot read.
std::vector<Token> scan(const std::string& sentence);

}  // namespace helios::spec::detail

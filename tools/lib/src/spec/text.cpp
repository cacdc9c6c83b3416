// The problem text as items for the sentence reader: bounds, encoding, sentences.
#include "text.hpp"

#include <cctype>
#include <cstdio>

#include "helios/io/error.hpp"
#include "helios/spec/parse.hpp"

namespace helios::spec::detail {
namespace {

// The length of the UTF-8 sequence that starts with byte c, 0 when c cannot start one.
int utf8_length(unsigned char c) {
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return 2;
  if (c >= 0xE0 && c <= 0xEF) return 3;
  if (c >= 0xF0 && c <= 0xF4) return 4;
  return 0;
}

}  // namespace

void check_text(const std::string& text, const std::string& source) {
  if (text.size() > kMaxProblemBytes)
    throw input_error(source + ": the problem text is " + std::to_string(text.size()) + " bytes; the limit is " +
                      std::to_string(kMaxProblemBytes));
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const auto at = [&] { return source + ":" + std::to_string(line) + ": "; };
    if (c == '\n') {
      ++line;
      line_start = ++i;
      continue;
    }
    if (i - line_start >= kMaxSentenceChars)
      throw input_error(at() + "the line is longer than " + std::to_string(kMaxSentenceChars) +
                        " characters, the limit of a line or sentence");
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7F) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X", c);
      throw input_error(at() + "control byte " + code + " in the problem text (is it a binary file?)");
    }
    const int n = utf8_length(c);
    bool valid = n > 0 && i + n <= text.size();
    for (int k = 1; valid && k < n; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (valid && n > 2) {  // no overlong form, no UTF-16 surrogate, nothing above U+10FFFF
      const auto second = static_cast<unsigned char>(text[i + 1]);
      valid = !(c == 0xE0 && second < 0xA0) && !(c == 0xED && second > 0x9F) && !(c == 0xF0 && second < 0x90) &&
              !(c == 0xF4 && second > 0x8F);
    }
    if (!valid) throw input_error(at() + "the problem text is not valid UTF-8");
    i += n;
  }
}

std::vector<Sentence> split_sentences(const std::string& text) {
  std::vector<Sentence> out;
  std::string current;
  int line = 1, start_line = 1;
  bool in_comment = false, at_line_start = true;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      in_comment = false;
      at_line_start = true;
      if (!current.empty() && current.back() != ' ') current += ' ';
      continue;
    }
    if (in_comment) continue;
    if (at_line_start && c == '#') {
      in_comment = true;
      continue;
    }
    if (at_line_start && c == '|') {
      // A table line ends any sentence before it (like the end of the text does) and is one item.
      while (!current.empty() && current.back() == ' ') current.pop_back();
      if (!current.empty()) out.push_back({current, start_line});
      current.clear();
      const std::size_t end = std::min(text.find('\n', i), text.size());
      std::string row;
      for (std::size_t j = i; j < end; ++j) {
        const bool space = std::isspace(static_cast<unsigned char>(text[j])) != 0;
        if (space && (row.empty() || row.back() == ' ')) continue;
        row += space ? ' ' : text[j];
      }
      while (!row.empty() && row.back() == ' ') row.pop_back();
      out.push_back({row, line, true});
      i = end - 1;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) at_line_start = false;
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!current.empty() && current.back() != ' ') current += ' ';
      continue;
    }
    if (current.empty()) start_line = line;
    // A period ends a sentence unless a digit follows (inside a number) or it sits between two
    // letters ("r.v", a dot product).
    const auto is = [&](std::size_t k, int (*test)(int)) {
      return k < text.size() && test(static_cast<unsigned char>(text[k])) != 0;
    };
    const bool inside = is(i + 1, std::isdigit) || (i > 0 && is(i - 1, std::isalpha) && is(i + 1, std::isalpha));
    if (c == '.' && !inside) {
      while (!current.empty() && current.back() == ' ') current.pop_back();
      if (!current.empty()) out.push_back({current, start_line});
      current.clear();
      continue;
    }
    current += c;
  }
  while (!current.empty() && current.back() == ' ') current.pop_back();
  if (!current.empty()) out.push_back({current, start_line});
  return out;
}

}  // namespace helios::spec::detail

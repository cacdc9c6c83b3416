#pragma once
// The problem text as items for the sentence reader (internal to tools/lib/src/spec): the text
// checked against its bounds and encoding, then cut into sentences and table lines.
#include <string>
#include <vector>

namespace helios::spec::detail {

// A sentence, or one line of a table (a line starting with '|').
struct Sentence {
  std::string text;        // whitespace collapsed, final period removed
  int line = 0;            // line where it starts
  bool table_row = false;  // a table line, read as it stands
};

// Refuses a text the sentence reader must not see: over kMaxProblemBytes, not UTF-8, a NUL or
// control byte, a line over kMaxSentenceChars. Throws input_error naming `source` and the line; the
// offending byte is named by its code, never echoed.
void check_text(const std::string& text, const std::string& source);

// The sentences (a period not inside a number ends one; whitespace collapsed) and table lines (a
// line starting with '|') of `text`, with the lines they start on; '#' lines are comments.
std::vector<Sentence> split_sentences(const std::string& text);

}  // namespace helios::spec::detail

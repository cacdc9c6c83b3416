#pragma once
// A program's C++ text as the compile cache reads it (internal to tools/lib/src/solve): its tokens
// outside comments, its preprocessor lines, which lines start in code, and whether anything at
// namespace or class scope runs before main (at static initialisation), where it could read a
// parameter before the parameters file replaces it. A conservative reader: what it does not know
// for sure is reported, and the program is then compiled on its own (README.md, "The compile cache").
#include <cstddef>
#include <string>
#include <vector>

namespace helios::solve::detail {

struct Token {
  enum class Kind { Identifier, Number, String, Punctuator };
  Kind kind;
  std::string text;  // a digraph as the punctuator it spells ({ for <%)
  std::size_t line;  // from 1
};

struct ProgramText {
  std::vector<Token> tokens;              // outside comments and preprocessor lines
  std::vector<std::string> directives;    // the preprocessor lines, trimmed
  std::vector<bool> line_starts_in_code;  // [line - 1]: not inside a comment or a raw string
  std::string unreadable;                 // why the text cannot be read for sure ("" when it can)
};

// The tokens of `source`. A line splice, a universal character name in code, an unterminated
// comment or literal, or a comment opened on a preprocessor line makes it `unreadable`.
ProgramText read_program_text(const std::string& source);

// "" when no declaration at namespace or class scope of `tokens` can run code before main: each is
// a function, a type, an alias, a static_assert, a constexpr one, a variable whose initializer is
// made of literals only, the runtime's records (kProblem, kOrbitBodies) of names, and
// HELIOS_MODULE_TABLE; else the first that is not, with its line and why.
std::string code_before_main(const std::vector<Token>& tokens);

}  // namespace helios::solve::detail

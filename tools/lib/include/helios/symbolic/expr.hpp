#pragma once
// GiNaC helpers shared by the PMP engine, the verifier and the code generator: a symbol table,
// text round trip (expressions are stored as text that GiNaC parses back), numeric evaluation.
#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace helios::symbolic {

// Bounds of an expression text (README "Limits of input"); the derivations of the scenarios stay
// under 27 kB and 8 levels of parentheses.
inline constexpr std::size_t kMaxExpressionChars = std::size_t{1} << 20;
inline constexpr int kMaxExpressionDepth = 256;

// Symbols by name. All GiNaC symbols of a derivation come from one table so that parsing a
// stored text yields the very same symbols.
class SymbolTable {
 public:
  // The symbol called `name`, created on first use. Names are C identifiers.
  const GiNaC::symbol& get(const std::string& name);
  bool has(const std::string& name) const { return table_.count(name) > 0; }
  // Parses `text` allowing only known symbols; throws std::invalid_argument
  // "<where>: cannot parse expression '<text>': <reason>" (the text cut at 200 characters), also
  // for a text beyond kMaxExpressionChars or nested deeper than kMaxExpressionDepth (GiNaC's
  // parser recurses per parenthesis: ~7,800 levels overflowed the stack).
  GiNaC::ex parse(const std::string& text, const std::string& where) const;
  const GiNaC::symtab& symtab() const { return table_; }

 private:
  GiNaC::symtab table_;
};

// Text GiNaC's parser reads back (the default print form).
std::string to_text(const GiNaC::ex& e);

// C++ source for `e` (csrc_double print form).
std::string to_csrc(const GiNaC::ex& e);

using Values = std::map<std::string, double>;

// Evaluates `e` numerically with the given symbol values; throws std::invalid_argument naming
// a symbol without a value, std::domain_error if the result is not a finite real number.
double evaluate(const GiNaC::ex& e, const SymbolTable& table, const Values& values);

// Names of the symbols `e` depends on.
std::vector<std::string> free_symbols(const GiNaC::ex& e);

// True if expand(a - b) simplifies to zero (cheap exact check; false means "not shown").
bool symbolically_equal(const GiNaC::ex& a, const GiNaC::ex& b);

}  // namespace helios::symbolic

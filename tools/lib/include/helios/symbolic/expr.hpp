#pragma once
// GiNaC helpers shared by the PMP engine, the verifier and the code generator: a symbol table,
// text round trip (expressions are stored as text that GiNaC parses back), numeric evaluation.
#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace helios::symbolic {

// Bounds of an expression text (README "Limits of input"); the derivations of the scenarios stay
// under 27 kB and 8 levels of parentheses.
inline constexpr std::size_t kMaxExpressionChars = std::size_t{1} << 20;
inline constexpr int kMaxExpressionDepth = 256;
// Bound of the symbolic work an expression may ask for: the terms of its expansion, and of the
// expansion of each first derivative (the costate equations and the control law expand those).
// The scenarios ask for at most 268 (S10); (x+y+z+vx+vy+vz)^40 asks for 1.2e6, and the limit
// is about what the 1 MiB limit of an expression text holds (6,200 terms took 310 kB).
inline constexpr double kMaxExpandedTerms = 2e4;
// Bounds of an expression with its intermediates substituted (SymbolTable::substitute_on_parse),
// which only a reader holds (no text): its nodes counted along every path (each intermediate may be
// a power of the one before) and the terms of its expansion.
inline constexpr std::size_t kMaxSubstitutedNodes = 200000;
inline constexpr double kMaxSubstitutedTerms = 2e5;

// An upper bound of the number of terms of e.expand() or of the expansion of any sum inside a
// function or a negative power (which expand() multiplies out too): a positive integer power k
// of n terms gives at most C(n + k - 1, k), a product the product of its factors' counts. One
// walk of e's tree, no expansion.
double expanded_terms(const GiNaC::ex& e);

// GiNaC orders the terms of a sum and the factors of a product by hashes seeded with the address
// of each class's type name, which address-space randomization moves from run to run: the same
// derivation then printed, now and then, an expression in another order or with another sign
// pulled out of a denominator (S11's sail Jacobian, 3 runs in 12), so helios-gen's program and
// its compile-cache key were not a function of the derivation. Called first in main by the tools
// that print expressions, this re-executes the process once with randomization off (Linux
// personality ADDR_NO_RANDOMIZE), which fixes the order. It is a no-op where randomization is
// already off, and where the kernel or a seccomp policy refuses the flag the tool carries on as
// before. Not for helios-solve: the programs it runs would inherit the flag.
void fix_expression_order(char** argv);

// The identifiers an expression text names, in order, without function names (a word followed by
// '(') or a number's exponent: a scan of the text, no parse.
std::vector<std::string> identifiers(const std::string& text);

// True if `s` is a C identifier (what a symbol's name must be).
bool is_identifier(const std::string& s);

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
  // parser recurses per parenthesis: ~7,800 levels overflowed the stack), and for an expression
  // whose expansion or whose first derivatives' expansions would exceed kMaxExpandedTerms
  // ("... would expand to about N terms"), as written or with the substitutions made.
  GiNaC::ex parse(const std::string& text, const std::string& where) const;
  const GiNaC::symtab& symtab() const { return table_; }
  // From here on, parse() returns its expression with these symbols replaced: a reader that checks
  // claims by its own arithmetic substitutes the derivation's intermediates in whatever it reads.
  void substitute_on_parse(GiNaC::exmap substitutions) { substitutions_ = std::move(substitutions); }

 private:
  GiNaC::symtab table_;
  GiNaC::exmap substitutions_;
};

// Text GiNaC's parser reads back (the default print form).
std::string to_text(const GiNaC::ex& e);

// C++ source for `e` (csrc_double print form). Double: the functions as std::pow, std::sin, ...;
// Generic: unqualified, for code templated on its scalar type (which brings std's in by `using`).
enum class CppScalar { Double, Generic };
std::string to_csrc(const GiNaC::ex& e, CppScalar scalar = CppScalar::Double);

using Values = std::map<std::string, double>;

// Evaluates `e` numerically with the given symbol values; throws std::invalid_argument naming
// a symbol without a value, std::domain_error if the result is not a finite real number.
double evaluate(const GiNaC::ex& e, const SymbolTable& table, const Values& values);

// Names of the symbols `e` depends on.
std::vector<std::string> free_symbols(const GiNaC::ex& e);

// True if expand(a - b) simplifies to zero (cheap exact check; false means "not shown").
bool symbolically_equal(const GiNaC::ex& a, const GiNaC::ex& b);

}  // namespace helios::symbolic

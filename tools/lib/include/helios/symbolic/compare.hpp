#pragma once
// Exact comparison of GiNaC expressions beyond expand(a - b) (square roots reduced), and the
// feedback a comparison gives a reader: a printed form, a tidier form, a term by term diagnosis.
#include <ginac/ginac.h>

#include <cstddef>
#include <string>

namespace helios::symbolic {

// Expressions beyond this many nodes skip the exact comparison (a caller's random points still
// decide): GiNaC's expand/normal grow quickly on large rational forms and a verdict must stay < 1 s.
constexpr std::size_t kExactBudget = 1500;
constexpr std::size_t kTidyBudget = 4 * kExactBudget;  // tidy() leaves a larger expression as it is

// Number of nodes of an expression tree, counted up to `limit`.
std::size_t tree_size(const GiNaC::ex& e, std::size_t limit);

// The text of `e` for a message: to_text, or GiNaC's own print form where that fails.
std::string print(const GiNaC::ex& e);

// True if a == b is shown exactly: expand + normal, and for expressions with square roots the
// substitution B^(k/2) -> w^k followed by reduction of the numerator modulo w^2 - B (so that, e.g.,
// S^(-3/2) - 3 x^2 S^(-5/2) and (S - 3 x^2) S^(-5/2) compare equal). False means "not shown".
bool exact_equal(const GiNaC::ex& a, const GiNaC::ex& b);

// True if `a` is a constant nonzero multiple of `b`, shown exactly.
bool exact_proportional(const GiNaC::ex& a, const GiNaC::ex& b);

// A tidier form for feedback: in an expanded sum, the terms sharing a factor B^(k/2) whose
// cofactors add up to a multiple q*B become q*B^(k/2+1) (so that sum(l_i^2)*S^(-1/2) with
// S = sum(l_i^2) prints as sqrt(S)). Falls back to `e` on any trouble.
GiNaC::ex tidy(const GiNaC::ex& e);

// Term by term comparison of two expanded expressions: flipped signs, missing and extra terms.
// Empty when the forms are too different for the comparison to mean anything.
std::string term_diagnosis(const GiNaC::ex& expected, const GiNaC::ex& given);

}  // namespace helios::symbolic

#pragma once
// Expressions as mathematics for people (tools/lib/src/report/README.md, "Compact form"): LaTeX of a
// compact form of a stored expression. The stored form is fully expanded (S10's periapsis row is
// 5.7 kB of polynomial); the compact form is an exact rewrite of it:
//   - a norm named: a power of a sum of squares, (rx^2+ry^2+rz^2)^(-3/2), becomes r^{-3} with
//     r = sqrt(rx^2+ry^2+rz^2) stated once, also where the norm stands expanded in a polynomial;
//   - a difference named: a sum of squared differences, the expanded |v- - v_Mars|^2, becomes the
//     norm of a named difference vector Delta_1 = v- - v_Mars, its components substituted;
//   - collected by the powers of the named norms, each coefficient factored where that is shorter.
// Each step is kept only if it shortens the LaTeX. Every named quantity is listed (definitions()),
// so the printed formula and its definitions say exactly what the stored expression says. The
// printer is not GiNaC's: that one follows GiNaC's term order, which follows hash values and so
// memory addresses; this one sorts terms and factors, so the same expression gives the same bytes.
#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace helios::symbolic {

// The LaTeX of a symbol name of a derivation: l_<x> is the costate lambda_<x>; a state component
// rx is r_x; Greek names are Greek (eps is varepsilon, lambda0 is lambda_0); an event's or a body's
// name is an upright superscript (vx_mars_m: v_x^{mars-}, the state just before the event mars;
// _p after it); a trailing _t0 / _tf is the time (t_0) / (t_f); a number part is a subscript; any
// other multi-letter word is upright. Not injective on every name: Typesetter checks its names.
std::string latex_symbol(const std::string& name);

// The LaTeX of an intermediate quantity's name: its first part the symbol, the others its subscript
// (P_in is P_{\mathrm{in}}, T_P is T_{P}), not the superscript of a body or an event: a
// superscript on a quantity reads as a power.
std::string latex_intermediate(const std::string& name);

// LaTeX text for prose (escapes the characters TeX treats specially).
std::string latex_text(const std::string& text);

// A quantity the compact form introduced: its LaTeX symbol and its definition (LaTeX, the right
// side of "symbol = definition").
struct NamedQuantity {
  std::string symbol, definition;
};

class Typesetter {
 public:
  // `names`: every symbol name the expressions may use. A name whose latex_symbol() another name
  // already prints as is printed as upright text instead, so no two symbols look alike.
  // `intermediates`: the names among them that are the derivation's intermediates, printed with
  // their qualifier as a subscript (latex_intermediate), and so their partials.
  explicit Typesetter(const std::vector<std::string>& names, const std::set<std::string>& intermediates = {});

  // The compact form of `e` (see the header comment), over symbols that print as LaTeX.
  GiNaC::ex compact(const GiNaC::ex& e);
  // LaTeX of e's compact form.
  std::string latex(const GiNaC::ex& e) { return print(compact(e)); }
  // The same split into lines of about `width` characters of LaTeX between the terms of a sum (for
  // an aligned block); one line when it is no sum or short enough.
  std::vector<std::string> latex_lines(const GiNaC::ex& e, std::size_t width);
  // LaTeX of an expression already in printable symbols (what compact() returns).
  static std::string print(const GiNaC::ex& e);
  // The LaTeX of a symbol name as this typesetter prints it.
  std::string symbol(const std::string& name) const;

  // Registers the norms and differences `e` holds as powers, without typesetting it: learning
  // every expression of a document first names each quantity the same way wherever it appears.
  void learn(const GiNaC::ex& e);

  // The quantities the compact forms so far use: the differences, then the norms (built on them).
  std::vector<NamedQuantity> definitions() const;

  // The stored expression back from a compact one: every named quantity replaced by its
  // definition and every symbol by the derivation's own (to check that compact() is exact).
  GiNaC::ex expanded_back(const GiNaC::ex& compact_form, const GiNaC::symtab& table) const;

 private:
  struct Norm {
    GiNaC::symbol symbol;
    std::vector<GiNaC::ex> components;  // printable symbols (possibly named differences)
    GiNaC::ex squared;                  // sum of the components' squares, expanded
  };
  struct Difference {
    GiNaC::symbol symbol;
    GiNaC::ex minuend, subtrahend;  // printable symbols: symbol = minuend - subtrahend
  };

  GiNaC::ex printable(const GiNaC::ex& e) const;
  void learn_printable(const GiNaC::ex& e);
  GiNaC::ex name_power_bases(const GiNaC::ex& e);
  const Norm* norm_of(const GiNaC::ex& base);
  GiNaC::ex substitute_differences(const GiNaC::ex& e) const;
  GiNaC::ex substitute_expanded_norms(const GiNaC::ex& e) const;
  GiNaC::ex collected(const GiNaC::ex& e) const;
  std::string norm_name(const std::vector<GiNaC::ex>& components) const;

  std::map<std::string, GiNaC::symbol> printable_;  // derivation name -> symbol with LaTeX name
  std::map<std::string, std::string> latex_of_;     // derivation name -> its LaTeX
  std::vector<Norm> norms_;
  std::vector<Difference> differences_;
  std::set<std::string> used_;  // names of the norms and differences a compact form used
};

}  // namespace helios::symbolic

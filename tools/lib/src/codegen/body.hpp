#pragma once
// A generated function's body whose unpacked locals are written only when its code uses them
// (internal to tools/lib/src/codegen).
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "context.hpp"

namespace helios::codegen::detail {

// The lines of a generated function in order, among them the unpacks of locals (a state from
// y[], a shooting variable from x[], a target's component, ...). An unpack is written only if
// the body uses one of the names it defines. The uses are the symbols of the expressions the
// body prints (cpp) and the names the generator writes into code itself (use).
class Body {
 public:
  // `scalar`: the type of the unpacked locals (double, or T in a function template, whose
  // expressions then call the math functions unqualified).
  explicit Body(Context& c, std::string scalar = "double") : c_(c), scalar_(std::move(scalar)) {}
  // The stream of plain code lines, written in order with the unpacks.
  std::ostringstream& code() { return code_; }
  // C++ for an expression (a stored one parsed, or one the generator built, such as a
  // derivative); its symbols count as used.
  std::string cpp(const GiNaC::ex& e);
  // `name`, counted as used: a name the generator writes into code itself.
  std::string use(const std::string& name);
  bool uses(const std::string& name) const { return used_.count(name) > 0; }
  // The line "  const <scalar> <name> = <value>;" (with "  // <comment>" when given), written if used.
  void unpack(const std::string& name, const std::string& value, const std::string& comment = "");
  // The local `name` = `value`, written if used, and then what `value` uses counts as used (it may
  // use the locals made before it, not later ones).
  void local(const std::string& name, const GiNaC::ex& value);
  // The states then the costates from y[], as the runtime's modules have them, then the
  // derivation's intermediates computed from them.
  void unpack_y();
  // unpack_y, then the controls from control[] (with_control) and the multipliers from mult.
  void unpack_variables(bool with_control);
  // `(void)p;` for each of the runtime function's `parameters` p (t, y, control, mult) the body
  // uses neither itself nor through its locals.
  std::string unused_parameters(const std::vector<std::string>& parameters) const;
  // A line (ending in "\n") that defines all of `names`, written if any of them is used.
  void unpack_line(const std::string& line, const std::vector<std::string>& names);
  // The local `name` = `from` - `to` (two unpacked symbols; written after them, if used). From
  // here on, an expression that prints shorter with `from` = `to` + `name` is printed so: a
  // swing-by's rows, expanded in the heliocentric velocities, cancel terms a thousand times their
  // sum; in the velocity relative to the planet they do not.
  void relative(const std::string& name, const std::string& from, const std::string& to);
  // The body's text: the code with the unpacks that are used.
  std::string str();

 private:
  struct Segment {
    std::string text;
    std::vector<std::string> defines;  // empty for plain code
  };
  // Moves the pending code into a segment.
  void flush();
  // e, or e in the relative locals where that prints shorter; marks what it prints as used.
  std::string print(const GiNaC::ex& e);
  symbolic::CppScalar dialect() const {
    return scalar_ == "double" ? symbolic::CppScalar::Double : symbolic::CppScalar::Generic;
  }

  Context& c_;
  std::string scalar_;
  std::ostringstream code_;
  std::vector<Segment> segments_;
  std::set<std::string> used_;
  GiNaC::exmap relative_;                                                         // from -> to + name
  std::vector<std::pair<std::string, std::vector<std::string>>> relative_parts_;  // name -> {from, to}
  std::vector<std::pair<std::string, std::vector<std::string>>> local_parts_;     // local -> the symbols it uses
};

}  // namespace helios::codegen::detail

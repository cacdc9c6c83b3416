// A program's numbers (its HELIOS_PARAMETER lines): the structure the compile cache keys on, when
// nothing else in the program can read them before main, and the parameters file helios-solve
// writes for the program.
#include <cmath>
#include <cstdlib>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "helios/solve/solve.hpp"
#include "program_text.hpp"

namespace helios::solve {
namespace {

using io::json;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The literal at line[at] as codegen's number() prints it (a sign, digits with a point, an
// exponent): its end, else npos.
std::size_t number_end(const std::string& line, std::size_t at) {
  std::size_t i = at + (at < line.size() && line[at] == '-' ? 1 : 0);
  const std::size_t digits = i;
  while (i < line.size() && is_digit(line[i])) ++i;
  if (i < line.size() && line[i] == '.') ++i;
  while (i < line.size() && is_digit(line[i])) ++i;
  if (i == digits || (i == digits + 1 && line[digits] == '.')) return std::string::npos;
  if (i < line.size() && (line[i] == 'e' || line[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < line.size() && (line[j] == '+' || line[j] == '-')) ++j;
    if (j >= line.size() || !is_digit(line[j])) return std::string::npos;
    while (j < line.size() && is_digit(line[j])) ++j;
    i = j;
  }
  return i;
}

// The identifier at line[at]: its end, else npos.
std::size_t name_end(const std::string& line, std::size_t at) {
  std::size_t i = at;
  const auto word = [](char c) { return c == '_' || is_digit(c) || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  if (i >= line.size() || is_digit(line[i]) || !word(line[i])) return std::string::npos;
  while (i < line.size() && word(line[i])) ++i;
  return i;
}

// One parameter line: its name, its numbers (the doubles their literals denote: strtod rounds to
// nearest, as the compiler does) and the line with each literal replaced by '#'; false when the
// line is not of the form.
bool parameter_line(const std::string& line, std::string& name, json& values, std::string& masked) {
  static const std::string scalar = "HELIOS_PARAMETER(", array = "HELIOS_PARAMETER_ARRAY(";
  const bool is_array = line.rfind(array, 0) == 0;
  if (!is_array && line.rfind(scalar, 0) != 0) return false;
  std::size_t i = (is_array ? array : scalar).size();
  const std::size_t end = name_end(line, i);
  if (end == std::string::npos) return false;
  name = line.substr(i, end - i);
  masked = line.substr(0, end);
  values = json::array();
  for (i = end; line.compare(i, 2, ", ") == 0;) {
    const std::size_t stop = number_end(line, i + 2);
    if (stop == std::string::npos) return false;
    const double v = std::strtod(line.substr(i + 2, stop - i - 2).c_str(), nullptr);
    if (!std::isfinite(v)) return false;  // 1e999: the compiler's inf, which JSON cannot carry
    values.push_back(v);
    masked += ", #";
    i = stop;
  }
  if (values.empty() || (!is_array && values.size() != 1) || line.compare(i, 2, ");") != 0) return false;
  const std::string rest = line.substr(i + 2);
  if (!rest.empty() && rest.rfind("  //", 0) != 0) return false;
  masked += line.substr(i);
  if (!is_array) values = values[0];
  return true;
}

}  // namespace

ProgramParameters program_parameters(const std::string& source) {
  const auto whole_source = [&](const std::string& why) {
    ProgramParameters p;
    p.structure = source;
    p.whole_source_because = why;
    return p;
  };
  const detail::ProgramText text = detail::read_program_text(source);
  if (!text.unreadable.empty()) return whole_source(text.unreadable);
  // The runtime's header, a system header, a pragma: no macro can change the rest of the text.
  static const std::regex allowed(R"(#include "helios_runtime\.hpp"|#\s*include\s*<[A-Za-z0-9_./+-]+>|#\s*pragma\s.*)");
  for (const auto& d : text.directives)
    if (!std::regex_match(d, allowed))
      return whole_source("the preprocessor line '" + d.substr(0, 60) + "' may change what the compiler reads");
  ProgramParameters p;
  p.readable = true;
  std::set<std::size_t> parameter_lines;
  std::size_t from = 0;
  for (std::size_t line = 1; from <= source.size(); ++line) {
    const std::size_t nl = source.find('\n', from);
    const std::size_t to = nl == std::string::npos ? source.size() : nl;
    const std::string text_line = source.substr(from, to - from);
    std::string name, masked;
    json values;
    if (text_line.rfind("HELIOS_PARAMETER", 0) == 0 && text.line_starts_in_code[line - 1]) {
      if (!parameter_line(text_line, name, values, masked))
        return whole_source("line " + std::to_string(line) +
                            ": a parameter line not of the form HELIOS_PARAMETER(name, number);");
      if (p.values.contains(name))
        return whole_source("line " + std::to_string(line) + ": the parameter " + name + " again");
      p.values[name] = values;
      p.structure += masked;
      parameter_lines.insert(line);
    } else {
      p.structure += text_line;
    }
    if (nl == std::string::npos) break;
    p.structure += '\n';
    from = to + 1;
  }
  std::vector<detail::Token> code;
  for (const auto& t : text.tokens) {
    if (parameter_lines.count(t.line)) continue;
    if (t.text == "HELIOS_PARAMETER" || t.text == "HELIOS_PARAMETER_ARRAY")
      return whole_source("line " + std::to_string(t.line) + ": " + t.text + " outside a parameter line");
    code.push_back(t);
  }
  if (const std::string why = detail::code_before_main(code); !why.empty())
    return whole_source(why + " (it could read a parameter before the parameters file replaces it)");
  return p;
}

json parameters_document(const json& values) {
  return {{"schema", "helios/parameters"}, {"values", values}};
}

}  // namespace helios::solve

// A program's numbers (its HELIOS_PARAMETER lines): the structure the compile cache keys on, and
// the parameters file helios-solve writes for the program.
#include <cmath>
#include <cstdlib>
#include <string>

#include "helios/solve/solve.hpp"

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
  ProgramParameters unreadable;
  unreadable.structure = source;
  ProgramParameters p;
  p.readable = true;
  bool directive = false;  // a preprocessor line other than the runtime's #include so far
  std::size_t from = 0;
  while (from < source.size()) {
    const std::size_t nl = source.find('\n', from);
    const std::size_t to = nl == std::string::npos ? source.size() : nl;
    const std::string line = source.substr(from, to - from);
    const std::size_t first = line.find_first_not_of(" \t");
    const std::string text = first == std::string::npos ? "" : line.substr(first);
    if (text.rfind("#", 0) == 0 && text != "#include \"helios_runtime.hpp\"") directive = true;
    std::string name, masked;
    json values;
    if (text.rfind("//", 0) == 0 || line.find("HELIOS_PARAMETER") == std::string::npos) {
      p.structure += line;
    } else if (!directive && parameter_line(line, name, values, masked) && !p.values.contains(name)) {
      p.values[name] = values;
      p.structure += masked;
    } else {
      return unreadable;
    }
    if (nl != std::string::npos) p.structure += '\n';
    from = to + 1;
  }
  return p;
}

json parameters_document(const json& values) {
  return {{"schema", "helios/parameters"}, {"values", values}};
}

}  // namespace helios::solve

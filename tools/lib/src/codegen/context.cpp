// The generator's shared text helpers.
#include "context.hpp"

#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace helios::codegen::detail {

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(17) << v;
  std::string s = out.str();
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string cpp_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\' || c == '?') {  // '?': no trigraph
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7F) {
      char octal[5];
      std::snprintf(octal, sizeof octal, "\\%03o", c);
      out += octal;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::string comment_text(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F || c == '\\') c = c == '\\' ? '/' : ' ';
  return s;
}

std::string quoted_list(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + cpp_string(s);
  return out;
}

int index_of(const std::vector<std::string>& v, const std::string& name) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] == name) return static_cast<int>(i);
  return -1;
}

}  // namespace helios::codegen::detail

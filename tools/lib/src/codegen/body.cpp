// A generated function's body: code and the unpacks it reads.
#include "body.hpp"

#include <string>
#include <vector>

namespace helios::codegen::detail {

std::string Body::cpp(const std::string& text, const std::string& where) {
  for (const auto& name : symbolic::free_symbols(c_.symbols.parse(text, "field " + where))) used_.insert(name);
  return c_.cpp(text, where);
}

std::string Body::cpp(const GiNaC::ex& e) {
  for (const auto& name : symbolic::free_symbols(e)) used_.insert(name);
  return c_.cpp(e);
}

std::string Body::use(const std::string& name) {
  used_.insert(name);
  return name;
}

void Body::unpack(const std::string& name, const std::string& value, const std::string& comment) {
  unpack_line(
      "  const double " + name + " = " + value + ";" + (comment.empty() ? "" : "  // " + comment_text(comment)) + "\n",
      {name});
}

void Body::unpack_line(const std::string& line, const std::vector<std::string>& names) {
  flush();
  segments_.push_back({line, names});
}

void Body::flush() {
  if (code_.tellp() <= 0) return;
  segments_.push_back({code_.str(), {}});
  code_.str("");
}

std::string Body::str() {
  flush();
  std::string out;
  for (const auto& s : segments_) {
    bool written = s.defines.empty();
    for (const auto& name : s.defines) written = written || uses(name);
    if (written) out += s.text;
  }
  return out;
}

}  // namespace helios::codegen::detail

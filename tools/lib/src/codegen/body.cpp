// A generated function's body: code and the unpacks it reads.
#include "body.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace helios::codegen::detail {

std::string Body::cpp(const GiNaC::ex& e) {
  return print(e);
}

std::string Body::print(const GiNaC::ex& e) {
  GiNaC::ex chosen = e;
  std::string text = c_.cpp(e, dialect());
  if (const GiNaC::ex r = e.subs(relative_); !r.is_equal(e)) {  // e has a symbol to write relative
    const GiNaC::ex expanded = r.expand();
    if (std::string t = c_.cpp(expanded, dialect()); t.size() < text.size()) {
      chosen = expanded;
      text = std::move(t);
    }
  }
  for (const auto& name : symbolic::free_symbols(chosen)) used_.insert(name);
  for (auto it = local_parts_.rbegin(); it != local_parts_.rend(); ++it)  // each uses earlier ones only
    if (uses(it->first)) used_.insert(it->second.begin(), it->second.end());
  for (const auto& [name, parts] : relative_parts_)
    if (uses(name)) used_.insert(parts.begin(), parts.end());
  return text;
}

void Body::relative(const std::string& name, const std::string& from, const std::string& to) {
  relative_[c_.symbols.get(from)] = c_.symbols.get(to) + GiNaC::symbol(name);
  relative_parts_.push_back({name, {from, to}});
  unpack(name, from + " - " + to);
}

std::string Body::use(const std::string& name) {
  used_.insert(name);
  return name;
}

void Body::unpack(const std::string& name, const std::string& value, const std::string& comment) {
  unpack_line("  const " + scalar_ + " " + name + " = " + value + ";" +
                  (comment.empty() ? "" : "  // " + comment_text(comment)) + "\n",
              {name});
}

void Body::unpack_y() {
  for (std::size_t i = 0; i < c_.states.size(); ++i) unpack(c_.states[i], "y[" + std::to_string(i) + "]");
  for (std::size_t i = 0; i < c_.costates.size(); ++i)
    unpack(c_.costates[i], "y[" + std::to_string(c_.states.size() + i) + "]");
  for (const auto& [q, expression] : c_.chain.order()) local(q.get_name(), expression);
}

void Body::local(const std::string& name, const GiNaC::ex& value) {
  unpack(name, c_.cpp(value, dialect()));
  local_parts_.emplace_back(name, symbolic::free_symbols(value));
}

void Body::unpack_variables(bool with_control) {
  unpack_y();
  if (with_control)
    for (std::size_t i = 0; i < c_.controls.size(); ++i) unpack(c_.controls[i], "control[" + std::to_string(i) + "]");
  unpack(c_.multiplier, "mult.lambda0");
  unpack(c_.homotopy, "mult.eps");
}

std::string Body::unused_parameters(const std::vector<std::string>& parameters) const {
  std::vector<std::string> y = c_.states;
  y.insert(y.end(), c_.costates.begin(), c_.costates.end());
  const std::map<std::string, std::vector<std::string>> used_through = {
      {"t", {"t"}}, {"y", y}, {"control", c_.controls}, {"mult", {c_.multiplier, c_.homotopy}}};
  std::string out;
  for (const auto& p : parameters) {
    const auto& names = used_through.at(p);
    if (std::none_of(names.begin(), names.end(), [&](const std::string& n) { return uses(n); }))
      out += "  (void)" + p + ";\n";
  }
  return out;
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

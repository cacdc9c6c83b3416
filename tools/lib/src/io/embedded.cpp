#include "helios/io/embedded.hpp"

#include <stdexcept>

namespace helios::embedded {

const std::string& file(const std::string& relative_path) {
  const auto& table = files();
  const auto it = table.find(relative_path);
  if (it == table.end()) throw std::logic_error("no embedded file " + relative_path);
  return it->second;
}

}  // namespace helios::embedded

// two_body: the gradient of the potential mu/|r|.
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

std::vector<Recomputation> two_body() {
  return {{"two_body",
           [](const Frame& x, const derivation::Term&, const std::vector<ex>& q, Check&) -> std::optional<Rates> {
             return Rates{x.gradient(q[0] / x.radius())};
           }}};
}

}  // namespace helios::verify::detail::recompute

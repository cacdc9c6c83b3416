// user_acceleration: its components as the derivation lists them (the verifier has no other way to
// know them).
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

std::vector<Recomputation> user_acceleration() {
  return {{"user_acceleration",
           [](const Frame& x, const derivation::Term& t, const std::vector<ex>&, Check& c) -> std::optional<Rates> {
             Rates out;
             try {
               for (std::size_t k = 0; k < 3; ++k)
                 out.acceleration.push_back(x.ctx.statement(
                     t.acceleration[k], "terms (" + t.label + ").acceleration[" + std::to_string(k) + "]"));
             } catch (const std::exception& e) {
               c.fail("term user_acceleration (" + t.label + "): " + e.what() + ".");
               return std::nullopt;
             }
             return out;
           }}};
}

}  // namespace helios::verify::detail::recompute

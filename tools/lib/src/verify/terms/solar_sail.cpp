// solar_sail: an ideal flat sail, ac (rref/r)^2 (n.rhat)^2 n with the unit normal n.
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

std::vector<Recomputation> solar_sail() {
  return {{"solar_sail",
           [](const Frame& x, const derivation::Term&, const std::vector<ex>& q, Check& c) -> std::optional<Rates> {
             const Context& ctx = x.ctx;
             if (ctx.sails.size() != 3) {
               c.fail("term solar_sail needs three sail_normal controls.");
               return std::nullopt;
             }
             ex nr = 0;
             for (int k = 0; k < 3; ++k) nr += ctx.sym(ctx.sails[k]) * x.r[k];
             Rates out;
             for (const auto& n : ctx.sails)
               out.acceleration.push_back(q[0] * GiNaC::pow(q[1], 2) * nr * nr * ctx.sym(n) /
                                          GiNaC::pow(x.radius(), 4));
             return out;
           }}};
}

}  // namespace helios::verify::detail::recompute

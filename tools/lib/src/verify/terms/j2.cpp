// j2: the gradient of the zonal potential -J2 mu R^2/(2 r^3) (3 z^2/r^2 - 1), z along the pole.
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

std::vector<Recomputation> j2() {
  return {
      {"j2", [](const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c) -> std::optional<Rates> {
         const auto mu = x.central_mu(t.name, c);
         if (!mu) return std::nullopt;
         const ex r = x.radius(), z = x.r[2];
         return Rates{x.gradient(-q[0] * (*mu) * q[1] * q[1] / (2 * GiNaC::pow(r, 3)) * (3 * z * z / (r * r) - 1))};
       }}};
}

}  // namespace helios::verify::detail::recompute

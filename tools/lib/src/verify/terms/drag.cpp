// drag: -1/2 rho Cd A |v_rel| v_rel / m, written here from the physics: the density falls by e over
// each scale height H above the reference radius r0 (rho0 Cd A = Bd there), the air turns with the
// body at w about z, so the spacecraft moves through it at v - w z x r.
#include "recompute.hpp"

namespace helios::verify::detail::recompute {

std::vector<Recomputation> drag() {
  return {
      {"drag", [](const Frame& x, const derivation::Term&, const std::vector<ex>& q, Check&) -> std::optional<Rates> {
         const ex &Bd = q[0], &r0 = q[1], &H = q[2], &w = q[3];
         const std::vector<ex> omega = {0, 0, w};
         std::vector<ex> air(3), rel(3);
         for (int i = 0; i < 3; ++i) {  // (omega x r)_i
           const int j = (i + 1) % 3, k = (i + 2) % 3;
           air[i] = omega[j] * x.r[k] - omega[k] * x.r[j];
           rel[i] = x.v[i] - air[i];
         }
         const ex density_area = Bd * GiNaC::exp((r0 - x.radius()) / H);
         const ex speed = GiNaC::sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
         Rates out;
         for (int i = 0; i < 3; ++i) out.acceleration.push_back(-density_area * speed * rel[i] / (2 * x.m));
         return out;
       }}};
}

}  // namespace helios::verify::detail::recompute

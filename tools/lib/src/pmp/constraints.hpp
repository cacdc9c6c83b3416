#pragma once
// The constraints of a problem, built from the spec's entries (constraints.cpp). Both add the
// targets' states to the problem's parameters and symbols, so build_problem calls them in the
// spec's order.
#include "helios/io/json_io.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp {

// The rows psi(x) = 0 of an orbit given by some of its classical elements (the spec's target of
// kind "orbital_elements"), with their meanings; adds the elements as parameters <element>_<id>.
// With them, the conditions g > 0 that tell the orbit from its mirror (the rows hold on both): h.n
// > 0 where the plane is given (the normal n, not -n), e_vec.P > 0 where the periapsis is.
struct OrbitRows {
  std::vector<GiNaC::ex> psi;
  std::vector<std::string> names;
  std::vector<SideCondition> must_be_positive;
};
OrbitRows orbit_rows(Problem& p, const std::string& id, const io::json& target);

// The position and velocity on an orbit given by its elements, as functions of its true anomaly
// `theta` (measured from the node where the orbit is circular, from the x axis where it is also
// equatorial): r = p/(1 + e cos theta) (cos theta P + sin theta Q), v = sqrt(mu/p) (-sin theta P +
// (e + cos theta) Q). Adds p = a (1 - e^2), e and the components of P and Q as parameters (p_<id>,
// e_<id>, Px_<id>...). The node and the argument of periapsis the target lists as "free" are the
// angles `node` and `argp` (P and Q turned by them: about z, and in the orbit's plane); throws,
// naming the element, when one that fixes the orbit is neither given nor free, or a free one is
// undefined (the node of an equatorial orbit, the periapsis of a circular one).
struct FreeOrbitAngles {
  GiNaC::ex theta, node, argp;  // node and argp used only where the target lists them as free
};
std::vector<GiNaC::ex> orbit_point(Problem& p, const std::string& id, const io::json& target,
                                   const FreeOrbitAngles& angles);

// psi(t_k, x(t_k), p) of an endpoint constraint (at t0 or tf).
EndpointConstraint endpoint_constraint(Problem& p, const io::json& constraint);

// An interior event: conditions c on the arriving state and the map g to the leaving state.
InteriorEvent interior_event(Problem& p, const io::json& constraint);

// Refuses a departure orbit's free node where nothing else in the spec changes when turned about
// the z axis (two-body gravity and J2, no events, an arrival on an orbit without a node or on
// conditions of r, v, h, hz, z, vz and m): every node would then give the same transfer, turned,
// and the shooting system would be singular.
void refuse_free_node_by_symmetry(const io::json& spec);

}  // namespace helios::pmp

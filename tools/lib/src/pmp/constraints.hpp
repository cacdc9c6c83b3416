#pragma once
// The constraints of a problem, built from the spec's entries (constraints.cpp). Both add the
// targets' states to the problem's parameters and symbols, so build_problem calls them in the
// spec's order.
#include "helios/io/json_io.hpp"
#include "helios/pmp/model.hpp"

namespace helios::pmp {

// The rows psi(x) = 0 of an orbit given by some of its classical elements (the spec's target of
// kind "orbital_elements"), with their meanings; adds the elements as parameters <element>_<id>.
struct OrbitRows {
  std::vector<GiNaC::ex> psi;
  std::vector<std::string> names;
};
OrbitRows orbit_rows(Problem& p, const std::string& id, const io::json& target);

// The position and velocity on an orbit given by all its elements, as functions of its true
// anomaly `theta` (measured from the node where the orbit is circular, from the x axis where it is
// also equatorial): r = p/(1 + e cos theta) (cos theta P + sin theta Q), v = sqrt(mu/p) (-sin theta
// P + (e + cos theta) Q). Adds p = a (1 - e^2), e and the components of P and Q as parameters
// (p_<id>, e_<id>, Px_<id>...); throws, naming the element, when one that fixes the orbit is
// missing.
std::vector<GiNaC::ex> orbit_point(Problem& p, const std::string& id, const io::json& target, const GiNaC::ex& theta);

// psi(t_k, x(t_k), p) of an endpoint constraint (at t0 or tf).
EndpointConstraint endpoint_constraint(Problem& p, const io::json& constraint);

// An interior event: conditions c on the arriving state and the map g to the leaving state.
InteriorEvent interior_event(Problem& p, const io::json& constraint);

}  // namespace helios::pmp

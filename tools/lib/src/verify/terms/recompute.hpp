#pragma once
// The verifier's own recomputation of each force of the catalogue (helios/pmp/catalogue.hpp),
// internal to tools/lib/src/verify: one file here per term file of pmp/terms, written from the
// physics, never from pmp. Each file's function of its name returns its recomputations; the build
// lists those files (CMakeLists.txt). verify/terms.cpp sums them into the dynamics it compares.
#include <optional>
#include <string>
#include <vector>

#include "../check.hpp"
#include "../context.hpp"
#include "helios/derivation/terms.hpp"

namespace helios::verify::detail::recompute {

// What a recomputation sees of the derivation: its context, the spacecraft's states by their kinds
// and every listed term.
struct Frame {
  const Context& ctx;
  std::vector<ex> r, v;  // the position and velocity states
  ex m = 1;              // the mass state (1 without one)
  int mass = -1;         // its index among the states (-1 without one)
  const std::vector<derivation::Term>& all;

  ex radius() const { return GiNaC::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]); }
  // The gradient of a potential with respect to the position.
  std::vector<ex> gradient(const ex& potential) const {
    return {potential.diff(GiNaC::ex_to<symbol>(r[0])), potential.diff(GiNaC::ex_to<symbol>(r[1])),
            potential.diff(GiNaC::ex_to<symbol>(r[2]))};
  }
  // The value of a parameter of the derivation (a constant).
  double value(const ex& parameter) const {
    return ctx.values[static_cast<std::size_t>(ctx.slot(GiNaC::ex_to<symbol>(parameter).get_name()))];
  }
  // The central body's mu: the parameter of the listed two_body term (fails c naming `who` without one).
  std::optional<ex> central_mu(const std::string& who, Check& c) const {
    for (const auto& t : all)
      if (t.name == "two_body" && t.parameters.size() == 1 && ctx.slots.count(t.parameters[0]))
        return ctx.sym(t.parameters[0]);
    c.fail("term " + who + " needs the central body's mu, the parameter of a two_body term.");
    return std::nullopt;
  }
};

// A force's acceleration (three components) and its contribution to the mass rate.
struct Rates {
  std::vector<ex> acceleration;
  ex mass_rate = 0;
};

struct Recomputation {
  std::string name;  // the catalogue's
  // The term's rates from its listed parameters q (their symbols, as many as the catalogue allows),
  // or nothing with the reason in c where the controls or the states do not fit it.
  std::optional<Rates> (*rates)(const Frame& x, const derivation::Term& t, const std::vector<ex>& q, Check& c);
  // An engine whose mass flow at full throttle is no parameter's ratio: that flow from its
  // parameters (T(r)/c), which its fuel cost lists too.
  ex (*full_flow)(const Frame& x, const std::vector<ex>& q) = nullptr;
};

// A solar-electric engine's input power (solar_electric.cpp): the arrays' P0/d^2 at the Sun's
// distance d in AU less the bus Pbus, floored at zero softly over Pbus/100 where a bus is, and
// capped softly at Pmax over Pw (no cap where Pmax is 0).
ex input_power(const Frame& x, const ex& P0, const ex& Pbus, const ex& Pmax, const ex& Pw);

// Every file's recomputations, in no order (the build's list), and the one of `name` or nullptr.
std::vector<Recomputation> all_files();
const Recomputation* find(const std::string& name);

}  // namespace helios::verify::detail::recompute

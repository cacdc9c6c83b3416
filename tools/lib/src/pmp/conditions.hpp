#pragma once
// The families of necessary conditions derive_conditions assembles, one unit each: the control
// law (control_law.cpp), the endpoint conditions (boundary_conditions.cpp) and the conditions
// of interior events (event_conditions.cpp). The symbol table of the problem grows as they
// introduce multipliers and values at events, so they run in a fixed order (the symbols'
// creation order fixes GiNaC's term order, hence the derivation's text).
#include <ginac/ginac.h>

#include <string>

#include "helios/pmp/derivation.hpp"

namespace helios::pmp {

// Minimizes H over the controls: the thrust direction, then a sail's normal, then the throttle.
ControlLaw control_law(Problem& p, const GiNaC::ex& H);

// Conditions of the endpoint constraints and of a free departure or final time; adds their
// shooting variables and equations and the initial values psi(x(t0)) = 0 determines.
void endpoint_conditions(Derivation& d);

// The costates at t0 (and a free initial mass) as shooting variables on the sphere
// |(lambda0, lambda(t0))| = 1, whose normalization equation closes the system.
void initial_costates(Derivation& d);

// Conditions of the interior event `e`; adds its shooting variables and equations to `shooting`.
EventConditions event_conditions(Problem& p, const InteriorEvent& e, Shooting& shooting);

// The expanded form of e where that is not longer (a swing-by's rotation expands enormously).
GiNaC::ex tidy(const GiNaC::ex& e);

// d e/dt through the time-dependent parameters (a target's state at its event).
GiNaC::ex time_derivative(Problem& p, const GiNaC::ex& e);

// The shooting variable of a multiplier; a bound's multiplier is 0 while the bound is inactive.
ShootingVariable multiplier_variable(const std::string& name, const std::string& meaning, bool inequality);

// The equation psi_j = 0 of a constraint row; a bound psi_j <= 0 is handled in two passes: while
// inactive its multiplier is 0 (the equation is then `multiplier` = 0), when active psi_j = 0.
ShootingEquation constraint_equation(const std::string& name, const GiNaC::ex& expression, const std::string& meaning,
                                     const std::string& source, const GiNaC::symbol& multiplier, bool inequality);

}  // namespace helios::pmp

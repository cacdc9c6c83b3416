// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime (templates/runtime/runtime.hpp): the fixed part of every generated
// shooting program, one header per concept, in the order below (helios-gen pastes them in this
// order; this list is the only one). It needs the PROBLEM block (namespace problem) before it and
// the modules DYNAMICS, SWITCH, RESIDUAL and SOLVE after it (their prototypes are in the headers).
//
// Numerics (design.md section 6): normalized units; an adaptive DOP853 integrator whose control
// mode (throttle off / interior / full) is frozen inside each step, with the switching times
// located to round-off so the shooting function stays smooth at eps = 0; eps-homotopy from
// eps = 1 with adaptive steps and retreat; seeded random restarts; cminpack hybrd1.
// ---------------------------------------------------------------------------------------------
#pragma once

#include "controls.hpp"
#include "targets.hpp"
#include "settings.hpp"
#include "propagator.hpp"
#include "residual.hpp"
#include "outcome.hpp"
#include "shooter.hpp"
#include "homotopy.hpp"
#include "legs.hpp"
#include "continuation.hpp"
#include "bounds.hpp"
#include "search.hpp"

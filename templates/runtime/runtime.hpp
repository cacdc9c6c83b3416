// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime (templates/runtime/runtime.hpp): the fixed part of every shooting
// program, one header per concept, in the order below (this list is the only one). runtime.cpp
// compiles them once into the static library libhelios-runtime.a; a generated program sees only
// helios_runtime.hpp (the problem's shape and the modules' prototypes) and links the library.
// Only what that header declares has external linkage; the rest of each header is in an unnamed
// namespace, so a module's function can never silently replace one of the runtime's own.
//
// Numerics (templates/runtime/DESIGN.md says why): normalized units; an adaptive DOP853 integrator
// whose control mode (throttle off / interior / full) is frozen inside each step, with the switching
// times located to round-off so the shooting function stays smooth at eps = 0 (propagator.hpp);
// cminpack hybrj on the exact shooting Jacobian, carried by dual numbers through the same steps, or
// hybrd's differences without it (shooter.hpp); eps-homotopy from eps = 1 with adaptive steps,
// tangent predictors and retreat (homotopy.hpp); interior events reached by continuation from the
// problem without them, else leg by leg (continuation.hpp, legs.hpp); bounds psi <= 0 by passes
// over the active set (bounds.hpp); a global search of routes over one pool of extremals, decided
// by one chooser (search/: pipeline.hpp, pool.hpp, chooser.hpp, a file per route: starts, the
// revolution families, a minimum-time problem's minimum-fuel companion, the continuation of a
// many-revolution transfer on the thrust, the route from the minimum time, the complete attempts
// of a problem with events); and the last polish of a converged solution by
// multiple shooting (nodes.hpp).
// ---------------------------------------------------------------------------------------------
#pragma once

// The headers in the runtime's order, each after what it uses.
// clang-format off
#include "helios_runtime.hpp"
#include "parameters.hpp"
#include "dop853.hpp"
#include "dual.hpp"
#include "counters.hpp"
#include "controls.hpp"
#include "targets.hpp"
#include "propagator.hpp"
#include "residual.hpp"
#include "shooter.hpp"
#include "homotopy.hpp"
#include "legs.hpp"
#include "continuation.hpp"
#include "nodes.hpp"
#include "search/draws.hpp"
#include "search/knobs.hpp"
#include "search/pool.hpp"
#include "search/chooser.hpp"
#include "bounds.hpp"
#include "search/route.hpp"
#include "search/search.hpp"
#include "search/starts.hpp"
#include "search/families.hpp"
#include "search/companion.hpp"
#include "search/thrust.hpp"
#include "search/scale.hpp"
#include "search/time_route.hpp"
#include "search/edge.hpp"
#include "search/bound.hpp"
#include "search/attempts.hpp"
#include "search/warm.hpp"
#include "search/pipeline.hpp"
#include "report.hpp"
// clang-format on

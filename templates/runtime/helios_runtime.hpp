// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, public header (templates/runtime/helios_runtime.hpp): what a generated
// shooting program sees of the runtime, declarations only, and the one header it includes. The
// runtime itself (the other headers of templates/runtime, compiled by runtime.cpp) is the static
// library libhelios-runtime.a, built once with the tools; helios-solve compiles a program against
// this header and links it with the library.
//
// It is three headers, each including the one before:
//   - runtime_records.hpp: the records the runtime and a program share (the problem's shape, the
//     settings, the plans of legs and events, the bounds, what a solve records, its Status);
//   - runtime_calls.hpp: what a module may call (its parameters, dual numbers, the targets, the
//     propagator, the bounds' rows, the solves a SOLVE module wraps, run);
//   - module_interface.hpp: what a program must define: kProblem; its numbers, each a
//     HELIOS_PARAMETER; the modules DYNAMICS (dynamics, hamiltonian), SWITCH (direction_control,
//     throttle_slopes with a throttle), RESIDUAL (shooting_function; shooting_legs with events;
//     coast_dynamics with a coasting target), SOLVE (solve_problem) and the optional ones declared
//     in its module table (kModules, HELIOS_MODULE_TABLE); and main, which calls run.
// ---------------------------------------------------------------------------------------------
#pragma once

#include "module_interface.hpp"

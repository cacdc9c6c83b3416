// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, the module interface (templates/runtime/module_interface.hpp): what a
// program must define (kProblem, its modules' functions) and the table that declares its optional
// modules (kModules).
// helios_runtime.hpp includes it; a program includes only that header.
// ---------------------------------------------------------------------------------------------
#pragma once

#include "runtime_calls.hpp"

namespace helios_rt {

// The PROBLEM block: the problem's shape (runtime_records.hpp's ProblemShape) and its numbers,
// each a HELIOS_PARAMETER (runtime_calls.hpp).
extern const ProblemShape kProblem;

// DYNAMICS module: state and costate right-hand sides and H at time t for a given control vector.
void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy);
double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult);
// SWITCH module: the continuous controls (all but the throttle) and dH/du at u = 0 and u = 1.
// A problem without a throttle (throttle_index < 0) has one mode and no throttle_slopes.
void direction_control(const double* y, double* control);
void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper);
// JACOBIAN module (generated from the derivation by GiNaC): the exact first derivatives in
// z = (y, lambda0) (nz = ny + 1 = 2 num_states + 1) of the right-hand side at fixed control,
// dfdz[i * nz + j] = d dy_i / d z_j and dfdu[i * nc + k] = d dy_i / d control_k (nc =
// num_controls), and of the direction law, dcontrol_dy[k * ny + j] (the throttle's row zero):
// the variational equations' pieces.
void dynamics_jacobian(double t, const double* y, const double* control, const Multipliers& mult, double* dfdz,
                       double* dfdu);
void direction_jacobian(const double* y, double* dcontrol_dy);
// With a throttle: d/dz_j of throttle_slopes' at_lower and at_upper (nz entries each).
void throttle_slopes_jacobian(const double* y, const Multipliers& mult, double* d_lower, double* d_upper);
// Unpowered dynamics of a coasting target (RESIDUAL module, when the problem has one).
void coast_dynamics(const double* y, double* dy);

// The shooting function of the RESIDUAL module, with the bookkeeping hybrd1 needs.
void shooting_function(const double* x, double eps, Propagator& prop, double* F);
// Its exact Jacobian (RESIDUAL module, when the program has the JACOBIAN module): F and
// J[i + j * n] = dF_i / dx_j (column-major, as cminpack's hybrj takes it).
void shooting_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J);
// The shooting function on dual numbers of any width (RESIDUAL module, with the JACOBIAN module,
// of a problem without interior events; one with them has shooting_legs_dual): the Jacobian of a
// system built on it, such as multiple shooting's (nodes.hpp).
void shooting_function_dual(const Dual* x, double eps, Propagator& prop, Dual* F);

// Problems with interior events also have the shooting function by legs (RESIDUAL module; its
// `legs`: runtime_records.hpp's LegsOf).
void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs);
// The same on dual numbers (RESIDUAL module, with the JACOBIAN module): the legs' exact Jacobians.
void shooting_legs_dual(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs);
// shooting_legs_dual under shooting_legs's name: code a program writes once for either scalar calls
// one (the runtime calls both through kModules).
inline void shooting_legs(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs) {
  shooting_legs_dual(x, eps, prop, F, legs);
}

// SOLVE module: the whole solve.
Result solve_problem(const Settings& settings);

// The optional modules a program defines, declared: each entry the address of the program's
// function, or nullptr where the program has none. The runtime calls an optional module only
// through kModules, so a table that names a function the program does not define fails to link
// (undefined reference to it), and a function misspelt in its definition is not silently
// unused: the table still names the right one. HELIOS_MODULE_TABLE defines kModules and refuses,
// at compile time, a table that lacks what the problem needs (problem::kThrottleIndex,
// problem::kHasEvents, problem::kCoastingTarget of the PROBLEM block):
//   constexpr ModuleTable kModuleTable = [] {
//     ModuleTable t;
//     t.throttle_slopes = &throttle_slopes;
//     return t;
//   }();
//   HELIOS_MODULE_TABLE(kModuleTable);
struct ModuleTable {
  // SWITCH, with a throttle.
  void (*throttle_slopes)(const double* y, const Multipliers& mult, double& at_lower, double& at_upper) = nullptr;
  // RESIDUAL: a coasting target's dynamics; with events, the shooting function by legs.
  void (*coast_dynamics)(const double* y, double* dy) = nullptr;
  void (*shooting_legs)(const double* x, double eps, Propagator& prop, double* F, const Legs* legs) = nullptr;
  // RESIDUAL with the JACOBIAN module: the exact Jacobian and the shooting function on dual numbers
  // (shooting_function_dual without events, shooting_legs_dual with them).
  void (*shooting_jacobian)(const double* x, double eps, Propagator& prop, double* F, double* J) = nullptr;
  void (*shooting_function_dual)(const Dual* x, double eps, Propagator& prop, Dual* F) = nullptr;
  void (*shooting_legs_dual)(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs) = nullptr;
  // JACOBIAN: the variational equations' pieces (throttle_slopes_jacobian with a throttle).
  void (*dynamics_jacobian)(double t, const double* y, const double* control, const Multipliers& mult, double* dfdz,
                            double* dfdu) = nullptr;
  void (*direction_jacobian)(const double* y, double* dcontrol_dy) = nullptr;
  void (*throttle_slopes_jacobian)(const double* y, const Multipliers& mult, double* d_lower,
                                   double* d_upper) = nullptr;
};
extern const ModuleTable kModules;

// Defines kModules from `table` (a constexpr ModuleTable in namespace helios_rt, after the PROBLEM
// block), each need of the problem a static_assert whose message names the missing module.
#define HELIOS_MODULE_TABLE(table)                                                                        \
  static_assert(::problem::kThrottleIndex < 0 || (table).throttle_slopes != nullptr,                      \
                "HELIOS module table: the problem has a throttle but the table names no throttle_slopes " \
                "(SWITCH module)");                                                                       \
  static_assert(!::problem::kCoastingTarget || (table).coast_dynamics != nullptr,                         \
                "HELIOS module table: the problem has a coasting target but the table names no "          \
                "coast_dynamics (RESIDUAL module)");                                                      \
  static_assert(!::problem::kHasEvents || (table).shooting_legs != nullptr,                               \
                "HELIOS module table: the problem has events but the table names no shooting_legs "       \
                "(RESIDUAL module)");                                                                     \
  static_assert(((table).shooting_function_dual == nullptr && (table).shooting_legs_dual == nullptr) ||   \
                    ((table).dynamics_jacobian != nullptr && (table).direction_jacobian != nullptr &&     \
                     (::problem::kThrottleIndex < 0 || (table).throttle_slopes_jacobian != nullptr)),     \
                "HELIOS module table: a shooting function on dual numbers needs the JACOBIAN module "     \
                "(dynamics_jacobian, direction_jacobian, and throttle_slopes_jacobian with a throttle)"); \
  const ModuleTable kModules = (table)

}  // namespace helios_rt

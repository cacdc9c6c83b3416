#pragma once
// The plans of a program with events (internal to tools/lib/src/codegen): the LegPlan (what each
// leg between events solves for alone) and the EventPlan (the continuation onto the events).
#include <string>
#include <vector>

#include "context.hpp"

namespace helios::codegen::detail {

// kLegPlan and kEventPlan, then shooting_function as the plain case of shooting_legs;
// `leg_sizes` are the equations of each leg alone, checked against its unknowns.
std::string legs_block(Context& c, const std::vector<int>& leg_sizes);

}  // namespace helios::codegen::detail

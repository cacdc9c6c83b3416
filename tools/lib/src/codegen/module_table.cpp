// The module table: which optional modules a generated program defines (module_interface.hpp's
// ModuleTable), emitted after the SOLVE module so that the runtime calls them only through it and
// the program's compile refuses a table without what the problem needs.
#include <string>

#include "context.hpp"

namespace helios::codegen::detail {

std::string module_table(Context& c, bool jacobian) {
  const bool throttle = c.control_law.throttle.has_value();
  const bool events = !c.interior_events.empty();
  std::string entries;
  const auto entry = [&](bool defined, const std::string& name) {
    if (defined) entries += "  t." + name + " = &" + name + ";\n";
  };
  entry(throttle, "throttle_slopes");
  entry(c.coast_dynamics.has_value(), "coast_dynamics");
  entry(events, "shooting_legs");
  entry(jacobian, "shooting_jacobian");
  entry(jacobian && !events, "shooting_function_dual");
  entry(jacobian && events, "shooting_legs_dual");
  entry(jacobian, "dynamics_jacobian");
  entry(jacobian, "direction_jacobian");
  entry(jacobian && throttle, "throttle_slopes_jacobian");
  return "namespace helios_rt {\n"
         "// The optional modules this program defines (helios_runtime.hpp's ModuleTable): the runtime calls\n"
         "// them only through kModules, and HELIOS_MODULE_TABLE refuses a table without what the problem needs.\n"
         "constexpr ModuleTable kModuleTable = [] {\n"
         "  ModuleTable t;\n" +
         entries +
         "  return t;\n"
         "}();\n"
         "HELIOS_MODULE_TABLE(kModuleTable);\n"
         "}  // namespace helios_rt\n";
}

}  // namespace helios::codegen::detail

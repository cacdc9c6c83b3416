#pragma once
// helios-gen (builtin): a derivation -> one C++ shooting program made of the PROBLEM block, the
// generated (or template) modules and the entry point; it links the prebuilt runtime
// libhelios-runtime.a (templates/runtime) through its header helios_runtime.hpp.
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::codegen {

enum class ModulePolicy {
  Auto,       // template DYNAMICS/SWITCH when the derivation's H is the template model's, else generated
  Generated,  // always generate DYNAMICS/SWITCH from the derivation
};

struct GenOptions {
  ModulePolicy modules = ModulePolicy::Auto;
  // The JACOBIAN module (exact first derivatives, jacobian_module.cpp) and the RESIDUAL module's
  // shooting_jacobian built on it, where the derivation allows (autonomous dynamics): the solver
  // then uses the exact shooting Jacobian (hybrj). Off: hybrd's finite differences.
  bool jacobian = true;
};

struct GeneratedProgram {
  std::string source;                          // the whole shoot.cpp
  std::vector<std::string> generated_modules;  // e.g. RESIDUAL, SOLVE
  std::vector<std::string> template_modules;   // e.g. DYNAMICS, SWITCH
};

// Throws std::invalid_argument naming the derivation field it cannot turn into code.
GeneratedProgram generate(const io::json& derivation, const GenOptions& options);

// The PROBLEM block (namespace problem: sizes, names, units, constant parameters) of a derivation.
std::string problem_block(const io::json& derivation);

// The runtime's header as a program includes it (templates/runtime/helios_runtime.hpp): the
// problem's shape, the modules' prototypes and the runtime's declarations.
std::string runtime_header();

// The whole program around `modules` (C++ defining DYNAMICS, SWITCH, RESIDUAL and SOLVE in
// namespace helios_rt): the map (with the runtime's SHA-256, found beside the executable), the
// runtime header's include, the PROBLEM block, the modules, the entry point. `origin` names the generator in the first
// comment line (builtin, or llm and the model).
std::string assemble(const io::json& derivation, const std::string& modules, const std::string& origin);

}  // namespace helios::codegen

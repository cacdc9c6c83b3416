#include "helios/codegen/generate.hpp"

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "context.hpp"
#include "helios/io/embedded.hpp"
#include "helios/io/sha256.hpp"

namespace helios::codegen {
namespace {

using namespace detail;

// An embedded header as it goes into the single-file program (no include guard pragma there).
std::string pasted(const std::string& path) {
  std::istringstream in(embedded::file(path));
  std::string line, out;
  while (std::getline(in, line))
    if (line.rfind("#pragma once", 0) != 0) out += line + "\n";
  return out;
}

}  // namespace

GeneratedProgram generate(const json& derivation, const GenOptions& options) {
  Context c(derivation);
  GeneratedProgram g;
  std::string dynamics;
  const json model = json::parse(embedded::file("templates/modules/dynamics_cartesian_low_thrust.json"));
  if (options.modules == ModulePolicy::Auto && template_matches(c, model)) {
    dynamics = embedded::file("templates/modules/dynamics_cartesian_low_thrust.cpp");
    g.template_modules = {"DYNAMICS", "SWITCH"};
  } else {
    dynamics = generated_dynamics(c);
    g.generated_modules = {"DYNAMICS", "SWITCH"};
  }
  g.generated_modules.push_back("RESIDUAL");
  g.generated_modules.push_back("SOLVE");
  g.source = assemble(derivation, dynamics + "\n" + residual_module(c) + "\n" + solve_module(c) + "\n", "builtin");
  return g;
}

std::string problem_block(const json& derivation) {
  Context c(derivation);
  return problem_block(c);
}

std::string runtime_source() {
  std::istringstream umbrella(embedded::file("templates/runtime/runtime.hpp"));
  std::string line, out;
  const std::string include = "#include \"";
  while (std::getline(umbrella, line))
    if (line.rfind(include, 0) == 0)
      out +=
          pasted("templates/runtime/" + line.substr(include.size(), line.find('"', include.size()) - include.size())) +
          "\n";
  return out;
}

namespace {

// The lines `text` spans.
int line_count(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// The modules in `modules` by their banners ("// ----- module X ---", or the llm backend's
// "// ===== HELIOS LLM MODULE: X ====="): name and line, 0-based within modules.
std::vector<std::pair<std::string, int>> module_lines(const std::string& modules) {
  static const std::string builtin = "// ----- ", llm = "// ===== HELIOS LLM MODULE: ";
  std::vector<std::pair<std::string, int>> out;
  std::istringstream in(modules);
  std::string line;
  for (int k = 0; std::getline(in, line); ++k) {
    if (line.rfind(builtin, 0) == 0)
      out.emplace_back(line.substr(builtin.size(), line.find(" ---", builtin.size()) - builtin.size()), k);
    else if (line.rfind(llm, 0) == 0)
      out.emplace_back("module " + line.substr(llm.size(), line.find(" =====", llm.size()) - llm.size()), k);
  }
  return out;
}
}  // namespace

std::string assemble(const json& derivation, const std::string& modules, const std::string& origin) {
  Context c(derivation);
  std::ostringstream prelude;
  prelude << "#include <cminpack-1/cminpack.h>\n\n"
          << "#include <algorithm>\n#include <array>\n#include <atomic>\n#include <chrono>\n#include <cmath>\n#include "
             "<cstdint>\n"
          << "#include <cstdio>\n#include <exception>\n#include <fstream>\n#include <functional>\n#include "
             "<map>\n#include <mutex>\n"
          << "#include <nlohmann/json.hpp>\n#include <random>\n#include <sstream>\n#include <stdexcept>\n#include "
             "<string>\n"
          << "#include <system_error>\n#include <thread>\n#include <vector>\n\n"
          << "#define HELIOS_ASTRO_EMBEDDED\n"
          << pasted("tools/lib/include/helios/astro/constants.hpp") << "\n"
          << pasted("tools/lib/include/helios/astro/kepler.hpp") << "\n"
          << pasted("tools/lib/include/helios/astro/ephemeris.hpp") << "\n"
          << pasted("templates/runtime/dop853.hpp") << "\n";
  const std::string problem = problem_block(c) + "\n", runtime = runtime_source();
  // The map a program opens with: where each part starts (line numbers of the whole file), the
  // shared runtime's lines and its SHA-256.
  const auto modules_at = module_lines(modules);
  const int header = 2 + 1 + 1 + static_cast<int>(modules_at.size()) + 1 + 2;  // the lines before prelude
  const int problem_line = header + line_count(prelude.str()) + 1, runtime_line = problem_line + line_count(problem);
  const int modules_line = runtime_line + line_count(runtime);
  std::ostringstream map;
  map << "// Map (line numbers of this file):\n"
      << "//   " << problem_line << "  PROBLEM (generated)\n";
  for (const auto& [name, k] : modules_at) map << "//   " << modules_line + k << "  " << name << "\n";
  map << "//   " << modules_line + line_count(modules) << "  entry point (templates/runtime/main.hpp)\n"
      << "//   runtime (templates/runtime, shared by every program): lines " << runtime_line << "-" << modules_line - 1
      << "\n//   runtime SHA-256 " << io::sha256_hex(runtime) << "\n";
  std::ostringstream src;
  src << "// Shooting program for problem " << detail::comment_text(derivation.at("problem").at("id"))
      << ", generated by helios-gen " << HELIOS_VERSION << " (" << origin << ") from its derivation. Do not edit:\n"
      << "// regenerate it. Fixed runtime from templates/runtime, modules below marked generated or template.\n"
      << map.str() << prelude.str() << problem << runtime << modules << embedded::file("templates/runtime/main.hpp");
  return src.str();
}

}  // namespace helios::codegen

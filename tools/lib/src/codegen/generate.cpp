#include "helios/codegen/generate.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "context.hpp"
#include "helios/derivation/terms.hpp"
#include "helios/io/embedded.hpp"
#include "helios/solve/runtime_files.hpp"
#include "helios/solve/solve.hpp"

namespace helios::codegen {
using namespace detail;

namespace {

// Whether the derivation's listed terms are the template's: its force terms exactly, and a cost
// term the template's running cost stands for. A derivation that lists no terms (an llm's
// may not) is matched by its expressions alone, as template_matches compares them anyway.
bool template_terms_match(const std::optional<std::vector<derivation::Term>>& terms, const json& model) {
  if (!terms) return true;
  std::vector<std::string> forces, costs;
  for (const auto& t : *terms) (t.kind == "force" ? forces : costs).push_back(t.name);
  const auto allowed = model.at("cost_terms").get<std::vector<std::string>>();
  return forces == model.at("terms").get<std::vector<std::string>>() && costs.size() == 1 &&
         std::find(allowed.begin(), allowed.end(), costs[0]) != allowed.end();
}

}  // namespace

GeneratedProgram generate(const json& derivation, const GenOptions& options) {
  Context c(derivation);
  GeneratedProgram g;
  std::string dynamics;
  const json model = json::parse(embedded::file("templates/modules/dynamics_cartesian_low_thrust.json"));
  if (options.modules == ModulePolicy::Auto && template_terms_match(c.terms, model) && template_matches(c, model)) {
    dynamics = embedded::file("templates/modules/dynamics_cartesian_low_thrust.cpp");
    g.template_modules = {"DYNAMICS", "SWITCH"};
  } else {
    dynamics = generated_dynamics(c);
    g.generated_modules = {"DYNAMICS", "SWITCH"};
  }
  const bool jacobian = options.jacobian && jacobian_supported(c);
  if (jacobian) g.generated_modules.push_back("JACOBIAN");
  g.generated_modules.push_back("RESIDUAL");
  g.generated_modules.push_back("SOLVE");
  g.source =
      assemble(derivation,
               dynamics + "\n" + (jacobian ? generated_jacobians(c) + "\n" : std::string()) +
                   residual_module(c, jacobian) + "\n" + solve_module(c) + "\n" + module_table(c, jacobian) + "\n",
               "builtin");
  // The output check: the compile cache reads its numbers (one program serves every problem of its
  // structure), which nothing reads before main (tools/lib/src/solve/README.md, "The compile cache").
  if (const solve::ProgramParameters p = solve::program_parameters(g.source); !p.readable)
    throw std::invalid_argument("the generated program's numbers are not the compile cache's to replace: " +
                                p.whole_source_because);
  return g;
}

std::string problem_block(const json& derivation) {
  Context c(derivation);
  return problem_block(c);
}

std::string runtime_header() {
  // The public header's three parts, in the order it includes them (what a program sees).
  return embedded::file("templates/runtime/runtime_records.hpp") +
         embedded::file("templates/runtime/runtime_calls.hpp") +
         embedded::file("templates/runtime/module_interface.hpp");
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
  // The runtime is not in the program: it is the prebuilt library, declared by its header.
  const std::string prelude = "#include \"helios_runtime.hpp\"\n\n";
  const std::string problem = problem_block(c) + "\n";
  // The map a program opens with: where each part starts (line numbers of the whole file), and
  // the runtime it links against.
  const auto modules_at = module_lines(modules);
  const int header = 2 + 1 + 1 + static_cast<int>(modules_at.size()) + 1 + 2;  // the lines before prelude
  const int problem_line = header + line_count(prelude) + 1, modules_line = problem_line + line_count(problem);
  std::ostringstream map;
  map << "// Map (line numbers of this file):\n"
      << "//   " << problem_line << "  PROBLEM (generated)\n";
  for (const auto& [name, k] : modules_at) map << "//   " << modules_line + k << "  " << name << "\n";
  map << "//   " << modules_line + line_count(modules) << "  entry point (templates/runtime/main.hpp)\n"
      << "//   runtime (templates/runtime, shared by every program): libhelios-runtime.a and helios_runtime.hpp\n"
      << "//   runtime SHA-256 " << solve::runtime_sha256() << "\n";
  std::ostringstream src;
  src << "// Shooting program for problem " << detail::comment_text(c.problem_id) << ", generated by helios-gen "
      << HELIOS_VERSION << " (" << origin << ") from its derivation. Do not edit:\n"
      << "// regenerate it. Links the prebuilt runtime (templates/runtime); modules below marked generated or "
         "template.\n"
      << map.str() << prelude << problem << modules << embedded::file("templates/runtime/main.hpp");
  return src.str();
}

}  // namespace helios::codegen

// helios-gen: derivation.json -> shoot.cpp (the problem and its generated modules, linking the
// prebuilt runtime, or modules written by the llm backend, one gen <-> compile repair round per call).
#include <optional>

#include "helios/codegen/generate.hpp"
#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/llm/backend.hpp"
#include "helios/symbolic/expr.hpp"

int main(int argc, char** argv) {
  helios::symbolic::fix_expression_order(argv);
  const helios::cli::ToolInfo info{
      "helios-gen",
      "generate the C++ shooting program of a derivation",
      "[options] DERIVATION.json|-",
      {{"backend", "", "NAME", "generator backend: builtin or llm", "builtin"},
       {"modules", "", "POLICY",
        "auto: template DYNAMICS/SWITCH when the derivation is the template's model; generated: always from the "
        "derivation",
        "auto"},
       {"jacobian", "", "MODE",
        "builtin: exact (the JACOBIAN module, exact df/dz, df/du, du/dy by GiNaC, and shooting_jacobian: the solver "
        "uses the exact shooting Jacobian where the dynamics are autonomous) or finite-difference (neither)",
        "exact"},
       {"previous", "", "FILE", "llm: shoot.cpp of the round before", ""},
       {"compile-report", "", "FILE", "llm: compile report of --previous (helios-solve --compile-only)", ""},
       {"round", "", "N", "llm: repair round number (1 = first generation)", "1"},
       {"transcript", "", "FILE", "llm: transcript of the exchange (default: next to -o, NAME.transcript.json)", ""},
       helios::cli::time_limit_option("the generation", "120"),
       helios::cli::memory_limit_option("the generation", "2048")},
      {"DERIVATION"},
      "The program is one C++17 file of the problem and its modules (RESIDUAL and SOLVE generated\n"
      "from the shooting system); it links the prebuilt runtime libhelios-runtime.a (ephemeris,\n"
      "DOP853 with switch detection, eps-homotopy, a global search over seeded starts, cminpack hybrj\n"
      "with the exact Jacobian (hybrd without it), a multiple-shooting polish, JSON output).\n"
      "With --backend llm the model writes the four modules (prompts/codegen.txt); round N > 1 sends\n"
      "the compiler's errors of --previous (prompts/repair.txt), and when --compile-report says the\n"
      "previous program compiled, writes it unchanged without asking the model.",
      "helios-gen runs/builtin/S01/derivation.json -o runs/builtin/S01/shoot.cpp"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    const std::string backend = helios::cli::backend_option(args, {"builtin", "llm"});
    helios::cli::limit_work("helios-gen", args);
    if (backend == "llm") {
      helios::llm::GenRequest request{helios::io::read_artifact("derivation", args.positionals[0]), std::nullopt,
                                      std::nullopt};
      if (args.has("previous")) request.previous_source = helios::io::read_text(args.get("previous"));
      if (args.has("compile-report"))
        request.compile_report = helios::io::read_artifact("compile", args.get("compile-report"));
      const int round = static_cast<int>(helios::cli::integer_option(args, "round", 1, 100));
      const auto call = helios::llm::call_info(args.output, args.get("transcript"), round);
      helios::io::write_text_atomic(args.output, helios::llm::generate(request, call));
      return 0;
    }
    for (const char* llm_only : {"previous", "compile-report", "transcript"})
      if (args.has(llm_only)) throw helios::usage_error(std::string("--") + llm_only + " needs --backend llm");
    helios::codegen::GenOptions options;
    const std::string jacobian = args.get("jacobian");
    if (jacobian != "exact" && jacobian != "finite-difference")
      throw helios::usage_error("--jacobian " + jacobian + " is not one of exact, finite-difference");
    options.jacobian = jacobian == "exact";
    const std::string policy = args.get("modules");
    if (policy == "generated")
      options.modules = helios::codegen::ModulePolicy::Generated;
    else if (policy != "auto")
      throw helios::usage_error("--modules " + policy + " is not one of auto, generated");
    const std::string& input = args.positionals[0];
    helios::cli::naming_input(input, [&] {
      const auto derivation = helios::io::read_artifact("derivation", input);
      helios::io::write_text_atomic(args.output, helios::codegen::generate(derivation, options).source);
    });
    return 0;
  });
}

// helios-derive: spec.json -> derivation.json (builtin symbolic PMP engine on GiNaC, or the llm
// backend, one derive <-> verify refinement round per call).
#include <optional>

#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/llm/backend.hpp"
#include "helios/pmp/derive.hpp"
#include "helios/symbolic/expr.hpp"

int main(int argc, char** argv) {
  helios::symbolic::fix_expression_order(argv);
  const helios::cli::ToolInfo info{
      "helios-derive",
      "derive the PMP necessary conditions and the shooting system of a problem",
      "[options] SPEC.json|-",
      {{"backend", "", "NAME", "deriver backend: builtin or llm", "builtin"},
       {"previous", "", "FILE", "llm: the derivation of the round before", ""},
       {"feedback", "", "FILE", "llm: verify.json of --previous; its failed checks go into the prompt", ""},
       {"round", "", "N", "llm: refinement round number (1 = first attempt)", "1"},
       {"transcript", "", "FILE", "llm: transcript of the exchange (default: next to -o, NAME.transcript.json)", ""},
       helios::cli::time_limit_option("the symbolic work", "120"),
       helios::cli::memory_limit_option("the symbolic work", "2048")},
      {"SPEC"},
      "Builds H = lambda0 L + lambda^T f, the state and costate ODEs, the optimal control law with\n"
      "its switching function and eps smoothing, the transversality conditions from psi, and the\n"
      "shooting variables and equations (with meaning and scaling). Expressions are GiNaC text.\n"
      "With --backend llm the model derives them (prompts/pmp_derive.txt) from the spec and the tool's\n"
      "normalized units and parameters; the reply is schema-checked and must be readable by\n"
      "helios-verify, else it is fed back. Round N > 1 takes --previous and its --feedback: when that\n"
      "verification passed, the previous derivation is written unchanged and the model is not asked.",
      "helios-derive runs/builtin/S01/spec.json -o runs/builtin/S01/derivation.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    const std::string backend = helios::cli::backend_option(args, {"builtin", "llm"});
    helios::cli::limit_work("helios-derive", args);
    const std::string& input = args.positionals[0];
    const auto spec = helios::io::read_artifact("spec", input);
    if (backend == "builtin") {
      for (const char* llm_only : {"previous", "feedback", "transcript"})
        if (args.has(llm_only)) throw helios::usage_error(std::string("--") + llm_only + " needs --backend llm");
      helios::cli::naming_input(
          input, [&] { helios::io::write_artifact("derivation", helios::pmp::derive_from_spec(spec), args.output); });
      return 0;
    }
    helios::llm::DeriveRequest request{spec, std::nullopt, std::nullopt};
    if (args.has("previous")) request.previous = helios::io::read_artifact("derivation", args.get("previous"));
    if (args.has("feedback")) request.feedback = helios::io::read_artifact("verify", args.get("feedback"));
    const int round = static_cast<int>(helios::cli::integer_option(args, "round", 1, 100));
    const auto call = helios::llm::call_info(args.output, args.get("transcript"), round);
    helios::io::write_artifact("derivation", helios::llm::derive(request, call), args.output);
    return 0;
  });
}

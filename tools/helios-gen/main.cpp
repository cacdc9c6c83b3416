// helios-gen: derivation.json -> shoot.cpp (fixed runtime from templates/ + generated modules).
#include "helios/codegen/generate.hpp"
#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"

int main(int argc, char** argv) {
  const helios::cli::ToolInfo info{
      "helios-gen",
      "generate the C++ shooting program of a derivation",
      "[options] DERIVATION.json|-",
      {{"backend", "", "NAME", "generator backend: builtin", "builtin"},
       {"modules", "", "POLICY",
        "auto: template DYNAMICS/SWITCH when the derivation is the template's model; generated: always from the "
        "derivation",
        "auto"}},
      {"DERIVATION"},
      "The program is one self-contained C++17 file: the fixed runtime (normalization, ephemeris,\n"
      "DOP853 with switch detection, eps-homotopy, seeded restarts, cminpack hybrd1, JSON output)\n"
      "and the modules RESIDUAL and SOLVE generated from the shooting system.",
      "helios-gen runs/builtin/S01/derivation.json -o runs/builtin/S01/shoot.cpp"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    helios::cli::backend_option(args, {"builtin"});
    helios::codegen::GenOptions options;
    const std::string policy = args.get("modules");
    if (policy == "generated")
      options.modules = helios::codegen::ModulePolicy::Generated;
    else if (policy != "auto")
      throw helios::usage_error("--modules " + policy + " is not one of auto, generated");
    const auto derivation = helios::io::read_artifact("derivation", args.positionals[0]);
    helios::io::write_text_atomic(args.output, helios::codegen::generate(derivation, options).source);
    return 0;
  });
}

// helios-derive: spec.json -> derivation.json (builtin symbolic PMP engine on GiNaC).
#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/pmp/derive.hpp"

int main(int argc, char** argv) {
  const helios::cli::ToolInfo info{
      "helios-derive",
      "derive the PMP necessary conditions and the shooting system of a problem",
      "[options] SPEC.json|-",
      {{"backend", "", "NAME", "deriver backend: builtin", "builtin"}},
      {"SPEC"},
      "Builds H = lambda0 L + lambda^T f, the state and costate ODEs, the optimal control law with\n"
      "its switching function and eps smoothing, the transversality conditions from psi, and the\n"
      "shooting variables and equations (with meaning and scaling). Expressions are GiNaC text.",
      "helios-derive runs/builtin/S01/spec.json -o runs/builtin/S01/derivation.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    helios::cli::backend_option(args, {"builtin"});
    const auto spec = helios::io::read_artifact("spec", args.positionals[0]);
    helios::io::write_artifact("derivation", helios::pmp::derive_from_spec(spec), args.output);
    return 0;
  });
}

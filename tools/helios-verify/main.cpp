// helios-verify: derivation.json -> verify.json (independent GiNaC recomputation of the PMP conditions).
#include <string>

#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/symbolic/expr.hpp"
#include "helios/verify/verify.hpp"

int main(int argc, char** argv) {
  helios::symbolic::fix_expression_order(argv);
  const helios::cli::ToolInfo info{
      "helios-verify",
      "check a derivation (builtin or LLM-written) by recomputing its necessary conditions",
      "[options] DERIVATION.json|-",
      {{"points", "", "N", "random sample points per check", "25"},
       {"seed", "", "N", "seed of the random sample points", "1"},
       {"advisory", "", "", "exit 0 even when the verdict is fail", ""},
       helios::cli::time_limit_option("the symbolic work", "120"),
       helios::cli::memory_limit_option("the symbolic work", "2048")},
      {"DERIVATION"},
      "Trusts only the problem statement of the derivation (states, controls, parameters, dynamics,\n"
      "costs, the constraints' targets) and recomputes H, the state and costate ODEs, the direction\n"
      "and throttle laws, transversality, the shooting counts and the normalization with GiNaC; psi\n"
      "must vanish, with full rank, at random states of each target. Each equality is tested\n"
      "at N random points (relative tolerance 1e-9) and, where GiNaC can show it, exactly. Every check\n"
      "carries a feedback sentence for the next refinement round. Exit 4 when the verdict is fail.",
      "helios-verify runs/builtin/S01/derivation.json -o runs/builtin/S01/verify.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    helios::verify::VerifyOptions options;
    options.points = static_cast<int>(helios::cli::integer_option(args, "points", 1, 100000));
    options.seed = static_cast<unsigned>(helios::cli::integer_option(args, "seed", 0, 4294967295L));
    helios::cli::limit_work("helios-verify", args);
    const auto derivation = helios::io::read_artifact("derivation", args.positionals[0]);
    const auto report = helios::verify::verify_derivation(derivation, options);
    helios::io::write_artifact("verify", report, args.output);
    if (report["verdict"] == "fail" && !args.has("advisory")) {
      std::string ids;
      for (const auto& c : report["checks"])
        if (c["verdict"] == "fail") ids += (ids.empty() ? "" : ", ") + c["id"].get<std::string>();
      throw helios::check_failed("verdict fail: " + std::to_string(report["summary"]["failed"].get<int>()) + " of " +
                                 std::to_string(report["summary"]["total"].get<int>()) + " checks failed (" + ids +
                                 ")");
    }
    return 0;
  });
}

// helios-parse: problem text -> spec.json (builtin controlled-English parser).
#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/spec/parse.hpp"

int main(int argc, char** argv) {
  const helios::cli::ToolInfo info{
      "helios-parse",
      "read a trajectory problem stated in controlled English into spec.json",
      "[options] PROBLEM.txt|-",
      {{"backend", "", "NAME", "parser backend: builtin", "builtin"}},
      {"PROBLEM"},
      "Every sentence must match a form of the controlled English documented in README.md;\n"
      "a sentence that does not is an error quoting it. Quantities are converted to the spec's\n"
      "units (km, km/s, N, s, days, kg, km^3/s^2).",
      "helios-parse scenarios/S01/problem.txt -o runs/builtin/S01/spec.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    helios::cli::backend_option(args, {"builtin"});
    const std::string& input = args.positionals[0];
    const auto spec = helios::spec::parse_problem_text(helios::io::read_text(input), input == "-" ? "<stdin>" : input);
    helios::io::write_artifact("spec", spec, args.output);
    return 0;
  });
}

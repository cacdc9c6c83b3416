// helios-parse: problem text -> spec.json (builtin controlled-English parser, or the llm backend).
#include "helios/io/cli.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/llm/backend.hpp"
#include "helios/spec/parse.hpp"
#include "helios/symbolic/expr.hpp"

int main(int argc, char** argv) {
  helios::symbolic::fix_expression_order(argv);
  const helios::cli::ToolInfo info{
      "helios-parse",
      "read a trajectory problem stated in controlled English into spec.json",
      "[options] PROBLEM.txt|-",
      {{"backend", "", "NAME", "parser backend: builtin or llm", "builtin"},
       {"transcript", "", "FILE", "llm: transcript of the exchange (default: next to -o, NAME.transcript.json)", ""},
       helios::cli::time_limit_option("reading the text", "60"),
       helios::cli::memory_limit_option("reading the text", "2048")},
      {"PROBLEM"},
      "Every sentence must match a form of the controlled English documented in README.md;\n"
      "a sentence that does not is an error quoting it. Quantities are converted to the spec's\n"
      "units (km, km/s, N, s, days, kg, km^3/s^2; orbital elements in AU and deg).\n"
      "With --backend llm the model reads the text (prompts/parse.txt) and its reply is schema-checked;\n"
      "a reply that is not a valid spec is fed back (HELIOS_LLM_MAX_TURNS). Endpoint and model come\n"
      "from HELIOS_LLM_BASE_URL, HELIOS_LLM_MODEL and HELIOS_LLM_API_KEY (see README.md).",
      "helios-parse scenarios/S01/problem.txt -o runs/builtin/S01/spec.json"};
  return helios::cli::run_tool(info, argc, argv, [](const helios::cli::Args& args) {
    const std::string backend = helios::cli::backend_option(args, {"builtin", "llm"});
    helios::cli::limit_work("helios-parse", args);
    const std::string& input = args.positionals[0];
    const std::string source = input == "-" ? "<stdin>" : input;
    if (backend == "llm") {
      const auto call = helios::llm::call_info(args.output, args.get("transcript"), 1);
      const std::string text = helios::io::read_text(input);
      helios::io::write_artifact("spec", helios::llm::parse_problem(text, source, call), args.output);
      return 0;
    }
    const auto spec = helios::spec::parse_problem_text(helios::io::read_text(input), source);
    helios::io::write_artifact("spec", spec, args.output);
    return 0;
  });
}

#pragma once
// The shared command-line runner of the helios-* tools: option parsing, --help/--version,
// and the mapping from exceptions to one-line errors and documented exit codes.
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace helios::cli {

struct Option {
  std::string name;        // long name without dashes, e.g. "backend"
  std::string short_name;  // e.g. "o", or ""
  std::string value_name;  // e.g. "FILE"; empty for a flag
  std::string help;
  std::string default_value;
};

struct ToolInfo {
  std::string name;                      // helios-parse
  std::string summary;                   // one line
  std::string usage;                     // "[options] PROBLEM.txt|-"
  std::vector<Option> options;           // besides -o, --help, --version
  std::vector<std::string> positionals;  // names of required positional arguments
  std::string description;               // paragraphs after the usage line
  std::string example;                   // the e.g.: line
};

struct Args {
  std::vector<std::string> positionals;
  std::map<std::string, std::string> values;  // option name -> value ("1" for flags)
  std::string output = "-";
  // True if the option was given a non-empty value (or the flag was given).
  bool has(const std::string& name) const { return values.count(name) > 0 && !values.at(name).empty(); }
  const std::string& get(const std::string& name) const { return values.at(name); }
};

std::string help_text(const ToolInfo& info);

// Typed option values; each throws usage_error "--NAME VALUE is not ..." on a bad value.
long integer_option(const Args& args, const std::string& name, long min, long max);
double positive_option(const Args& args, const std::string& name);
// The value of option `name`, a folder made when missing: refused (usage_error naming the option
// and its value) when it, or the nearest part of its path that exists, is not a folder.
std::string folder_option(const Args& args, const std::string& name);
// The --backend value, which must be one of `available`.
std::string backend_option(const Args& args, const std::vector<std::string>& available);

// The options of a tool's own work budget (--time-limit, --memory-limit), with their defaults, and
// their application: limit_work() bounds this process's CPU time and address space. Beyond the
// CPU time the tool prints "<tool>: error: ... exceeded the CPU-time budget of N s" and exits
// kExitOther with no artifact written; an allocation beyond the memory budget is reported by
// run_tool as "out of memory: ... budget of N MB" (exit kExitOther). Under AddressSanitizer, whose
// shadow memory needs terabytes of address space, the memory budget is not applied.
Option time_limit_option(const std::string& work, const std::string& seconds);
Option memory_limit_option(const std::string& work, const std::string& mb);
void limit_work(const std::string& tool, const Args& args);

// Runs `work`, which reads the input `source` ("-" = stdin): an error about that input
// (input_error, std::invalid_argument, std::domain_error) whose message does not start with a
// file name already is rethrown as input_error "SOURCE: <message>", so that a library's
// "field /x: ..." names the file too.
void naming_input(const std::string& source, const std::function<void()>& work);

// A mode of a tool that does several jobs (helios-score --report, --oem, ...): the flag that
// selects it ("" for the default mode), the options it needs and those it may take besides them.
struct Mode {
  std::string flag;
  std::vector<std::string> needs;
  std::vector<std::string> takes;
  std::function<int(const Args&)> run;
};

// The one mode `args` select: the mode whose flag was given, else the default one. Throws
// usage_error naming the two flags given, a needed option missing ("--report needs --problem
// FILE"), or an option the mode does not take ("--report takes no --trajectory (it goes with
// --oem)", "--problem goes with --report").
const Mode& select_mode(const ToolInfo& info, const Args& args, const std::vector<Mode>& modes);

// Parses argv; throws usage_error. Returns false if --help or --version was handled.
bool parse_args(const ToolInfo& info, int argc, char** argv, Args& args);

// Runs `body` and returns the process exit code, printing "<tool>: error: <what>" on failure.
int run_tool(const ToolInfo& info, int argc, char** argv, const std::function<int(const Args&)>& body);

}  // namespace helios::cli

#include "helios/io/cli.hpp"

#include <cln/malloc.h>
#include <gmp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>

#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"

namespace helios::cli {
namespace {

const Option* find_option(const ToolInfo& info, const std::string& name, bool by_short) {
  for (const auto& opt : info.options)
    if ((by_short ? opt.short_name : opt.name) == name) return &opt;
  return nullptr;
}

// What the budget handlers write: fixed storage, so that they do not allocate.
char g_cpu_budget_message[512] = {};
char g_memory_budget_message[512] = {};
double g_memory_budget_mb = 0;

[[noreturn]] void exit_beyond_budget(const char* message) {
  io::remove_registered_temps();
  const ssize_t ignored = ::write(STDERR_FILENO, message, std::strlen(message));
  (void)ignored;
  ::_exit(kExitOther);
}

void cpu_budget_exceeded(int) {
  exit_beyond_budget(g_cpu_budget_message);
}

// GMP and CLN abort when an allocation fails (GMP printing its own line); with a memory budget
// set, their allocations go through these, which report the budget instead.
void* budget_malloc(std::size_t n) {
  void* p = std::malloc(n);
  if (p == nullptr && n > 0) exit_beyond_budget(g_memory_budget_message);
  return p;
}
void* gmp_budget_realloc(void* p, std::size_t, std::size_t n) {
  void* q = std::realloc(p, n);
  if (q == nullptr && n > 0) exit_beyond_budget(g_memory_budget_message);
  return q;
}
void gmp_free(void* p, std::size_t) {
  std::free(p);
}

bool under_address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#endif
#endif
  return false;
}

}  // namespace

Option time_limit_option(const std::string& work, const std::string& seconds) {
  return {"time-limit", "", "SECONDS", "CPU-time budget of " + work + " (beyond it: an error, exit 1)", seconds};
}

Option memory_limit_option(const std::string& work, const std::string& mb) {
  return {"memory-limit", "", "MB", "memory (address-space) budget of " + work + " (beyond it: exit 1)", mb};
}

void limit_work(const std::string& tool, const Args& args) {
  const double seconds = positive_option(args, "time-limit");
  const double mb = positive_option(args, "memory-limit");
  std::snprintf(g_cpu_budget_message, sizeof g_cpu_budget_message,
                "%s: error: the work exceeded the CPU-time budget of %g s (--time-limit); no artifact written\n",
                tool.c_str(), seconds);
  std::snprintf(g_memory_budget_message, sizeof g_memory_budget_message,
                "%s: error: the work exceeded the memory budget of %g MB (--memory-limit); no artifact written\n",
                tool.c_str(), mb);
  std::signal(SIGXCPU, cpu_budget_exceeded);
  const auto cpu = static_cast<rlim_t>(std::ceil(seconds));
  const rlimit cpu_limit{cpu, cpu + 5};  // the hard limit kills a process that ignores SIGXCPU
  ::setrlimit(RLIMIT_CPU, &cpu_limit);
  if (under_address_sanitizer()) return;
  g_memory_budget_mb = mb;
  mp_set_memory_functions(budget_malloc, gmp_budget_realloc, gmp_free);
  cln::malloc_hook = budget_malloc;
  const auto bytes = static_cast<rlim_t>(mb * 1024 * 1024);
  const rlimit memory_limit{bytes, bytes};
  ::setrlimit(RLIMIT_AS, &memory_limit);
}

void naming_input(const std::string& source, const std::function<void()>& work) {
  const std::string name = source == "-" ? "<stdin>" : source;
  const auto rethrow = [&](const std::exception& e) {
    const std::string what = e.what();
    if (what.rfind(name + ":", 0) == 0) throw;
    throw input_error(name + ": " + what);
  };
  try {
    work();
  } catch (const input_error& e) {
    rethrow(e);
  } catch (const std::invalid_argument& e) {
    rethrow(e);
  } catch (const std::domain_error& e) {
    rethrow(e);
  }
}

std::string help_text(const ToolInfo& info) {
  std::ostringstream out;
  out << info.name << " - " << info.summary << "\n\n"
      << "usage: " << info.name << " " << info.usage << "\n\n";
  if (!info.description.empty()) out << info.description << "\n\n";
  out << "options:\n"
      << "  -o, --output FILE   write the artifact to FILE atomically; - = stdout (default -)\n";
  for (const auto& opt : info.options) {
    std::string head =
        "  " + (opt.short_name.empty() ? std::string("    ") : "-" + opt.short_name + ", ") + "--" + opt.name;
    if (!opt.value_name.empty()) head += " " + opt.value_name;
    out << head << std::string(head.size() < 22 ? 22 - head.size() : 1, ' ') << opt.help;
    if (!opt.default_value.empty()) out << " (default " << opt.default_value << ")";
    out << "\n";
  }
  out << "  -h, --help          print this help and exit\n"
      << "      --version       print the version and exit\n\n"
      << "exit codes: 0 ok, 1 other failure (solver, I/O), 2 usage, 3 invalid input, 4 check failed,\n"
      << "5 the problem is infeasible (helios-solve: solution.json written, with the minimum time that shows it)\n"
      << "e.g.: " << info.example << "\n";
  return out.str();
}

bool parse_args(const ToolInfo& info, int argc, char** argv, Args& args) {
  // Options with a value always have one (possibly empty); flags are present only when given.
  for (const auto& opt : info.options)
    if (!opt.value_name.empty()) args.values[opt.name] = opt.default_value;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::cout << help_text(info);
      return false;
    }
    if (a == "--version") {
      std::cout << info.name << " " << HELIOS_VERSION << "\n";
      return false;
    }
    if (a == "-" || a.empty() || a[0] != '-') {
      args.positionals.push_back(a);
      continue;
    }
    const bool is_long = a.rfind("--", 0) == 0;
    std::string name = is_long ? a.substr(2) : a.substr(1);
    std::string value;
    bool has_inline_value = false;
    if (const auto eq = name.find('='); is_long && eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_inline_value = true;
    }
    const bool is_output = name == "output" || (!is_long && name == "o");
    const Option* opt = is_output ? nullptr : find_option(info, name, !is_long);
    if (!is_output && !opt) throw usage_error("unknown option " + a + ", see " + info.name + " --help");
    const bool takes_value = is_output || !opt->value_name.empty();
    if (takes_value && !has_inline_value) {
      if (i + 1 >= argc) throw usage_error("option " + a + " needs a value, see " + info.name + " --help");
      value = argv[++i];
    }
    if (!takes_value && has_inline_value) throw usage_error("option --" + name + " takes no value");
    if (is_output)
      args.output = value;
    else
      args.values[opt->name] = takes_value ? value : "1";
  }
  if (args.positionals.size() != info.positionals.size()) {
    std::string names;
    for (const auto& p : info.positionals) names += (names.empty() ? "" : " ") + p;
    throw usage_error("expected " + std::to_string(info.positionals.size()) + " input argument(s) (" + names +
                      "), got " + std::to_string(args.positionals.size()) + ", see " + info.name + " --help");
  }
  return true;
}

long integer_option(const Args& args, const std::string& name, long min, long max) {
  const std::string& text = args.get(name);
  std::size_t used = 0;
  long value = -1;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < min || value > max)
    throw usage_error("--" + name + " " + text + " is not an integer in [" + std::to_string(min) + ", " +
                      std::to_string(max) + "]");
  return value;
}

double positive_option(const Args& args, const std::string& name) {
  const std::string& text = args.get(name);
  std::size_t used = 0;
  double value = -1;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(value > 0) || !std::isfinite(value))
    throw usage_error("--" + name + " " + text + " is not a positive number");
  return value;
}

std::string folder_option(const Args& args, const std::string& name) {
  const std::string& value = args.get(name);
  std::error_code ec;
  for (std::filesystem::path p = value; !p.empty(); p = p.parent_path()) {
    const auto status = std::filesystem::status(p, ec);
    if (std::filesystem::is_directory(status)) break;
    if (std::filesystem::exists(status))
      throw usage_error("--" + name + " " + value + ": " + (p == value ? "" : p.string() + " ") +
                        "is not a folder, name a folder (it is made when missing)");
    if (p == p.parent_path()) break;
  }
  return value;
}

const Mode& select_mode(const ToolInfo& info, const Args& args, const std::vector<Mode>& modes) {
  const std::string see = ", see " + info.name + " --help";
  const Mode* chosen = nullptr;
  const Mode* fallback = nullptr;
  for (const auto& m : modes) {
    if (m.flag.empty()) fallback = &m;
    if (m.flag.empty() || !args.has(m.flag)) continue;
    if (chosen) throw usage_error("--" + chosen->flag + " and --" + m.flag + " are two jobs: give one" + see);
    chosen = &m;
  }
  if (!chosen) chosen = fallback;
  if (!chosen) throw usage_error("no job given" + see);
  const auto declared = [&](const std::string& option) {
    for (const auto& o : info.options)
      if (o.name == option) return o;
    return Option{};
  };
  const auto takes = [](const Mode& m, const std::string& option) {
    return option == m.flag || std::find(m.needs.begin(), m.needs.end(), option) != m.needs.end() ||
           std::find(m.takes.begin(), m.takes.end(), option) != m.takes.end();
  };
  for (const auto& [option, value] : args.values) {
    if (value.empty() || value == declared(option).default_value || takes(*chosen, option)) continue;
    std::string others;
    for (const auto& m : modes)
      if (!m.flag.empty() && takes(m, option)) others += (others.empty() ? "--" : " or --") + m.flag;
    if (chosen->flag.empty())
      throw usage_error("--" + option + " goes with " + (others.empty() ? "another job" : others) + see);
    throw usage_error("--" + chosen->flag + " takes no --" + option +
                      (others.empty() ? "" : " (it goes with " + others + ")") + see);
  }
  for (const auto& option : chosen->needs)
    if (!args.has(option))
      throw usage_error((chosen->flag.empty() ? "missing" : "--" + chosen->flag + " needs") + " --" + option + " " +
                        declared(option).value_name + see);
  return *chosen;
}

std::string backend_option(const Args& args, const std::vector<std::string>& available) {
  const std::string& backend = args.get("backend");
  std::string names;
  for (const auto& a : available) {
    if (a == backend) return backend;
    names += (names.empty() ? "" : ", ") + a;
  }
  throw usage_error("--backend " + backend + " is not available in this build (use " + names + ")");
}

int run_tool(const ToolInfo& info, int argc, char** argv, const std::function<int(const Args&)>& body) {
  io::install_cleanup_handlers();
  const auto fail = [&](int code, const std::string& what) {
    std::cerr << info.name << ": error: " << what << "\n";
    return code;
  };
  try {
    Args args;
    if (!parse_args(info, argc, argv, args)) return kExitOk;
    return body(args);
  } catch (const usage_error& e) {
    return fail(kExitUsage, e.what());
  } catch (const input_error& e) {
    return fail(kExitInvalidInput, e.what());
  } catch (const std::invalid_argument& e) {
    return fail(kExitInvalidInput, e.what());
  } catch (const std::domain_error& e) {
    return fail(kExitInvalidInput, e.what());
  } catch (const check_failed& e) {
    return fail(kExitCheckFailed, e.what());
  } catch (const std::bad_alloc&) {
    if (g_memory_budget_mb > 0) exit_beyond_budget(g_memory_budget_message);
    return fail(kExitOther, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitOther, e.what());
  }
}

}  // namespace helios::cli

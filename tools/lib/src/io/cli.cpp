#include "helios/io/cli.hpp"

#include <cmath>
#include <exception>
#include <iostream>
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

}  // namespace

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
      << "exit codes: 0 ok, 1 other failure (solver, I/O), 2 usage, 3 invalid input, 4 check failed\n"
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
  } catch (const std::exception& e) {
    return fail(kExitOther, e.what());
  }
}

}  // namespace helios::cli

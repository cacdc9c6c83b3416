// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, parameters (templates/runtime/parameters.hpp): the program's
// HELIOS_PARAMETERs by name, and the parameters file that replaces their values before the solve
// (helios_runtime.hpp says why).
// ---------------------------------------------------------------------------------------------
#pragma once

namespace helios_rt {

namespace {

struct Parameter {
  std::string name;
  double* values;
  int count;
  bool array;
};

// Filled by the program's registrations, during its static initialisation (before main).
std::vector<Parameter>& parameters() {
  static std::vector<Parameter> registered;
  return registered;
}

// A parameters file's value as `p`'s numbers: a finite number, or an array of p.count of them.
std::vector<double> parameter_values(const Parameter& p, const nlohmann::json& v, const std::string& where) {
  const std::string wanted = p.array ? "an array of " + std::to_string(p.count) + " finite numbers" : "a finite number";
  std::vector<double> out;
  if (p.array ? !v.is_array() || static_cast<int>(v.size()) != p.count : !v.is_number())
    throw std::runtime_error(where + " is not " + wanted);
  for (const auto& x : p.array ? v : nlohmann::json::array({v})) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) throw std::runtime_error(where + " is not " + wanted);
    out.push_back(x.get<double>());
  }
  return out;
}

// The program's scalar parameter `name` (nullptr: it has none), for the paths that move one.
inline double* scalar_parameter(const std::string& name) {
  for (const Parameter& p : parameters())
    if (!p.array && p.name == name) return p.values;
  return nullptr;
}

}  // namespace

ParameterRegistration::ParameterRegistration(const char* name, double* values, int count, bool array) {
  parameters().push_back({name, values, count, array});
}

void load_parameters(const std::string& path) {
  const std::string file = "parameters " + path;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + file);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file + ": not JSON: " + e.what());
  }
  if (!j.is_object() || j.size() != 2 || j.value("schema", nlohmann::json()) != "helios/parameters" ||
      !j.contains("values") || !j.at("values").is_object())
    throw std::runtime_error(file + ": not {\"schema\": \"helios/parameters\", \"values\": {...}}");
  const nlohmann::json& values = j.at("values");
  std::vector<std::vector<double>> read;
  for (const Parameter& p : parameters()) {
    if (!values.contains(p.name))
      throw std::runtime_error(file + ": values/" + p.name + " is missing (the program's parameter)");
    read.push_back(parameter_values(p, values.at(p.name), file + ": values/" + p.name));
  }
  for (auto it = values.begin(); it != values.end(); ++it)
    if (std::none_of(parameters().begin(), parameters().end(), [&](const Parameter& p) { return p.name == it.key(); }))
      throw std::runtime_error(file + ": values/" + it.key() + " is not a parameter of this program");
  // Nothing changes unless every value is good.
  for (std::size_t k = 0; k < read.size(); ++k) std::copy(read[k].begin(), read[k].end(), parameters()[k].values);
}

}  // namespace helios_rt

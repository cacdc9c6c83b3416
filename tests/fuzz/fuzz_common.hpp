#pragma once
// What a fuzz target counts as a clean outcome: the tool would exit with its documented code and
// a message written for the user. helios::cli::run_tool maps the helios error types, and
// std::invalid_argument and std::domain_error (the field accessors', the unit tables'), to exit
// codes 2-4 (numerical_error to 1, a solver's breakdown); any other exception reaches the user as a
// raw library message under exit 1 ("[json.exception.type_error.302] ...", "vector::_M_range_check",
// "stod"), which is a finding: the target aborts, so libFuzzer keeps the input.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <typeinfo>

#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"

namespace helios::fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

// A message that is only the name of the library function that threw (std::stod's "stod").
inline bool bare_library_message(const std::string& what) {
  for (const char* name : {"stoi", "stol", "stoll", "stoul", "stoull", "stof", "stod", "stold"})
    if (what == name) return true;
  return false;
}

// Runs `body`; returns true when it completed, false when it threw a clean error; aborts otherwise.
template <class Body>
bool clean_outcome(const char* stage, Body&& body) {
  try {
    body();
    return true;
  } catch (const input_error&) {
  } catch (const usage_error&) {
  } catch (const check_failed&) {
  } catch (const numerical_error&) {
  } catch (const std::invalid_argument& e) {
    if (bare_library_message(e.what())) finding(std::string(stage) + ": std::invalid_argument: " + e.what());
  } catch (const std::domain_error&) {
  } catch (const std::exception& e) {
    finding(std::string(stage) + ": " + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding(std::string(stage) + ": an exception not derived from std::exception");
  }
  return false;
}

// An artifact a tool writes must pass its own schema (write_artifact checks it, and a violation
// there would blame the output for what the input did).
inline void expect_valid(const std::string& kind, const io::json& doc) {
  try {
    io::validate(kind, doc, "output " + kind);
  } catch (const input_error& e) {
    finding(e.what());
  } catch (const std::exception& e) {  // e.g. a string of the artifact that is not UTF-8
    finding("output " + kind + ": " + typeid(e).name() + ": " + e.what());
  }
}

}  // namespace helios::fuzz

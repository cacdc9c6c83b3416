#pragma once
// Files compiled into libhelios by cmake/embed.cmake (schemas, templates, astro headers).
#include <map>
#include <string>

namespace helios::embedded {
const std::map<std::string, std::string>& files();
// Text of an embedded file by its path relative to the source root; throws if unknown.
const std::string& file(const std::string& relative_path);
}  // namespace helios::embedded

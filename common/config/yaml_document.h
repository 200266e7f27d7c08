// YAML text from outside (configuration files, a dataset's sensor.yaml)
// parsed with errors that name its source. yaml-cpp stops at a fixed depth of
// recursion, so input nested deeper than that cannot exhaust the stack; it
// calls that a bad file, and here it is said as what it is.
#pragma once

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <istream>
#include <string>

namespace lineloc {

// Throws std::runtime_error "SOURCE: not valid YAML: ..." on a syntax error or
// on nesting too deep to parse (with its line and column).
YAML::Node loadYamlDocument(std::istream& text, const std::string& source);

}  // namespace lineloc

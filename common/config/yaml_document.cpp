#include "common/config/yaml_document.h"

#include <fmt/format.h>

#include <stdexcept>

namespace lineloc {

YAML::Node loadYamlDocument(std::istream& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& error) {
    throw std::runtime_error(
        fmt::format("{}: not valid YAML: nested too deeply (line {}, column {})", source,
                    error.mark.line + 1, error.mark.column + 1));
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: not valid YAML: {}", source, error.what()));
  }
}

}  // namespace lineloc

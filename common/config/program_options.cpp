#include "common/config/program_options.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <stdexcept>

namespace lineloc {

ProgramOptions::ProgramOptions(const std::string& program, const std::string& description)
    : app_(description, program) {
  app_.add_option("--config", config_path_,
                  "YAML file with any of these options as keys (flags override it)");
  app_.add_flag("--print-config", print_config_,
                "print every option as a documented YAML config file, then exit");
  app_.set_version_flag("--version", fmt::format("{} (lineloc {})", program, LINELOC_VERSION));
  app_.add_option("--log-level", log_level_,
                  "level of the log: trace, debug, info, warn, error, critical or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
}

void ProgramOptions::printConfig() const {
  std::cout << "# " << app_.get_name() << " configuration: " << app_.get_description() << '\n';
  for (const Binding& binding : bindings_) {
    YAML::Emitter value;
    value << YAML::Flow << binding.current();
    std::cout << "\n# " << binding.option->get_description() << '\n'
              << binding.key << ": " << value.c_str() << '\n';
  }
}

std::string ProgramOptions::flagFor(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

void ProgramOptions::throwBadValue(const std::string& file, const std::string& key,
                                   const YAML::Node& node, const std::string& why) {
  throw std::runtime_error(fmt::format("{}:{}: key '{}' has an invalid value: {}", file,
                                       node.Mark().line + 1, key, why));
}

void ProgramOptions::applyConfigFile(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(fmt::format("cannot read config file '{}'", path));
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: not valid YAML: {}", path, error.what()));
  }
  applyConfig(root, path);
}

void ProgramOptions::applyConfig(const YAML::Node& root, const std::string& source) {
  if (root.IsNull()) {
    return;
  }
  if (!root.IsMap()) {
    throw std::runtime_error(fmt::format("{}: expected a map of option keys", source));
  }
  for (const auto& entry : root) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
    const auto binding = std::find_if(bindings_.begin(), bindings_.end(),
                                      [&](const Binding& b) { return b.key == key; });
    if (binding == bindings_.end()) {
      throw std::runtime_error(
          fmt::format("{}:{}: unknown key '{}'", source, entry.first.Mark().line + 1, key));
    }
    binding->apply(entry.second, source);
  }
}

std::optional<int> ProgramOptions::parse(int argc, const char* const* argv) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app_.exit(error);
  }
  spdlog::set_level(spdlog::level::from_str(log_level_));
  try {
    if (!config_path_.empty()) {
      applyConfigFile(config_path_);
    }
  } catch (const std::exception& error) {
    std::cerr << app_.get_name() << ": " << error.what() << '\n';
    return 2;
  }
  if (print_config_) {
    printConfig();
    return 0;
  }
  return std::nullopt;
}

}  // namespace lineloc

#include "common/config/program_options.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "common/config/yaml_document.h"

namespace lineloc {
namespace {

std::string flagFor(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

[[noreturn]] void throwBadValue(const std::string& file, const std::string& key,
                                const YAML::Node& node, const std::string& why) {
  throw std::runtime_error(fmt::format("{}:{}: key '{}' has an invalid value: {}", file,
                                       node.Mark().line + 1, key, why));
}

}  // namespace

struct ProgramOptions::Parsers {
  struct Binding {
    std::string key;
    CLI::Option* option;
    std::function<void(const YAML::Node&, const std::string&)> apply;
    std::function<YAML::Node()> current;
  };

  Parsers(const std::string& program, const std::string& description) : app(description, program) {}

  // The YAML key `key` sets `value` unless the command line gave `option`.
  template <typename T>
  void bind(const std::string& key, CLI::Option* option, T& value) {
    const auto apply = [option, &value, key](const YAML::Node& node, const std::string& file) {
      if (option->count() > 0) {
        return;
      }
      try {
        value = node.as<T>();
      } catch (const YAML::Exception& error) {
        throwBadValue(file, key, node, error.what());
      }
    };
    bindings.push_back({key, option, apply, [&value] { return YAML::Node(value); }});
  }

  void apply(const YAML::Node& root, const std::string& source) {
    if (root.IsNull()) {
      return;
    }
    if (!root.IsMap()) {
      throw std::runtime_error(fmt::format("{}: expected a map of option keys", source));
    }
    for (const auto& entry : root) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
      const auto binding = std::find_if(bindings.begin(), bindings.end(),
                                        [&](const Binding& b) { return b.key == key; });
      if (binding == bindings.end()) {
        throw std::runtime_error(
            fmt::format("{}:{}: unknown key '{}'", source, entry.first.Mark().line + 1, key));
      }
      binding->apply(entry.second, source);
    }
  }

  void printConfig() const {
    std::cout << "# " << app.get_name() << " configuration: " << app.get_description() << '\n';
    for (const Binding& binding : bindings) {
      YAML::Emitter value;
      value << YAML::Flow << binding.current();
      std::cout << "\n# " << binding.option->get_description() << '\n'
                << binding.key << ": " << value.c_str() << '\n';
    }
  }

  CLI::App app;
  std::string config_path;
  bool print_config = false;
  std::string log_level = "info";
  std::vector<Binding> bindings;
};

ProgramOptions::ProgramOptions(const std::string& program, const std::string& description)
    : parsers_(std::make_unique<Parsers>(program, description)) {
  CLI::App& app = parsers_->app;
  app.add_option("--config", parsers_->config_path,
                 "YAML file with any of these options as keys (flags override it)");
  app.add_flag("--print-config", parsers_->print_config,
               "print every option as a documented YAML config file, then exit");
  app.set_version_flag("--version", fmt::format("{} (lineloc {})", program, LINELOC_VERSION));
  app.add_option("--log-level", parsers_->log_level,
                 "level of the log: trace, debug, info, warn, error, critical or off")
      ->capture_default_str()
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
}

ProgramOptions::~ProgramOptions() = default;

template <typename T>
void ProgramOptions::add(const std::string& key, T& value, const std::string& help) {
  parsers_->bind(key, parsers_->app.add_option(flagFor(key), value, help)->capture_default_str(),
                 value);
}

template <typename T>
void ProgramOptions::addFixedSize(const std::string& key, std::vector<T>& value, int count,
                                  const std::string& help) {
  CLI::Option* option = parsers_->app.add_option(flagFor(key), value, help)->capture_default_str();
  parsers_->bind(key, option->expected(count)->allow_extra_args(false), value);
}

void ProgramOptions::addFlag(const std::string& key, bool& value, const std::string& help) {
  parsers_->bind(key, parsers_->app.add_flag(flagFor(key), value, help)->capture_default_str(),
                 value);
}

void ProgramOptions::addPositional(const std::string& name, std::vector<std::string>& values,
                                   const std::string& help, int count, bool required) {
  CLI::Option* option = parsers_->app.add_option(name, values, help);
  if (count >= 0) {
    option->expected(count);
  }
  option->required(required);
}

void ProgramOptions::addPositional(const std::string& name, std::string& value,
                                   const std::string& help, bool required) {
  parsers_->app.add_option(name, value, help)->required(required);
}

void ProgramOptions::applyConfig(const std::string& yaml, const std::string& source) {
  std::istringstream text(yaml);
  parsers_->apply(loadYamlDocument(text, source), source);
}

std::optional<int> ProgramOptions::parse(int argc, const char* const* argv) {
  CLI::App& app = parsers_->app;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  spdlog::set_level(spdlog::level::from_str(parsers_->log_level));
  try {
    if (!parsers_->config_path.empty()) {
      std::ifstream file(parsers_->config_path);
      if (!file) {
        throw std::runtime_error(
            fmt::format("cannot read config file '{}'", parsers_->config_path));
      }
      std::stringstream text;
      text << file.rdbuf();
      applyConfig(text.str(), parsers_->config_path);
    }
  } catch (const std::exception& error) {
    std::cerr << app.get_name() << ": " << error.what() << '\n';
    return 2;
  }
  if (parsers_->print_config) {
    parsers_->printConfig();
    return 0;
  }
  return std::nullopt;
}

#define LINELOC_PROGRAM_OPTION_TYPE(T)                                                    \
  template void ProgramOptions::add<T>(const std::string&, T&, const std::string&);       \
  template void ProgramOptions::add<std::vector<T>>(const std::string&, std::vector<T>&,  \
                                                    const std::string&);                  \
  template void ProgramOptions::addFixedSize<T>(const std::string&, std::vector<T>&, int, \
                                                const std::string&);
LINELOC_PROGRAM_OPTION_TYPE(int)
LINELOC_PROGRAM_OPTION_TYPE(unsigned)
LINELOC_PROGRAM_OPTION_TYPE(int64_t)
LINELOC_PROGRAM_OPTION_TYPE(uint64_t)
LINELOC_PROGRAM_OPTION_TYPE(double)
LINELOC_PROGRAM_OPTION_TYPE(float)
LINELOC_PROGRAM_OPTION_TYPE(std::string)
#undef LINELOC_PROGRAM_OPTION_TYPE
template void ProgramOptions::add<bool>(const std::string&, bool&, const std::string&);

}  // namespace lineloc

// Program options: one YAML file per program, overridden by command-line flags.
//
// Each option is declared once, with its default (the variable's current value)
// and its documentation: YAML key `robot_id` is also flag `--robot-id`. The
// YAML file is named by `--config FILE`; keys it does not know are an error, so
// a typo never silently leaves a default in force. Every program also takes
// `--version` and `--log-level` (trace, debug, info, warn, error, critical,
// off: the level of its log, info by default).
#pragma once

#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lineloc {

class ProgramOptions {
 public:
  ProgramOptions(const std::string& program, const std::string& description);

  // Declares an option. T is anything both CLI11 and yaml-cpp convert
  // (numbers, strings, bool, std::vector of those).
  template <typename T>
  void add(const std::string& key, T& value, const std::string& help) {
    bind(key, app_.add_option(flagFor(key), value, help)->capture_default_str(), value);
  }

  // Declares a vector option that takes exactly `count` values on the command
  // line (`--origin 84900 447600 0`), so it does not swallow the positional
  // arguments after it; the YAML key, or leaving it out, may still leave it empty.
  template <typename T>
  void addFixedSize(const std::string& key, std::vector<T>& value, int count,
                    const std::string& help) {
    CLI::Option* option = app_.add_option(flagFor(key), value, help)->capture_default_str();
    bind(key, option->expected(count)->allow_extra_args(false), value);
  }

  // Declares a boolean that is a bare flag on the command line (`--dry-run`)
  // and a true/false key in the YAML file.
  void addFlag(const std::string& key, bool& value, const std::string& help) {
    bind(key, app_.add_flag(flagFor(key), value, help)->capture_default_str(), value);
  }

  // Parses argv and the config file. Returns an exit code when the program
  // should stop now (after --help or --print-config, or with an error already
  // printed). --print-config writes every key with its documentation and its
  // value after the config file and flags: a complete, commented config file.
  std::optional<int> parse(int argc, const char* const* argv);

  // Applies a parsed YAML map (`source` names it in errors) to the options not
  // given on the command line. Throws std::runtime_error on unknown keys or bad values.
  void applyConfig(const YAML::Node& root, const std::string& source);

  CLI::App& app() { return app_; }

 private:
  struct Binding {
    std::string key;
    CLI::Option* option;
    std::function<void(const YAML::Node&, const std::string&)> apply;
    std::function<YAML::Node()> current;
  };

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
    bindings_.push_back({key, option, apply, [&value] { return YAML::Node(value); }});
  }

  static std::string flagFor(const std::string& key);
  [[noreturn]] static void throwBadValue(const std::string& file, const std::string& key,
                                         const YAML::Node& node, const std::string& why);
  void applyConfigFile(const std::string& path);
  void printConfig() const;

  CLI::App app_;
  std::string config_path_;
  bool print_config_ = false;
  std::string log_level_ = "info";
  std::vector<Binding> bindings_;
};

}  // namespace lineloc

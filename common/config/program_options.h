// Program options: one YAML file per program, overridden by command-line flags.
//
// Each option is declared once, with its default (the variable's current value)
// and its documentation: YAML key `robot_id` is also flag `--robot-id`. The
// YAML file is named by `--config FILE`; keys it does not know are an error, so
// a typo never silently leaves a default in force. Every program also takes
// `--version` and `--log-level` (trace, debug, info, warn, error, critical,
// off: the level of its log, info by default).
//
// The parsers (CLI11, yaml-cpp) stay behind this header: a program's main,
// which only declares its options, does not compile them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lineloc {

class ProgramOptions {
 public:
  ProgramOptions(const std::string& program, const std::string& description);
  ~ProgramOptions();
  ProgramOptions(const ProgramOptions&) = delete;
  ProgramOptions& operator=(const ProgramOptions&) = delete;

  // Declares an option. T is one of the types program_options.cpp
  // instantiates: bool (true/false after the flag), int, unsigned, int64_t,
  // uint64_t, double, float, std::string, and std::vector of each but bool.
  template <typename T>
  void add(const std::string& key, T& value, const std::string& help);

  // Declares a vector option that takes exactly `count` values on the command
  // line (`--site-origin 84900 447600 0`), so it does not swallow the
  // positional arguments after it; the YAML key, or leaving it out, may still
  // leave it empty.
  template <typename T>
  void addFixedSize(const std::string& key, std::vector<T>& value, int count,
                    const std::string& help);

  // Declares a boolean that is a bare flag on the command line (`--dry-run`)
  // and a true/false key in the YAML file.
  void addFlag(const std::string& key, bool& value, const std::string& help);

  // Declares positional arguments, command line only: `count` of them (-1:
  // any number), at least one when `required`.
  void addPositional(const std::string& name, std::vector<std::string>& values,
                     const std::string& help, int count = -1, bool required = false);
  void addPositional(const std::string& name, std::string& value, const std::string& help,
                     bool required);

  // Parses argv and the config file. Returns an exit code when the program
  // should stop now (after --help or --print-config, or with an error already
  // printed). --print-config writes every key with its documentation and its
  // value after the config file and flags: a complete, commented config file.
  std::optional<int> parse(int argc, const char* const* argv);

  // Applies a YAML map (`source` names it in errors) to the options not given
  // on the command line. Throws std::runtime_error on malformed YAML, unknown
  // keys or bad values.
  void applyConfig(const std::string& yaml, const std::string& source);

 private:
  struct Parsers;
  std::unique_ptr<Parsers> parsers_;
};

}  // namespace lineloc

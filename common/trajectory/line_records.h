// Text files of one record per line, '#' comments and blank lines skipped, as
// the TUM trajectory and the fix log are: each line is parsed with its
// "path:line" for error messages.
#pragma once

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace lineloc {

// The whitespace-separated fields of one line.
inline std::vector<std::string> splitFields(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> fields;
  for (std::string field; stream >> field;) {
    fields.push_back(field);
  }
  return fields;
}

// Field `name` as a finite number; throws std::runtime_error naming `where`.
inline double parseFinite(const std::string& text, const char* name, const std::string& where) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw std::runtime_error(fmt::format("{}: {} '{}' is not a finite number", where, name, text));
  }
  return value;
}

// Throws std::runtime_error naming `what` and the path when the file cannot be
// opened; parse errors propagate.
template <typename Record, typename Parse>
std::vector<Record> readLineRecords(const std::string& path, const char* what, Parse parse) {
  std::ifstream stream(path);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open {} '{}'", what, path));
  }
  std::vector<Record> records;
  std::string line;
  for (int line_number = 1; std::getline(stream, line); ++line_number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') {
      continue;
    }
    records.push_back(parse(line, fmt::format("{}:{}", path, line_number)));
  }
  return records;
}

}  // namespace lineloc

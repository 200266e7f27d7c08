// Text files of one record per line, '#' comments and blank lines skipped, as
// the TUM trajectory and the fix log are: each line is parsed with its
// "path:line" for error messages.
#pragma once

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace lineloc {

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

// Checks shared by the tests of the line-per-record logs (TUM, fix log, pose
// log with covariance): a scratch file, a good line with one field replaced,
// and a parse error that names the line and what is wrong.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lineloc::testing {

inline std::string temporaryPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + std::to_string(getpid()))).string();
}

// `line` with its field `index` (0-based) replaced by `value`.
inline std::string withField(const std::string& line, int index, const std::string& value) {
  std::istringstream stream(line);
  std::string replaced;
  int i = 0;
  for (std::string field; stream >> field; ++i) {
    replaced += (i == index ? value : field) + ' ';
  }
  return replaced;
}

// `parse(line, where)` throws std::runtime_error naming `where` and saying `expected`.
template <typename Parse>
void expectParseError(Parse parse, const std::string& line, const std::string& expected) {
  const std::string where = "log.txt:3";
  try {
    parse(line, where);
    ADD_FAILURE() << "accepted: " << line;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(where), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

}  // namespace lineloc::testing

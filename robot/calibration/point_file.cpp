#include "robot/calibration/point_file.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lineloc {

namespace {

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

double parseNumber(std::string_view token, const std::string& source, int line) {
  // from_chars rejects a leading '+', which other tools may write.
  const std::string_view digits = token.front() == '+' ? token.substr(1) : token;
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size()) {
    throw std::runtime_error(
        fmt::format("{}:{}: '{}' is not a number", source, line, std::string(token)));
  }
  if (!std::isfinite(value)) {
    throw std::runtime_error(
        fmt::format("{}:{}: non-finite value '{}'", source, line, std::string(token)));
  }
  return value;
}

}  // namespace

std::vector<Eigen::Vector2d> parsePointPairs(std::string_view text, const std::string& source) {
  std::vector<double> values;
  int line = 1;
  size_t at = 0;
  while (at < text.size()) {
    const char c = text[at];
    if (c == '\n') {
      ++line;
      ++at;
    } else if (isSpace(c)) {
      ++at;
    } else if (c == '#') {
      while (at < text.size() && text[at] != '\n') {
        ++at;
      }
    } else {
      const size_t start = at;
      while (at < text.size() && !isSpace(text[at]) && text[at] != '#') {
        ++at;
      }
      values.push_back(parseNumber(text.substr(start, at - start), source, line));
    }
  }
  if (values.empty()) {
    throw std::runtime_error(fmt::format("{}: no coordinates", source));
  }
  if (values.size() % 2 != 0) {
    throw std::runtime_error(
        fmt::format("{}: odd number of coordinates ({}): expected pairs", source, values.size()));
  }
  std::vector<Eigen::Vector2d> points;
  points.reserve(values.size() / 2);
  for (size_t i = 0; i < values.size(); i += 2) {
    points.emplace_back(values[i], values[i + 1]);
  }
  return points;
}

std::vector<Eigen::Vector2d> readPointFile(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot read point file '{}'", path));
  }
  std::ostringstream text;
  text << stream.rdbuf();
  return parsePointPairs(text.str(), path);
}

}  // namespace lineloc

#include "sim/world/waypoint_file.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lineloc {
namespace {

bool isSeparator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

// Parses the numbers of one line into `values`; false on anything else.
bool parseNumbers(std::string_view line, std::vector<double>& values) {
  values.clear();
  size_t at = 0;
  while (at < line.size()) {
    if (isSeparator(line[at])) {
      ++at;
      continue;
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(line.data() + at, line.data() + line.size(), value);
    if (error != std::errc() || (end != line.data() + line.size() && !isSeparator(*end))) {
      return false;
    }
    values.push_back(value);
    at = static_cast<size_t>(end - line.data());
  }
  return true;
}

}  // namespace

std::vector<Eigen::Vector2d> parseWaypoints(std::string_view text, const std::string& source) {
  std::vector<Eigen::Vector2d> waypoints;
  std::vector<double> values;
  int line_number = 0;
  while (!text.empty()) {
    const size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') {
      continue;
    }
    if (!parseNumbers(line, values) || values.size() != 2) {
      throw std::runtime_error(
          fmt::format("{}:{}: expected two numbers 'x y' (metres)", source, line_number));
    }
    const Eigen::Vector2d point(values[0], values[1]);
    if (!point.allFinite()) {
      throw std::runtime_error(fmt::format("{}:{}: non-finite coordinate", source, line_number));
    }
    if (!waypoints.empty() && waypoints.back() == point) {
      throw std::runtime_error(
          fmt::format("{}:{}: repeats the previous waypoint", source, line_number));
    }
    waypoints.push_back(point);
  }
  if (waypoints.size() < 2) {
    throw std::runtime_error(fmt::format("{}: a route needs at least two waypoints, found {}",
                                         source, waypoints.size()));
  }
  return waypoints;
}

std::vector<Eigen::Vector2d> readWaypointFile(const std::string& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open waypoint file '{}'", path));
  }
  std::ostringstream text;
  text << stream.rdbuf();
  return parseWaypoints(text.str(), path);
}

}  // namespace lineloc

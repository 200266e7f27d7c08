// Waypoint files: the route a simulated robot drives, one "x y" pair per line
// (world frame after the site origin, metres; separated by spaces, tabs or a
// comma). Lines starting with '#' and blank lines are ignored.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace lineloc {

// Throws std::runtime_error naming `source` and the line of the first
// malformed entry (not two numbers, non-finite, or a repeated point), or when
// fewer than two waypoints remain.
std::vector<Eigen::Vector2d> parseWaypoints(std::string_view text, const std::string& source);

// Reads and parses a file; throws std::runtime_error naming it when unreadable.
std::vector<Eigen::Vector2d> readWaypointFile(const std::string& path);

}  // namespace lineloc

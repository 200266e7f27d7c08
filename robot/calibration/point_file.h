// Point correspondence files of lineloc-calibrate --points: a flat stream of
// whitespace-separated coordinate pairs (X Y for the model, u v for a view),
// any number of pairs per line, so files exported by other tools are read as
// they are. '#' starts a comment to the end of the line.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace lineloc {

// Throws std::runtime_error naming `source` and the line for a token that is
// not a number, a non-finite value, an odd number of values or no values.
std::vector<Eigen::Vector2d> parsePointPairs(std::string_view text, const std::string& source);

// Reads and parses a file; throws std::runtime_error naming it when unreadable.
std::vector<Eigen::Vector2d> readPointFile(const std::string& path);

}  // namespace lineloc

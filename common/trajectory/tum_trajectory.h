// TUM trajectory files: one pose per line, "t tx ty tz qx qy qz qw", t in
// seconds, as read by evo and the TUM RGB-D benchmark tools. Lines starting
// with '#' are comments.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace lineloc {

struct StampedPose {
  int64_t stamp_ns = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

// Appends poses to a TUM file, flushing each line so a killed process leaves
// every pose written so far.
class TumWriter {
 public:
  // Throws std::runtime_error naming the path when it cannot be opened.
  explicit TumWriter(const std::string& path);
  void write(const StampedPose& stamped);

 private:
  std::string path_;
  std::ofstream stream_;
};

// Formats one TUM line (without newline): nanosecond-exact time, 9 decimals.
std::string formatTumLine(const StampedPose& stamped);

// Reads a whole TUM file. Throws std::runtime_error naming the file and line of
// the first malformed entry (wrong field count, non-numeric, non-finite, or a
// quaternion far from unit norm).
std::vector<StampedPose> readTumFile(const std::string& path);

// Parses one TUM line; `where` names it in error messages.
StampedPose parseTumLine(const std::string& line, const std::string& where);

// Parses the first eight of `fields` (at least eight) as a TUM line: the pose
// that starts the lines of the logs that extend it (fix_log.h,
// pose_covariance_log.h).
StampedPose parseTumFields(const std::vector<std::string>& fields, const std::string& where);

}  // namespace lineloc

// A trajectory with the covariance of each pose: a TUM pose line
// (tum_trajectory.h) followed by the pose's 6 x 6 covariance (upper triangle,
// row-major, in the error convention of common/geometry/pose.h):
//
//   t tx ty tz qx qy qz qw c00 c01 .. c05 c11 .. c55
//
// The robot logs in it the camera pose its state reports each time it
// publishes one (lineloc-robot --state-log-out), so that a run can be checked
// for a robot sure of a wrong pose (lineloc-eval --state-log). The robot's fix
// log (fix_log.h) ends with the same 21 covariance fields. Lines starting with
// '#' are comments.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "common/geometry/pose.h"

namespace lineloc {

struct StampedPoseWithCovariance {
  int64_t stamp_ns = 0;
  PoseWithCovariance pose;
};

// Appends poses, flushing each line so a killed process leaves every pose so far.
class PoseCovarianceLogWriter {
 public:
  // Throws std::runtime_error naming the path when it cannot be opened.
  explicit PoseCovarianceLogWriter(const std::string& path);
  void write(const StampedPoseWithCovariance& stamped);

 private:
  std::ofstream stream_;
};

std::string formatPoseCovarianceLine(const StampedPoseWithCovariance& stamped);

// Parses one line; `where` names it in error messages. Throws
// std::runtime_error on a wrong field count, a malformed pose (as
// parseTumLine) or a covariance that is not finite and positive definite.
StampedPoseWithCovariance parsePoseCovarianceLine(const std::string& line,
                                                  const std::string& where);

// Reads a whole log; errors name the file and line.
std::vector<StampedPoseWithCovariance> readPoseCovarianceLog(const std::string& path);

// The 21 fields of a covariance's upper triangle, each after a space.
std::string formatCovarianceFields(const Matrix6d& covariance);

// The covariance in fields[first, first + 21); throws std::runtime_error
// naming `where` when an entry is not a finite number or the matrix is not
// positive definite.
Matrix6d parseCovarianceFields(const std::vector<std::string>& fields, size_t first,
                               const std::string& where);

}  // namespace lineloc

// The robot's log of the backbone's answers: one line per PoseFix received,
// a TUM pose line (tum_trajectory.h) followed by the answer's status, its
// counts and the pose's 6 x 6 covariance (upper triangle, row-major, in the
// error convention of common/geometry/pose.h):
//
//   t tx ty tz qx qy qz qw status inliers model_lines residual_rms_px latency_ms
//     front_end_ms to_backbone_ms backbone_ms back_ms c00 .. c55
//
// latency_ms runs from the frame's exposure to the robot receiving the answer,
// so t + latency_ms is when the robot's estimate first includes the fix. The
// four legs after it say where that time went: the robot's front end (exposure
// to LineSet sent), DDS to the backbone with the LineSet's wait there, the
// backbone's answer, and DDS back. The two DDS legs are timed across the two
// hosts' clocks, so they are only as good as their synchronisation, and may
// be negative without it.
//
// The first eight fields alone are a TUM trajectory. With the covariance, a run
// can be checked for precise wrong poses against ground truth (lineloc-eval
// --fix-log). Lines starting with '#' are comments.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "common/geometry/pose.h"

namespace lineloc {

struct LoggedFix {
  int64_t stamp_ns = 0;
  PoseWithCovariance T_world_camera;
  std::string status;  // the PoseFix status as toString() names it: "ok", "too_few_matches", ...
  uint32_t inliers = 0;
  uint32_t model_lines = 0;
  double residual_rms_px = 0.0;
  double latency_ms = 0.0;
  double front_end_ms = 0.0;
  double to_backbone_ms = 0.0;
  double backbone_ms = 0.0;
  double back_ms = 0.0;
};

// Appends fixes, flushing each line so a killed process leaves every fix so far.
class FixLogWriter {
 public:
  // Throws std::runtime_error naming the path when it cannot be opened.
  explicit FixLogWriter(const std::string& path);
  void write(const LoggedFix& fix);

 private:
  std::ofstream stream_;
};

std::string formatFixLogLine(const LoggedFix& fix);

// Parses one line; `where` names it in error messages. Throws
// std::runtime_error on a malformed pose (as parseTumLine), a status that is
// not lower-case letters and underscores, counts that are not unsigned
// integers, a residual, latency, front end or backbone time that is negative
// or not finite, a DDS leg that is not finite, or a covariance that is not
// finite and positive definite.
LoggedFix parseFixLogLine(const std::string& line, const std::string& where);

// Reads a whole log; errors name the file and line.
std::vector<LoggedFix> readFixLog(const std::string& path);

}  // namespace lineloc

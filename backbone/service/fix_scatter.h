// The scatter of a robot's recent answers as a floor under each new answer's
// covariance: covariance matching (Mehra, "On the identification of variances
// and adaptive Kalman filtering", IEEE TAC 15(2), 1970; Mohamed & Schwarz,
// "Adaptive Kalman filtering for INS/GPS", J. Geodesy 73, 1999, eq. 20),
// with the differences between answers of one pose as the residuals.
//
// A view whose lines fit two alignments a few centimetres and a few tenths
// of a degree apart can flip between them from frame to frame, each answer
// reporting the covariance of its own basin, and so one answer in a few lies
// beyond its covariance.
//
// Each recent answer A_i of the robot is moved to the new answer's frame by
// the robot's own motion (predicted_motion.h), A_i O_i^-1 O, and taken as
// d_i = poseError(answer, A_i O_i^-1 O); with the new answer's own d = 0,
// their sample covariance S = (1/(n-1)) sum (d_i - mean)(d_i - mean)^T is
// Sigma when the answers are as precise as they say. Where S exceeds Sigma,
// the answer's covariance is raised to it, direction by direction
// (coveringCovariance, common/geometry/pose.h). An answer of
// either basin then covers the other one in proportion to how often the
// answers fall there. The answers' errors are correlated from frame to frame
// (one view, one model), so S is a lower bound on their spread, never
// grounds to shrink Sigma.
#pragma once

#include <cstdint>
#include <deque>

#include "backbone/service/predicted_motion.h"
#include "common/geometry/pose.h"

namespace lineloc {

struct FixScatterOptions {
  // Answers this recent count (s): dead reckoning over a second errs by
  // millimetres, a fix by centimetres.
  double window_s = 1.0;
  // No floor from fewer answers than this.
  int min_answers = 5;
};

// One robot's recent answers. Not thread-safe: one per robot, used from the
// thread that answers it.
class FixScatter {
 public:
  explicit FixScatter(const FixScatterOptions& options = {});

  // `answer` at `stamp_ns` and `odometry` with its covariance raised to the
  // scatter of the recent answers and it; then remembered.
  PoseWithCovariance floorAndAdd(int64_t stamp_ns, const OdometryPose& odometry,
                                 const PoseWithCovariance& answer);

 private:
  struct RecentAnswer {
    int64_t stamp_ns;
    OdometryPose odometry;
    Eigen::Isometry3d T_world_camera;
  };
  void forgetOlderThan(int64_t stamp_ns, uint64_t epoch);

  FixScatterOptions options_;
  std::deque<RecentAnswer> recent_;
};

}  // namespace lineloc

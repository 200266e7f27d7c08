// A robot's own motion, read from the predicted poses its LineSets carry: the
// odometry a search's pose is moved by to later frames (line_set_handler.h).
//
// Between two frames the prediction moves by the robot's motion plus whatever
// the robot's filter corrected in between: a DGPS fix right after the start
// moves it by decimetres to metres while the robot stands still. A Kalman
// update moves the mean by d = K (z - h) with E[d d^T] = K S K^T = P- - P+, the
// drop of the covariance it causes. So the increment P_{k-1}^-1 P_k is taken
// as motion when the trace of the position covariance dropped by at most
// max_correction_m^2 and that of the rotation covariance by at most
// max_correction_rad^2 (the compass's and standstill updates wobble them by
// 1e-5 m^2: millimetres); otherwise the previous increment's velocity is
// carried over the frame instead, xi_k = (dt_k / dt_{k-1}) xi_{k-1} with xi
// the increment's translation and rotation vector: over 33 ms a constant
// velocity errs by a millimetre, a DGPS correction by a metre.
//
// The chain T_odom_k = T_odom_{k-1} Delta_k starts at the first prediction;
// only its increments mean anything. A frame older than the last one (the
// robot restarted, or its frames came out of order) starts a new chain: its
// epoch counts up, and poses of two epochs are not to be compared.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>

#include "common/geometry/pose.h"

namespace lineloc {

struct PredictedMotionOptions {
  double max_correction_m = 0.05;
  double max_correction_rad = 0.1 * M_PI / 180.0;
};

struct OdometryPose {
  Eigen::Isometry3d T_odom_camera = Eigen::Isometry3d::Identity();
  uint64_t epoch = 0;
};

// The camera's motion from odometry pose `from` to `to`, O_from^-1 O_to: a
// pose A found at `from` is A O_from^-1 O_to at `to` (both of one epoch).
inline Eigen::Isometry3d motionBetween(const OdometryPose& from, const OdometryPose& to) {
  return from.T_odom_camera.inverse() * to.T_odom_camera;
}

class PredictedMotion {
 public:
  explicit PredictedMotion(const PredictedMotionOptions& options = {});

  // The odometry pose of the frame at `stamp_ns` whose predicted pose is `predicted`.
  OdometryPose add(int64_t stamp_ns, const PoseWithCovariance& predicted);

 private:
  bool correctedSinceLast(const PoseWithCovariance& predicted) const;

  PredictedMotionOptions options_;
  bool started_ = false;
  int64_t last_stamp_ns_ = 0;
  PoseWithCovariance last_predicted_;
  // The last increment's translation and rotation vector per second.
  Eigen::Vector3d velocity_m_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_rad_s_ = Eigen::Vector3d::Zero();
  OdometryPose odometry_;
};

}  // namespace lineloc

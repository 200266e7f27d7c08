#include "backbone/service/predicted_motion.h"

namespace lineloc {

PredictedMotion::PredictedMotion(const PredictedMotionOptions& options) : options_(options) {}

bool PredictedMotion::correctedSinceLast(const PoseWithCovariance& predicted) const {
  const auto square = [](double x) { return x * x; };
  const double position_drop_m2 = last_predicted_.covariance.topLeftCorner<3, 3>().trace() -
                                  predicted.covariance.topLeftCorner<3, 3>().trace();
  const double rotation_drop_rad2 = last_predicted_.covariance.bottomRightCorner<3, 3>().trace() -
                                    predicted.covariance.bottomRightCorner<3, 3>().trace();
  return position_drop_m2 > square(options_.max_correction_m) ||
         rotation_drop_rad2 > square(options_.max_correction_rad);
}

OdometryPose PredictedMotion::add(int64_t stamp_ns, const PoseWithCovariance& predicted) {
  if (!started_ || stamp_ns <= last_stamp_ns_) {
    odometry_.epoch += started_ ? 1 : 0;
    odometry_.T_odom_camera = predicted.pose;
    velocity_m_s_.setZero();
    angular_velocity_rad_s_.setZero();
  } else {
    const double dt_s = (stamp_ns - last_stamp_ns_) * 1e-9;
    if (!correctedSinceLast(predicted)) {
      const Eigen::Isometry3d increment = last_predicted_.pose.inverse() * predicted.pose;
      const Eigen::AngleAxisd rotation(increment.linear());
      velocity_m_s_ = increment.translation() / dt_s;
      angular_velocity_rad_s_ = rotation.angle() * rotation.axis() / dt_s;
    }
    Eigen::Isometry3d increment = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d rotation_vector = angular_velocity_rad_s_ * dt_s;
    if (rotation_vector.norm() > 0.0) {
      increment.linear() = Eigen::AngleAxisd(rotation_vector.norm(), rotation_vector.normalized())
                               .toRotationMatrix();
    }
    increment.translation() = velocity_m_s_ * dt_s;
    odometry_.T_odom_camera = odometry_.T_odom_camera * increment;
  }
  started_ = true;
  last_stamp_ns_ = stamp_ns;
  last_predicted_ = predicted;
  return odometry_;
}

}  // namespace lineloc

#include "robot/inertial/in_motion_alignment.h"

#include <cmath>
#include <functional>

#include "robot/inertial/measurement_models.h"
#include "robot/inertial/robust_heading.h"
#include "robot/inertial/strapdown.h"

namespace lineloc {
namespace {

constexpr double kNsToS = 1e-9;
constexpr double kMagnitudeGateSigmas = 5.0;
// How much a ground robot's vertical speed changes over the interval (a road
// whose grade changes), which u leaves out.
constexpr double kVerticalVelocityChangeSigma_mps = 0.1;

}  // namespace

std::optional<InMotionAttitude> alignInMotion(const std::vector<ImuSample>& imu,
                                              int64_t from_stamp_ns,
                                              const Eigen::Vector2d& v_from_mps,
                                              int64_t to_stamp_ns, const Eigen::Vector2d& v_to_mps,
                                              const std::vector<TimedYaw>& compass_yaws,
                                              const InMotionAlignmentNoise& noise) {
  const std::optional<std::vector<ImuSample>> samples =
      imuOver(imu.begin(), imu.end(), from_stamp_ns, to_stamp_ns, std::identity{});
  if (!samples) {
    return std::nullopt;
  }
  // Integrated without gravity and biases from q = I, v = 0 at t1, the state
  // holds R_b1_b in q and dv_f in v.
  const Strapdown integrator(ImuNoiseDensities{}, Eigen::Vector3d::Zero());
  NavigationState b1;
  b1.stamp_ns = from_stamp_ns;
  std::vector<double> yaws_at_t1_rad;
  auto next_yaw = compass_yaws.begin();
  // The readings up to `stamp_ns`, each turned back to t1 by the body's turn
  // so far (within one IMU sample of its own time).
  const auto takeYawsUntil = [&](int64_t stamp_ns) {
    for (; next_yaw != compass_yaws.end() && next_yaw->stamp_ns <= stamp_ns; ++next_yaw) {
      if (next_yaw->stamp_ns >= from_stamp_ns) {
        yaws_at_t1_rad.push_back(wrapAngle(next_yaw->yaw_rad - yawOf(b1.q_world_body)));
      }
    }
  };
  for (size_t k = 1; k < samples->size(); ++k) {
    takeYawsUntil((*samples)[k - 1].stamp_ns);
    integrator.propagate((*samples)[k - 1], (*samples)[k], b1);
  }
  takeYawsUntil(to_stamp_ns);
  if (yaws_at_t1_rad.empty()) {
    return std::nullopt;
  }

  const double dt = static_cast<double>(to_stamp_ns - from_stamp_ns) * kNsToS;
  const Eigen::Vector3d& dv_force = b1.v_world_body;
  const Eigen::Vector2d dv_ground = v_to_mps - v_from_mps;
  const Eigen::Vector3d u(dv_ground.x(), dv_ground.y(), noise.gravity_mps2 * dt);
  const double magnitude_sigma = std::sqrt(std::pow(noise.accel_bias_sigma_mps2 * dt, 2) +
                                           2.0 * std::pow(noise.velocity_sigma_mps, 2) +
                                           std::pow(kVerticalVelocityChangeSigma_mps, 2));
  if (std::abs(dv_force.norm() - u.norm()) > kMagnitudeGateSigmas * magnitude_sigma) {
    return std::nullopt;
  }
  const double yaw_t1_rad = robustCircularMean(yaws_at_t1_rad, noise.compass_gate_rad).heading_rad;
  const Eigen::AngleAxisd heading(yaw_t1_rad, Eigen::Vector3d::UnitZ());
  const Eigen::Quaterniond tilt =
      Eigen::Quaterniond::FromTwoVectors(dv_force, heading.inverse() * u);
  InMotionAttitude attitude;
  attitude.stamp_ns = to_stamp_ns;
  attitude.q_world_body = (heading * tilt * b1.q_world_body).normalized();
  attitude.tilt_sigma_rad =
      std::sqrt(2.0 * std::pow(noise.velocity_sigma_mps / (noise.gravity_mps2 * dt), 2) +
                std::pow(noise.accel_bias_sigma_mps2 / noise.gravity_mps2, 2) +
                std::pow(noise.gyro_bias_sigma_radps * dt, 2));
  return attitude;
}

}  // namespace lineloc

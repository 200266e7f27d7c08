// Coarse alignment of a strapdown IMU on a moving vehicle by velocity
// matching (Groves, "Principles of GNSS, Inertial, and Multisensor Integrated
// Navigation Systems", 2nd ed., 2013, §5.6: initialisation and alignment).
// A robot that never stood still since power-on (started while driving, or
// its software restarted mid-drive) has no standstill to level from; the
// receiver's Doppler velocity at two epochs t1 < t2 gives the acceleration
// the accelerometers felt on top of gravity instead:
//
//   v(t2) - v(t1) = R_world_b1 dv_f + g_world (t2 - t1),
//   dv_f = integral over [t1, t2] of R_b1_b(t) f_b(t) dt,
//
// with R_b1_b the body's rotation since t1 from the gyros and f_b the
// specific force. The world side is u = [dv_x, dv_y, g (t2 - t1)] (the
// receiver's horizontal velocity; a ground robot's vertical velocity does
// not change over a second), so R_world_b1 turns dv_f onto u: that fixes
// roll and pitch, and the compass fixes the rotation about u. Its heading
// is the robust mean (robust_heading.h) of the compass readings within
// [t1, t2], each moved back to t1 by the gyros' turn since.
//
// Tilt standard deviation: the velocities' noise across u, sqrt(2) sigma_v
// / (g dt), with the accelerometer bias's b_a / g and the gyro bias's drift
// over the interval, sigma_bg dt. Over dt = 1 s at 0.1 m/s per velocity the
// first term is 0.8 degrees and the three together 0.9, where standing still
// gives b_a / g = 0.3 degrees.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "robot/inertial/imu_sample.h"

namespace lineloc {

struct InMotionAlignmentNoise {
  double gravity_mps2 = 9.80665;
  double velocity_sigma_mps = 0.1;  // per horizontal axis, per epoch
  double accel_bias_sigma_mps2 = 0.05;
  double gyro_bias_sigma_radps = 0.0035;
  double compass_gate_rad = 0.1;  // robustCircularMean's gate
};

// A world yaw (anticlockwise from the site's x axis) measured at a time.
struct TimedYaw {
  int64_t stamp_ns = 0;
  double yaw_rad = 0.0;
};

struct InMotionAttitude {
  int64_t stamp_ns = 0;  // t2
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
  double tilt_sigma_rad = 0.0;  // about each horizontal world axis
};

// The attitude at `to_stamp_ns` from the body-frame IMU samples `imu`, which
// must cover [from_stamp_ns, to_stamp_ns] (time-ordered), the horizontal
// velocities at both ends and the yaws `compass_yaws` measured between them.
// nullopt when the samples do not cover the interval, no yaw lies in it, or
// |dv_f| and |u| differ by more than five standard deviations of their
// noise (a wrong velocity, or a vehicle whose vertical speed changed).
std::optional<InMotionAttitude> alignInMotion(const std::vector<ImuSample>& imu,
                                              int64_t from_stamp_ns,
                                              const Eigen::Vector2d& v_from_mps,
                                              int64_t to_stamp_ns, const Eigen::Vector2d& v_to_mps,
                                              const std::vector<TimedYaw>& compass_yaws,
                                              const InMotionAlignmentNoise& noise);

}  // namespace lineloc

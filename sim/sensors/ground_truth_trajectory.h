// A smooth ground-truth trajectory of a ground robot, random per seed: it
// stands still for a while (so the IMU can be aligned), then drives straight
// legs at 0.5-2 m/s, turns, and stops. Speed v(t) and yaw rate w(t) are sums
// of quintic smoothstep ramps s(u) = 6u^5 - 15u^4 + 10u^3 (continuous
// acceleration and jerk), so the yaw has a closed form through
// S(u) = integral of s = u^6 - 3u^5 + 5u^4/2. The planar position
// integral of v (cos psi, sin psi) is tabulated with 5-point Gauss-Legendre
// quadrature on 10 ms knots (error far below 1e-12 m). Roll, pitch and height
// follow small sinusoids, as on an uneven pavement.
//
// Everything an IMU would sense is analytic: the world acceleration
// a = (v' cos psi - v psi' sin psi, v' sin psi + v psi' cos psi, z''), the
// body rates of the Z-Y-X Euler angles w_b = E(roll, pitch) [roll', pitch', psi']
// and the specific force f_b = R^T (a - g).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace lineloc::sim {

struct TrajectoryConfig {
  uint64_t seed = 1;
  int64_t start_stamp_ns = 1'700'000'000'000'000'000;
  double duration_s = 300.0;
  double initial_still_s = 5.0;
  double min_speed_mps = 0.5;
  double max_speed_mps = 2.0;
  double max_accel_mps2 = 0.5;
  double max_lateral_accel_mps2 = 0.4;
  double max_yaw_rate_radps = 0.5;
  double stop_probability = 0.15;
  double turn_probability = 0.4;
  double min_leg_s = 4.0;
  double max_leg_s = 15.0;
  double ramp_s = 2.0;
  double tilt_amplitude_rad = 0.02;
  double height_amplitude_m = 0.3;
  Eigen::Vector3d start_position_m = Eigen::Vector3d::Zero();
  double start_yaw_rad = 0.0;
  double gravity_mps2 = 9.80665;
};

struct TruthSample {
  int64_t stamp_ns = 0;
  Eigen::Vector3d p_world_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_world_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_world_body = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
  Eigen::Vector3d gyro_body_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_body_mps2 = Eigen::Vector3d::Zero();
};

// What the sensor synthesisers need of a ground-truth trajectory: the full
// kinematic state at any time. Implemented by GroundTruthTrajectory (a random
// drive) and by the simulator's street-following RouteTrajectory.
class TruthTrajectory {
 public:
  virtual ~TruthTrajectory() = default;
  // The state at `stamp_ns`, clamped to [start, end].
  virtual TruthSample at(int64_t stamp_ns) const = 0;
  virtual int64_t startStamp_ns() const = 0;
  virtual int64_t endStamp_ns() const = 0;
};

class GroundTruthTrajectory : public TruthTrajectory {
 public:
  explicit GroundTruthTrajectory(const TrajectoryConfig& config);

  // The state at `stamp_ns`, clamped to [start, end].
  TruthSample at(int64_t stamp_ns) const override;

  int64_t startStamp_ns() const override { return config_.start_stamp_ns; }
  int64_t endStamp_ns() const override;
  const TrajectoryConfig& config() const { return config_; }

 private:
  struct Ramp {
    double start_s;
    double duration_s;
    double change;
  };
  struct Profile {
    double initial = 0.0;
    std::vector<Ramp> ramps;
    double value(double t) const;
    double rate(double t) const;
    double second(double t) const;
    double integral(double t) const;
  };
  struct Wave {
    double amplitude;
    double angular_frequency;
    double phase;
  };

  void planLegs();
  Eigen::Vector2d planarVelocity(double t) const;
  Eigen::Vector2d planarPosition(double t) const;

  TrajectoryConfig config_;
  Profile speed_;
  Profile yaw_rate_;
  Wave roll_{};
  Wave pitch_{};
  Wave height_{};
  std::vector<Eigen::Vector2d> knots_;
};

}  // namespace lineloc::sim

#include "robot/inertial/in_motion_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "robot/inertial/measurement_models.h"
#include "robot/inertial/navigation_state.h"
#include "simulated_drive.h"

namespace lineloc {
namespace {

using testing::dgpsWithoutOutages;
using testing::toImuSample;

constexpr double kDegToRad = M_PI / 180.0;

// A simulated drive's IMU, DGPS velocities (0.05 m/s per axis, the
// simulator's receiver) and compass (2 degrees, no disturbance), and the
// interval between two DGPS epochs, while driving, over which the robot's
// velocity changed most (braking, pulling away, turning).
struct DriveInterval {
  explicit DriveInterval(uint64_t seed)
      : trajectory([&] {
          sim::TrajectoryConfig config;
          config.seed = seed;
          config.duration_s = 40.0;
          config.initial_still_s = 2.0;
          // A car in town: up to 10 m/s, braking and pulling away at 2 m/s^2.
          config.max_speed_mps = 10.0;
          config.max_accel_mps2 = 2.0;
          config.max_lateral_accel_mps2 = 2.0;
          return config;
        }()),
        gps(sim::synthesiseGps(trajectory, dgpsWithoutOutages(), seed)) {
    for (const sim::SimImuSample& sample : sim::synthesiseImu(trajectory, sim::ImuModel{}, seed)) {
      imu.push_back(toImuSample(sample));
    }
    sim::CompassModel compass_model;
    compass_model.disturbance_rate_hz = 0.0;
    for (const sim::SimCompassReading& reading :
         sim::synthesiseCompass(trajectory, compass_model, 0.0, seed)) {
      yaws.push_back({reading.stamp_ns, wrapAngle(M_PI_2 - reading.magnetic_heading_rad)});
    }
    size_t from_epoch = 3;
    for (size_t epoch = from_epoch; epoch + 1 < gps.size(); ++epoch) {
      from_epoch = speedChange(epoch) > speedChange(from_epoch) ? epoch : from_epoch;
    }
    from = gps[from_epoch];
    to = gps[from_epoch + 1];
  }

  double speedChange(size_t epoch) const {
    return (gps[epoch + 1].true_v_world_antenna_mps - gps[epoch].true_v_world_antenna_mps).norm();
  }

  std::optional<InMotionAttitude> align(const InMotionAlignmentNoise& noise = {}) const {
    return alignInMotion(imu, from.stamp_ns, from.v_world_antenna_mps, to.stamp_ns,
                         to.v_world_antenna_mps, yaws, noise);
  }

  // The attitude error of `q_world_body` at the interval's end, about the
  // world axes (left perturbation, navigation_state.h).
  Eigen::Vector3d attitudeError(const Eigen::Quaterniond& q_world_body) const {
    return logSO3(trajectory.at(to.stamp_ns).q_world_body * q_world_body.conjugate());
  }

  sim::GroundTruthTrajectory trajectory;
  std::vector<sim::SimGpsFix> gps;
  std::vector<ImuSample> imu;
  std::vector<TimedYaw> yaws;
  sim::SimGpsFix from;
  sim::SimGpsFix to;
};

// Twenty drives, each aligned over its second of hardest acceleration: roll
// and pitch within three of the reported tilt sigmas, the heading within
// three of one compass reading's sigma (the robust mean of about ten).
// Levelling from the accelerometers alone, as if standing, would put the tilt
// the robot's acceleration over g off (5-13 degrees here, against errors of
// 0.0-1.1 degrees): beyond the same bound on most of these drives, so the
// check tells velocity matching from no correction at all.
TEST(InMotionAlignment, TiltAndHeadingWithinTheirSigmaWhileDriving) {
  int accelerating = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const DriveInterval drive(seed);
    const std::optional<InMotionAttitude> attitude = drive.align();
    ASSERT_TRUE(attitude) << "seed " << seed;
    EXPECT_EQ(attitude->stamp_ns, drive.to.stamp_ns);
    const Eigen::Vector3d error = drive.attitudeError(attitude->q_world_body);
    const double bound = 3.0 * attitude->tilt_sigma_rad;
    EXPECT_LT(std::abs(error.x()), bound) << "seed " << seed;
    EXPECT_LT(std::abs(error.y()), bound) << "seed " << seed;
    EXPECT_LT(std::abs(error.z()), 3.0 * 2.0 * kDegToRad) << "seed " << seed;
    EXPECT_LT(attitude->tilt_sigma_rad, 1.0 * kDegToRad);
    const double dt_s = static_cast<double>(drive.to.stamp_ns - drive.from.stamp_ns) * 1e-9;
    const double acceleration_mps2 =
        (drive.to.true_v_world_antenna_mps - drive.from.true_v_world_antenna_mps).norm() / dt_s;
    accelerating += acceleration_mps2 / 9.81 > bound;
  }
  EXPECT_GE(accelerating, 15);
}

// An IMU that reports its specific force in g, not m/s^2, cannot be matched
// with the velocities: |dv_f| is a tenth of |u|.
TEST(InMotionAlignment, RefusesAnAccelerometerInTheWrongUnit) {
  DriveInterval drive(3);
  for (ImuSample& sample : drive.imu) {
    sample.accel_mps2 /= 9.80665;
  }
  EXPECT_FALSE(drive.align());
}

TEST(InMotionAlignment, NeedsTheIntervalCoveredAndACompassReadingInIt) {
  const DriveInterval drive(4);
  ASSERT_TRUE(drive.align());
  DriveInterval without_compass = drive;
  without_compass.yaws.clear();
  EXPECT_FALSE(without_compass.align());
  DriveInterval short_imu = drive;
  std::erase_if(short_imu.imu, [&](const ImuSample& sample) {
    return sample.stamp_ns > drive.to.stamp_ns - 100'000'000;
  });
  EXPECT_FALSE(short_imu.align());
  EXPECT_FALSE(alignInMotion(drive.imu, drive.to.stamp_ns, drive.to.v_world_antenna_mps,
                             drive.from.stamp_ns, drive.from.v_world_antenna_mps, drive.yaws, {}));
}

}  // namespace
}  // namespace lineloc

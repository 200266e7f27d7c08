// The robot's sensors: each from its config when given, else from a Kalibr
// camchain, else from the dataset's sensor.yaml files, else the navigator's
// defaults; a setup that is not whole or not valid is an error naming the
// option.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "common/geometry/pose.h"
#include "robot/agent/sensor_setup.h"

namespace lineloc {
namespace {

// A dataset's IMU four times noisier than the default, its camera 1.2 m up.
SensorStreams datasetStreams() {
  SensorStreams streams;
  const ImuNoiseDensities defaults;
  streams.imu_noise = ImuNoiseDensities{4 * defaults.gyro_noise_radps_per_sqrt_hz,
                                        4 * defaults.accel_noise_mps2_per_sqrt_hz,
                                        4 * defaults.gyro_bias_random_walk_radps2_per_sqrt_hz,
                                        4 * defaults.accel_bias_random_walk_mps3_per_sqrt_hz};
  Eigen::Isometry3d T_body_camera = InertialNavigatorConfig::defaultBodyCamera();
  T_body_camera.translation() = Eigen::Vector3d(0.0, 0.0, 1.2);
  streams.T_body_camera = T_body_camera;
  return streams;
}

// A camera 0.3 m ahead of the body origin, looking forward.
std::vector<double> cameraAhead() {
  Eigen::Isometry3d T_body_camera = InertialNavigatorConfig::defaultBodyCamera();
  T_body_camera.translation() = Eigen::Vector3d(0.3, 0.0, 0.0);
  std::vector<double> entries;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      entries.push_back(T_body_camera.matrix()(row, col));
    }
  }
  return entries;
}

void expectInvalidNaming(const SensorSetup& setup, const std::string& option) {
  InertialNavigatorConfig navigator;
  try {
    applySensorSetup(setup, datasetStreams(), std::nullopt, navigator);
    ADD_FAILURE() << "accepted a setup with a bad " << option;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(option), std::string::npos) << error.what();
  }
}

TEST(SensorSetup, WithoutConfigTheDatasetsSensorsAreTaken) {
  InertialNavigatorConfig navigator;
  const SensorStreams streams = datasetStreams();
  applySensorSetup(SensorSetup{}, streams, std::nullopt, navigator);
  EXPECT_EQ(navigator.imu_noise.gyro_noise_radps_per_sqrt_hz,
            streams.imu_noise->gyro_noise_radps_per_sqrt_hz);
  EXPECT_EQ(navigator.imu_noise.accel_bias_random_walk_mps3_per_sqrt_hz,
            streams.imu_noise->accel_bias_random_walk_mps3_per_sqrt_hz);
  EXPECT_TRUE(navigator.T_body_camera.isApprox(*streams.T_body_camera));
}

TEST(SensorSetup, WithoutEitherTheNavigatorsDefaultsStay) {
  InertialNavigatorConfig navigator;
  applySensorSetup(SensorSetup{}, SensorStreams{}, std::nullopt, navigator);
  const InertialNavigatorConfig defaults;
  EXPECT_EQ(navigator.imu_noise.gyro_noise_radps_per_sqrt_hz,
            defaults.imu_noise.gyro_noise_radps_per_sqrt_hz);
  EXPECT_EQ(navigator.gyro_range_radps, defaults.gyro_range_radps);
  EXPECT_TRUE(navigator.T_body_camera.isApprox(defaults.T_body_camera));
  EXPECT_TRUE(navigator.p_body_gps_antenna.isZero());
}

TEST(SensorSetup, TheConfigOverridesTheDataset) {
  SensorSetup setup;
  setup.gyro_noise_density = 1e-3;
  setup.accel_noise_density = 2e-2;
  setup.gyro_random_walk = 3e-5;
  setup.accel_random_walk = 4e-3;
  setup.gyro_range_radps = 8.7;
  setup.accel_range_mps2 = 78.0;
  setup.T_body_camera = cameraAhead();
  setup.p_body_gps_antenna = {-0.2, 0.0, 0.9};
  InertialNavigatorConfig navigator;
  applySensorSetup(setup, datasetStreams(), std::nullopt, navigator);
  EXPECT_EQ(navigator.imu_noise.gyro_noise_radps_per_sqrt_hz, 1e-3);
  EXPECT_EQ(navigator.imu_noise.accel_noise_mps2_per_sqrt_hz, 2e-2);
  EXPECT_EQ(navigator.imu_noise.gyro_bias_random_walk_radps2_per_sqrt_hz, 3e-5);
  EXPECT_EQ(navigator.imu_noise.accel_bias_random_walk_mps3_per_sqrt_hz, 4e-3);
  EXPECT_EQ(navigator.gyro_range_radps, 8.7);
  EXPECT_EQ(navigator.accel_range_mps2, 78.0);
  EXPECT_TRUE(navigator.T_body_camera.translation().isApprox(Eigen::Vector3d(0.3, 0.0, 0.0)));
  EXPECT_TRUE(navigator.p_body_gps_antenna.isApprox(Eigen::Vector3d(-0.2, 0.0, 0.9)));
}

TEST(SensorSetup, TheImusRotationOnTheBodyIsTaken) {
  SensorSetup setup;
  // The IMU mounted upside down: its z axis is the body's -z.
  setup.T_body_imu = {1, 0, 0, 0.1, 0, -1, 0, 0, 0, 0, -1, 0.2, 0, 0, 0, 1};
  InertialNavigatorConfig navigator;
  applySensorSetup(setup, SensorStreams{}, std::nullopt, navigator);
  EXPECT_TRUE(
      (navigator.R_body_imu * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitZ()));
}

TEST(SensorSetup, ASetupNotWholeOrNotValidNamesTheOption) {
  SensorSetup partial_noise;
  partial_noise.gyro_noise_density = 1e-3;
  expectInvalidNaming(partial_noise, "accel_noise_density");
  SensorSetup negative_noise;
  negative_noise.gyro_noise_density = 1e-3;
  negative_noise.accel_noise_density = -2e-2;
  negative_noise.gyro_random_walk = 3e-5;
  negative_noise.accel_random_walk = 4e-3;
  expectInvalidNaming(negative_noise, "accel_noise_density");
  SensorSetup negative_range;
  negative_range.accel_range_mps2 = -1.0;
  expectInvalidNaming(negative_range, "accel_range_mps2");
  SensorSetup sheared;
  sheared.T_body_camera = {1, 0.5, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  expectInvalidNaming(sheared, "T_body_camera");
  SensorSetup short_pose;
  short_pose.T_body_imu = {1, 0, 0};
  expectInvalidNaming(short_pose, "T_body_imu");
  SensorSetup antenna;
  antenna.p_body_gps_antenna = {0.0, 0.0};
  expectInvalidNaming(antenna, "p_body_gps_antenna");
  SensorSetup offset;
  offset.camera_time_offset_s = std::numeric_limits<double>::infinity();
  EXPECT_THROW(cameraTimeOffsetNs(offset, std::nullopt), std::invalid_argument);
}

// A Kalibr camchain's camera-IMU calibration: the IMU 5 cm behind the
// camera's centre, its axes the camera's; the camera clock 2.5 ms behind.
KalibrCamera camchain() {
  KalibrCamera camera;
  Eigen::Isometry3d T_cam_imu = Eigen::Isometry3d::Identity();
  T_cam_imu.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
  camera.T_cam_imu = T_cam_imu;
  camera.timeshift_cam_imu_s = 0.0025;
  return camera;
}

TEST(SensorSetup, TheCameraTimeOffsetIsTheConfigsLessTheCamchainsShift) {
  SensorSetup setup;
  setup.camera_time_offset_s = -0.0125;
  EXPECT_EQ(cameraTimeOffsetNs(setup, std::nullopt), -12'500'000);
  EXPECT_EQ(cameraTimeOffsetNs(setup, camchain()), -15'000'000);
}

// The camchain places the camera on the IMU's body; the config's own pose
// wins over it, and it over the dataset's.
TEST(SensorSetup, ACamchainPlacesTheCameraOnTheImusBody) {
  SensorSetup setup;
  setup.T_body_imu = {0, -1, 0, 0.2, 1, 0, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1};
  InertialNavigatorConfig navigator;
  applySensorSetup(setup, datasetStreams(), camchain(), navigator);
  const Eigen::Isometry3d T_body_imu = rigidTransform(setup.T_body_imu, "T_body_imu");
  EXPECT_TRUE(navigator.T_body_camera.isApprox(T_body_imu * camchain().T_cam_imu->inverse()));
  EXPECT_TRUE(navigator.T_body_camera.translation().isApprox(Eigen::Vector3d(0.2, 0.0, 0.55)));
  setup.T_body_camera = cameraAhead();
  applySensorSetup(setup, datasetStreams(), camchain(), navigator);
  EXPECT_TRUE(navigator.T_body_camera.translation().isApprox(Eigen::Vector3d(0.3, 0.0, 0.0)));
}

}  // namespace
}  // namespace lineloc

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "robot/input/euroc_sensor.h"

namespace lineloc {
namespace {

Eigen::Isometry3d parse(const std::string& text) {
  std::istringstream stream(text);
  return parseEurocSensorPose(stream, "cam0/sensor.yaml");
}

std::string sensorYaml(const std::string& data) {
  return "sensor_type: camera\nT_BS:\n  cols: 4\n  rows: 4\n  data: [" + data + "]\n";
}

TEST(EurocSensor, ReadsTheBodySensorPoseRowMajor) {
  // A forward-looking camera 1.2 m above the body origin.
  const Eigen::Isometry3d T_body_camera =
      parse(sensorYaml("0, 0, 1, 0.1, -1, 0, 0, 0.2, 0, -1, 0, 1.2, 0, 0, 0, 1"));
  EXPECT_TRUE(T_body_camera.translation().isApprox(Eigen::Vector3d(0.1, 0.2, 1.2)));
  // The optical axis (camera z) is the body's forward axis x.
  EXPECT_TRUE(
      (T_body_camera.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
}

TEST(EurocSensor, RejectsMalformedBlocksNamingTheFile) {
  const std::string identity = "1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1";
  for (const std::string& text :
       {std::string("sensor_type: camera\n"), sensorYaml("1, 0, 0"),
        sensorYaml("1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,2"),
        sensorYaml("2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1"),
        sensorYaml("-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1"),
        sensorYaml("1,0,0,0, 0,1,0,0, 0,0,1,.nan, 0,0,0,1"),
        sensorYaml("x,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1"),
        "T_BS:\n  cols: 3\n  rows: 4\n  data: [" + identity + "]\n", std::string("T_BS: [[[")}) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("cam0/sensor.yaml"), std::string::npos)
          << error.what();
    }
  }
}

TEST(EurocSensor, NestingTooDeepIsAnErrorNamingTheFile) {
  try {
    parse("T_BS: " + std::string(70000, '[') + std::string(70000, ']') + "\n");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("cam0/sensor.yaml: not valid YAML: nested too deeply"),
              std::string::npos)
        << error.what();
  }
}

std::optional<ImuNoiseDensities> parseNoise(const std::string& text) {
  std::istringstream stream(text);
  return parseEurocImuNoise(stream, "imu0/sensor.yaml");
}

// EuRoC's own imu0/sensor.yaml (an ADIS16448), comments and all.
const std::string kEurocImu =
    "sensor_type: imu\ncomment: VI-Sensor IMU (ADIS16448)\nrate_hz: 200\n"
    "gyroscope_noise_density: 1.6968e-04     # [ rad / s / sqrt(Hz) ]   ( gyro \"white noise\" )\n"
    "gyroscope_random_walk: 1.9393e-05       # [ rad / s^2 / sqrt(Hz) ] ( gyro bias diffusion )\n"
    "accelerometer_noise_density: 2.0000e-3  # [ m / s^2 / sqrt(Hz) ]   ( accel \"white noise\" )\n"
    "accelerometer_random_walk: 3.0000e-3    # [ m / s^3 / sqrt(Hz) ].  ( accel bias diffusion )\n";

TEST(EurocSensor, ReadsAnImusNoiseDensities) {
  const std::optional<ImuNoiseDensities> noise = parseNoise(kEurocImu);
  ASSERT_TRUE(noise.has_value());
  EXPECT_EQ(noise->gyro_noise_radps_per_sqrt_hz, 1.6968e-04);
  EXPECT_EQ(noise->gyro_bias_random_walk_radps2_per_sqrt_hz, 1.9393e-05);
  EXPECT_EQ(noise->accel_noise_mps2_per_sqrt_hz, 2.0e-3);
  EXPECT_EQ(noise->accel_bias_random_walk_mps3_per_sqrt_hz, 3.0e-3);
  EXPECT_FALSE(parseNoise(sensorYaml("1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1")).has_value());
  EXPECT_FALSE(parseNoise("just a scalar\n").has_value());
}

TEST(EurocSensor, RejectsAPartOrANonPositiveDensityNamingTheKey) {
  const auto replaced = [](const std::string& from, const std::string& to) {
    std::string text = kEurocImu;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  for (const auto& [text, key] :
       {std::pair{replaced("gyroscope_random_walk", "gyro_random_walk"), "gyroscope_random_walk"},
        std::pair{replaced("2.0000e-3", "-2.0e-3"), "accelerometer_noise_density"},
        std::pair{replaced("1.6968e-04", "0"), "gyroscope_noise_density"},
        std::pair{replaced("3.0000e-3", ".inf"), "accelerometer_random_walk"},
        std::pair{replaced("1.9393e-05", "fast"), "imu0/sensor.yaml"}}) {
    try {
      parseNoise(text);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("imu0/sensor.yaml"), std::string::npos)
          << error.what();
    }
  }
}

TEST(EurocSensor, MissingFileIsAnError) {
  EXPECT_THROW(readEurocSensorPose("no-such-dir/sensor.yaml"), std::runtime_error);
}

}  // namespace
}  // namespace lineloc

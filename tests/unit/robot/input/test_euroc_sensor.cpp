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

TEST(EurocSensor, MissingFileIsAnError) {
  EXPECT_THROW(readEurocSensorPose("no-such-dir/sensor.yaml"), std::runtime_error);
}

}  // namespace
}  // namespace lineloc

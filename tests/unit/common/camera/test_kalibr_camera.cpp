// Kalibr's camchain.yaml and EuRoC's cam0/sensor.yaml read as a camera
// calibration, directly and through readCameraCalibration beside OpenCV's
// YAML; a camera in them that is incomplete or unsupported is an error
// naming the file and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/camera/kalibr_camera.h"

namespace lineloc {
namespace {

// EuRoC MH_01_easy's cam0/sensor.yaml.
const std::string kEurocCamera = R"(# General sensor definitions.
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)

# Sensor extrinsics wrt. the body-frame.
T_BS:
  cols: 4
  rows: 4
  data: [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
         0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,
        -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
         0.0, 0.0, 0.0, 1.0]

# Camera specific definitions.
rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
)";

// The same camera as Kalibr writes it calibrated against an IMU.
const std::string kKalibrCamchain = R"(cam0:
  T_cam_imu:
  - [0.0148655429818, 0.999557249008, -0.0257744366974, 0.0652229095355]
  - [-0.999880929698, 0.0149672133247, 0.00375618835797, -0.0207064330118]
  - [0.00414029679422, 0.025715529948, 0.999660727178, -0.00805460971714]
  - [0.0, 0.0, 0.0, 1.0]
  cam_overlaps: [1]
  camera_model: pinhole
  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
  distortion_model: radtan
  intrinsics: [458.654, 457.296, 367.215, 248.375]
  resolution: [752, 480]
  rostopic: /cam0/image_raw
  timeshift_cam_imu: -0.0027
)";

std::optional<KalibrCamera> parse(const std::string& text) {
  std::istringstream stream(text);
  return parseKalibrCamera(stream, "camchain.yaml");
}

void expectCamera(const CameraCalibration& calibration) {
  EXPECT_EQ(calibration.camera.fx, 458.654);
  EXPECT_EQ(calibration.camera.fy, 457.296);
  EXPECT_EQ(calibration.camera.cx, 367.215);
  EXPECT_EQ(calibration.camera.cy, 248.375);
  EXPECT_EQ(calibration.camera.width, 752);
  EXPECT_EQ(calibration.camera.height, 480);
  EXPECT_EQ(calibration.distortion,
            (std::vector<double>{-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(KalibrCamera, ReadsAnEurocSensorYaml) {
  const std::optional<KalibrCamera> camera = parse(kEurocCamera);
  ASSERT_TRUE(camera.has_value());
  expectCamera(camera->calibration);
  EXPECT_FALSE(camera->T_cam_imu.has_value());
}

TEST(KalibrCamera, ReadsACamchainsCameraItsImuPoseAndTimeShift) {
  const std::optional<KalibrCamera> camera = parse(kKalibrCamchain);
  ASSERT_TRUE(camera.has_value());
  expectCamera(camera->calibration);
  ASSERT_TRUE(camera->T_cam_imu.has_value());
  EXPECT_TRUE(camera->T_cam_imu->translation().isApprox(
      Eigen::Vector3d(0.0652229095355, -0.0207064330118, -0.00805460971714)));
  EXPECT_EQ(camera->timeshift_cam_imu_s, -0.0027);
}

TEST(KalibrCamera, OtherYamlIsNeither) {
  EXPECT_FALSE(parse("camera_matrix: {rows: 3}\nimage_width: 640\n").has_value());
  EXPECT_FALSE(parse("- a list\n").has_value());
}

TEST(KalibrCamera, AnIncompleteOrUnsupportedCameraNamesTheKey) {
  for (const auto& [text, key] : {
           std::pair{replaced(kKalibrCamchain, "radtan", "fov"), "distortion_model"},
           std::pair{replaced(replaced(kKalibrCamchain, "radtan", "equidistant"),
                              ", 1.76187114e-05]", ", 1.76187114e-05, 0.1]"),
                     "distortion_coeffs"},
           std::pair{replaced(kKalibrCamchain, "camera_model: pinhole", "camera_model: omni"),
                     "camera_model"},
           std::pair{replaced(kKalibrCamchain, "[458.654, 457.296, 367.215, 248.375]",
                              "[458.654, 457.296, 367.215]"),
                     "intrinsics"},
           std::pair{replaced(kKalibrCamchain, "[458.654, 457.296,", "[-458.654, 457.296,"),
                     "focal lengths"},
           std::pair{replaced(kKalibrCamchain, "[752, 480]", "[752.5, 480]"), "resolution"},
           std::pair{replaced(kKalibrCamchain, "[752, 480]", "[0, 480]"), "resolution"},
           std::pair{replaced(kKalibrCamchain, ", 1.76187114e-05]", "]"), "distortion_coeffs"},
           std::pair{replaced(kKalibrCamchain, "distortion_coeffs", "distortion_coefficients"),
                     "distortion_coeffs"},
           std::pair{replaced(kKalibrCamchain, "[0.0, 0.0, 0.0, 1.0]", "[0.0, 0.0, 0.0, 2.0]"),
                     "T_cam_imu"},
           std::pair{replaced(kKalibrCamchain, "- [0.0, 0.0, 0.0, 1.0]", ""), "T_cam_imu"},
           std::pair{
               replaced(kKalibrCamchain, "timeshift_cam_imu: -0.0027", "timeshift_cam_imu: .nan"),
               "timeshift_cam_imu"},
           std::pair{std::string("cam0: 3\n"), "cam0"},
           std::pair{replaced(kEurocCamera, "distortion_coefficients", "distortion_coeffs"),
                     "distortion_coefficients"},
           std::pair{replaced(kEurocCamera, "[458.654,", "[fast,"), "camchain.yaml"},
           std::pair{std::string("cam0: [[[\n"), "camchain.yaml"},
       }) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("camchain.yaml"), std::string::npos) << error.what();
    }
  }
}

// readCameraCalibration takes all three formats: a camchain, a sensor.yaml
// and OpenCV's YAML, which it writes.
TEST(KalibrCamera, ReadCameraCalibrationTakesEachFormat) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("kalibr_camera_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "camchain.yaml") << kKalibrCamchain;
  std::ofstream(folder / "sensor.yaml") << kEurocCamera;
  expectCamera(readCameraCalibration((folder / "camchain.yaml").string()));
  const CameraCalibration from_sensor = readCameraCalibration((folder / "sensor.yaml").string());
  expectCamera(from_sensor);
  writeCameraCalibration((folder / "opencv.yaml").string(), from_sensor);
  expectCamera(readCameraCalibration((folder / "opencv.yaml").string()));
  // Kalibr's pinhole-equi fisheye, read and written back as one.
  std::ofstream(folder / "fisheye.yaml") << replaced(kKalibrCamchain, "radtan", "equidistant");
  const CameraCalibration fisheye = readCameraCalibration((folder / "fisheye.yaml").string());
  expectCamera(fisheye);
  EXPECT_EQ(fisheye.lens, LensModel::kEquidistant);
  EXPECT_EQ(fisheye.distortion.size(), 4u);
  writeCameraCalibration((folder / "fisheye_opencv.yaml").string(), fisheye);
  const CameraCalibration again = readCameraCalibration((folder / "fisheye_opencv.yaml").string());
  EXPECT_EQ(again.lens, LensModel::kEquidistant);
  EXPECT_EQ(again.distortion, fisheye.distortion);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace lineloc

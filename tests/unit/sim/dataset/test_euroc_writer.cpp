#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "sim/dataset/euroc_writer.h"
#include "tests/unit/sim/dataset/read_file.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

EurocDatasetSpec testSpec() {
  EurocDatasetSpec spec;
  spec.camera.camera = {500.0, 501.0, 320.5, 240.5, 0.0, 64, 48};
  spec.camera.distortion = {-0.2, 0.05, 1e-3, -2e-3, 0.01};
  spec.T_body_camera.translation() = Eigen::Vector3d(0.2, 0.0, 1.3);
  spec.imu.gyroscope_noise_density = 1.7e-4;
  return spec;
}

// A fresh folder under the test's temporary directory.
fs::path freshFolder(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("lineloc_test_euroc_" + name);
  fs::remove_all(path);
  return path;
}

void writeDrive(const fs::path& root) {
  EurocWriter writer(root.string(), testSpec());
  for (int i = 0; i < 3; ++i) {
    const int64_t stamp_ns = 1'000'000'000 + i * 50'000'000;
    cv::Mat image(48, 64, CV_8UC1, cv::Scalar(40 * i));
    Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
    T_world_camera.translation() = Eigen::Vector3d(i * 0.1, 2.0, 1.5);
    writer.writeImage(stamp_ns, image);
    writer.writeCameraGroundTruth({stamp_ns, T_world_camera});
    writer.writeImu(stamp_ns, Eigen::Vector3d(0.01, -0.02, 0.3), Eigen::Vector3d(0.1, 0.0, 9.81));
    writer.writeCompass(stamp_ns, 1.25);
    writer.writeGroundTruth({stamp_ns, Eigen::Isometry3d(T_world_camera), Eigen::Vector3d(2, 0, 0),
                             Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  }
  writer.writeNmea(1'000'000'000,
                   "$GPGGA,120000.00,5200.000,N,00421.000,E,2,09,0.9,1.5,M,43.2,M,,*5A");
}

TEST(EurocWriter, WritesTheEurocLayout) {
  const fs::path root = freshFolder("layout");
  writeDrive(root);
  const std::string images = readAll(root / "cam0" / "data.csv");
  EXPECT_EQ(images,
            "#timestamp [ns],filename\n1000000000,1000000000.png\n1050000000,1050000000.png\n"
            "1100000000,1100000000.png\n");
  const cv::Mat image =
      cv::imread((root / "cam0" / "data" / "1050000000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.type(), CV_8UC1);
  EXPECT_EQ(image.at<uint8_t>(10, 10), 40);
  const YAML::Node camera = YAML::LoadFile((root / "cam0" / "sensor.yaml").string());
  EXPECT_EQ(camera["resolution"][0].as<int>(), 64);
  EXPECT_DOUBLE_EQ(camera["intrinsics"][1].as<double>(), 501.0);
  EXPECT_DOUBLE_EQ(camera["distortion_coefficients"][3].as<double>(), -2e-3);
  EXPECT_DOUBLE_EQ(camera["T_BS"]["data"][11].as<double>(), 1.3);
  const CameraCalibration calibration =
      readCameraCalibration((root / "cam0" / "calibration.yaml").string());
  EXPECT_EQ(calibration.distortion, testSpec().camera.distortion);
  // The sensor.yaml holds the same camera, the whole lens model with it.
  const CameraCalibration from_sensor =
      readCameraCalibration((root / "cam0" / "sensor.yaml").string());
  EXPECT_EQ(from_sensor.distortion, testSpec().camera.distortion);
  EXPECT_EQ(from_sensor.camera.fy, calibration.camera.fy);
  EXPECT_DOUBLE_EQ(calibration.camera.cy, 240.5);
  const YAML::Node imu = YAML::LoadFile((root / "imu0" / "sensor.yaml").string());
  EXPECT_DOUBLE_EQ(imu["gyroscope_noise_density"].as<double>(), 1.7e-4);
  EXPECT_DOUBLE_EQ(imu["rate_hz"].as<double>(), 200.0);
  const std::string imu_rows = readAll(root / "imu0" / "data.csv");
  EXPECT_NE(imu_rows.find("\n1000000000,0.010000000,-0.020000000,0.300000000,0.100000000,"
                          "0.000000000,9.810000000\n"),
            std::string::npos);
  EXPECT_NE(readAll(root / "gps0" / "data.csv").find("1000000000,\"$GPGGA,120000.00"),
            std::string::npos);
  EXPECT_EQ(readAll(root / "gps0" / "nmea.txt").substr(0, 7), "$GPGGA,");
  EXPECT_NE(readAll(root / "compass0" / "data.csv").find("1100000000,1.250000000"),
            std::string::npos);
  const std::vector<StampedPose> truth = readTumFile((root / "groundtruth_cam0.tum").string());
  ASSERT_EQ(truth.size(), 3u);
  EXPECT_EQ(truth[2].stamp_ns, 1'100'000'000);
  EXPECT_NEAR(truth[2].pose.translation().x(), 0.2, 1e-9);
  const std::string states = readAll(root / "state_groundtruth_estimate0" / "data.csv");
  EXPECT_NE(states.find("\n1050000000,0.100000000,2.000000000,1.500000000,1.000000000000,"),
            std::string::npos);
}

TEST(EurocWriter, SameInputSameBytes) {
  const fs::path a = freshFolder("bytes_a");
  const fs::path b = freshFolder("bytes_b");
  writeDrive(a);
  writeDrive(b);
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (entry.is_regular_file()) {
      ++files;
      const fs::path other = b / fs::relative(entry.path(), a);
      EXPECT_EQ(readAll(entry.path()), readAll(other)) << entry.path();
    }
  }
  EXPECT_EQ(files, 13);
}

TEST(EurocWriter, RefusesBadStampsSentencesAndFolders) {
  const fs::path root = freshFolder("errors");
  EurocWriter writer(root.string(), testSpec());
  writer.writeCompass(10, 0.0);
  EXPECT_THROW(writer.writeCompass(10, 0.1), std::invalid_argument);
  EXPECT_THROW(writer.writeNmea(5, "$GPGGA,\"quoted\""), std::invalid_argument);
  // The folder now holds a dataset: a second writer must not mix into it.
  EXPECT_THROW(EurocWriter(root.string(), testSpec()), std::runtime_error);
}

}  // namespace
}  // namespace lineloc

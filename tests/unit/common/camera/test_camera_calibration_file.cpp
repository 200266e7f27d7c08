#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/camera/camera_calibration.h"

namespace lineloc {
namespace {

std::filesystem::path temporaryFile(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
          name);
}

CameraCalibration exampleCalibration() {
  CameraCalibration calibration;
  calibration.camera = {535.9, 535.8, 342.3, 235.6, 0.01, 640, 480};
  calibration.distortion = {-0.26, -0.04, 0.0018, -0.0003, 0.25};
  return calibration;
}

TEST(CameraCalibrationFile, WriteThenReadRoundTrips) {
  const std::filesystem::path path = temporaryFile("camera.yml");
  const CameraCalibration written = exampleCalibration();
  writeCameraCalibration(path.string(), written);
  const CameraCalibration read = readCameraCalibration(path.string());
  EXPECT_EQ(read.camera.K(), written.camera.K());
  EXPECT_EQ(read.camera.width, 640);
  EXPECT_EQ(read.camera.height, 480);
  EXPECT_EQ(read.distortion, written.distortion);
  std::filesystem::remove(path);
}

TEST(CameraCalibrationFile, OpenCvReadsTheWrittenFile) {
  const std::filesystem::path path = temporaryFile("camera.yml");
  writeCameraCalibration(path.string(), exampleCalibration());
  cv::FileStorage storage(path.string(), cv::FileStorage::READ);
  cv::Mat K;
  cv::Mat distortion;
  storage["camera_matrix"] >> K;
  storage["distortion_coefficients"] >> distortion;
  EXPECT_EQ(static_cast<int>(storage["image_width"]), 640);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 2), 342.3);
  EXPECT_EQ(distortion.total(), 5u);
  std::filesystem::remove(path);
}

TEST(CameraCalibrationFile, NoDistortionIsWrittenAsZeros) {
  const std::filesystem::path path = temporaryFile("camera.yml");
  CameraCalibration calibration = exampleCalibration();
  calibration.distortion.clear();
  writeCameraCalibration(path.string(), calibration);
  EXPECT_EQ(readCameraCalibration(path.string()).distortion, std::vector<double>(5, 0.0));
  std::filesystem::remove(path);
}

TEST(CameraCalibrationFile, UnwritablePathIsNamed) {
  try {
    writeCameraCalibration("/nonexistent-folder/camera.yml", exampleCalibration());
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent-folder/camera.yml"), std::string::npos);
  }
}

TEST(CameraCalibrationFile, OpenCvsYamlAndJsonAreReadItsXmlRefusedNamed) {
  for (const std::string name : {"camera.yml", "camera.json"}) {
    const std::filesystem::path path = temporaryFile(name);
    writeCameraCalibration(path.string(), exampleCalibration());
    const CameraCalibration read = readCameraCalibration(path.string());
    EXPECT_EQ(read.distortion, exampleCalibration().distortion) << name;
    EXPECT_EQ(read.camera, exampleCalibration().camera) << name;
    std::filesystem::remove(path);
  }
  const std::filesystem::path xml = temporaryFile("camera.xml");
  EXPECT_THROW(writeCameraCalibration(xml.string(), exampleCalibration()), std::runtime_error);
  std::ofstream(xml)
      << "<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>640</image_width>\n"
         "</opencv_storage>\n";
  try {
    readCameraCalibration(xml.string());
    ADD_FAILURE() << "read an XML calibration";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(xml.string() + ": an XML calibration is not read"),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove(xml);
}

// Damaged files, among them a truncated XML prolog that crashes OpenCV's own
// parser, are errors naming the file.
TEST(CameraCalibrationFile, DamagedFilesAreErrorsNamingTheFile) {
  const std::filesystem::path path = temporaryFile("damaged.yml");
  for (const std::string text :
       {"<?xml version=", "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n",
        "{\"image_width\": 640, \"camera_matrix\": {\"rows\": 3, \"cols\": 3,",
        "%YAML:1.0\n---\nimage_width: 640.5\n", "%YAML:1.0", "",
        "%YAML:1.0\ncamera_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0]}\n",
        "%YAML:1.0\ncamera_matrix: {rows: 3, cols: 3, data: [1, 0, .nan, 0, 1, 0, 0, 0, 1]}\n"}) {
    std::ofstream(path, std::ios::trunc) << text;
    try {
      readCameraCalibration(path.string());
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
    }
  }
  std::filesystem::remove(path);
}

TEST(CameraCalibrationFile, DepthBombsAreRefusedNamed) {
  const int depth = 70000;
  std::string xml = "<?xml version=\"1.0\"?>\n<opencv_storage>";
  for (int level = 0; level < depth; ++level) {
    xml += "<a>";
  }
  for (int level = 0; level < depth; ++level) {
    xml += "</a>";
  }
  xml += "</opencv_storage>\n";
  const std::string arrays = std::string(depth, '[') + std::string(depth, ']');
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"bomb.yml", "%YAML:1.0\n---\ncamera_matrix: " + arrays + "\n"},
           {"bomb.json", "{\"camera_matrix\": " + arrays + "}\n"},
           {"bomb.xml", xml}}) {
    const std::string expected = name == "bomb.xml" ? ": an XML calibration is not read"
                                                    : ": not valid YAML: nested too deeply";
    const std::filesystem::path path = temporaryFile(name);
    std::ofstream(path) << text;
    try {
      readCameraCalibration(path.string());
      ADD_FAILURE() << name << " accepted";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string() + expected), std::string::npos)
          << error.what();
    }
    std::filesystem::remove(path);
  }
}

TEST(CameraCalibrationFile, MissingKeyIsNamed) {
  const std::filesystem::path path = temporaryFile("camera.yml");
  std::ofstream(path) << "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n";
  try {
    readCameraCalibration(path.string());
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("camera_matrix"), std::string::npos);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lineloc

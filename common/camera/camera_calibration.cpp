#include "common/camera/camera_calibration.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/camera/kalibr_camera.h"

namespace lineloc {

Eigen::Matrix3d PinholeCamera::K() const {
  Eigen::Matrix3d K;
  K << fx, skew, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return K;
}

Eigen::Vector2d PinholeCamera::project(const Eigen::Vector3d& p_camera) const {
  const double x = p_camera.x() / p_camera.z();
  const double y = p_camera.y() / p_camera.z();
  return {fx * x + skew * y + cx, fy * y + cy};
}

namespace {

// An OpenCV matrix {rows, cols, dt, data: [rows x cols numbers]}, row-major.
std::vector<double> readMatrix(const YAML::Node& root, const std::string& key, int rows, int cols,
                               const std::string& path) {
  const YAML::Node matrix = root[key];
  if (!matrix || !matrix.IsMap()) {
    throw std::runtime_error(fmt::format("{}: missing or empty '{}'", path, key));
  }
  const YAML::Node data = matrix["data"];
  if (!matrix["rows"] || !matrix["cols"] || !data || !data.IsSequence() ||
      matrix["rows"].as<int>() != rows || matrix["cols"].as<int>() != cols ||
      data.size() != static_cast<size_t>(rows) * static_cast<size_t>(cols)) {
    throw std::runtime_error(
        fmt::format("{}: '{}' must be a {} x {} matrix (rows, cols, data)", path, key, rows, cols));
  }
  std::vector<double> values;
  for (const YAML::Node& value : data) {
    values.push_back(value.as<double>());
    if (!std::isfinite(values.back())) {
      throw std::runtime_error(fmt::format("{}: '{}' has non-finite entries", path, key));
    }
  }
  return values;
}

// A coefficient vector written as one row or one column of `count` numbers.
std::vector<double> readCoefficients(const YAML::Node& root, const std::string& key,
                                     const std::string& path) {
  const YAML::Node matrix = root[key];
  if (!matrix || !matrix.IsMap() || !matrix["rows"] || !matrix["cols"]) {
    throw std::runtime_error(fmt::format("{}: missing or empty '{}'", path, key));
  }
  const int rows = matrix["rows"].as<int>();
  const int cols = matrix["cols"].as<int>();
  if (!((rows == 1 && cols >= 4 && cols <= 8) || (cols == 1 && rows >= 4 && rows <= 8))) {
    throw std::runtime_error(fmt::format("{}: {} must have 4 to 8 entries", path, key));
  }
  return readMatrix(root, key, rows, cols, path);
}

int readPositiveInt(const YAML::Node& root, const std::string& key, const std::string& path) {
  const YAML::Node node = root[key];
  if (!node || !node.IsScalar() || node.as<int>() <= 0) {
    throw std::runtime_error(fmt::format("{}: '{}' must be a positive integer", path, key));
  }
  return node.as<int>();
}

CameraCalibration readOpenCvCalibration(const YAML::Node& root, const std::string& path) {
  if (!root.IsMap()) {
    throw std::runtime_error(fmt::format("{}: not a map of calibration keys", path));
  }
  const std::vector<double> K = readMatrix(root, "camera_matrix", 3, 3, path);
  CameraCalibration calibration;
  PinholeCamera& camera = calibration.camera;
  camera.fx = K[0];
  camera.skew = K[1];
  camera.cx = K[2];
  camera.fy = K[4];
  camera.cy = K[5];
  if (camera.fx <= 0.0 || camera.fy <= 0.0) {
    throw std::runtime_error(fmt::format("{}: focal lengths must be positive", path));
  }
  camera.width = readPositiveInt(root, "image_width", path);
  camera.height = readPositiveInt(root, "image_height", path);
  if (const YAML::Node model = root["distortion_model"]) {
    const std::string name = model.IsScalar() ? model.as<std::string>() : "";
    if (name == "equidistant" || name == "fisheye") {
      calibration.lens = LensModel::kEquidistant;
    } else if (name != "radial-tangential" && name != "plumb_bob" && name != "radtan" &&
               name != "k1k2" && name != "opencv5") {
      // k1k2 and opencv5: lineloc-calibrate's radial-tangential coefficient sets.
      throw std::runtime_error(fmt::format(
          "{}: distortion_model '{}' is not radial-tangential (plumb_bob, k1k2, opencv5) or "
          "equidistant (fisheye)",
          path, name));
    }
  }
  calibration.distortion = readCoefficients(root, "distortion_coefficients", path);
  if (calibration.lens == LensModel::kEquidistant && calibration.distortion.size() != 4) {
    throw std::runtime_error(
        fmt::format("{}: an equidistant lens has 4 distortion_coefficients (k1 k2 k3 k4)", path));
  }
  return calibration;
}

}  // namespace

CameraCalibration readCameraCalibration(const std::string& path) {
  const YAML::Node root = calibrationDocument(path);
  if (const std::optional<KalibrCamera> kalibr = kalibrCamera(root, path)) {
    return kalibr->calibration;
  }
  try {
    return readOpenCvCalibration(root, path);
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: {}", path, error.what()));
  }
}

void writeCameraCalibration(cv::FileStorage& storage, const CameraCalibration& calibration) {
  const PinholeCamera& camera = calibration.camera;
  storage << "image_width" << camera.width;
  storage << "image_height" << camera.height;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << camera.fx, camera.skew, camera.cx, 0.0, camera.fy,
                     camera.cy, 0.0, 0.0, 1.0);
  storage << "camera_matrix" << K;
  // No distortion is written as five zeros, the shortest list OpenCV reads.
  const bool equidistant = calibration.lens == LensModel::kEquidistant;
  const std::vector<double> distortion = calibration.distortion.empty()
                                             ? std::vector<double>(equidistant ? 4 : 5, 0.0)
                                             : calibration.distortion;
  storage << "distortion_coefficients" << cv::Mat(distortion, true);
  if (equidistant) {
    storage << "distortion_model"
            << "equidistant";
  }
}

cv::FileStorage openCalibrationFileForWriting(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".xml") {
    throw std::runtime_error(fmt::format(
        "cannot write '{}': calibrations are written as YAML or JSON, which are read back", path));
  }
  cv::FileStorage storage;
  try {
    storage.open(path, cv::FileStorage::WRITE);
  } catch (const cv::Exception& error) {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", path, error.what()));
  }
  if (!storage.isOpened()) {
    throw std::runtime_error(fmt::format("cannot write camera calibration '{}'", path));
  }
  return storage;
}

void writeCameraCalibration(const std::string& path, const CameraCalibration& calibration) {
  cv::FileStorage storage = openCalibrationFileForWriting(path);
  writeCameraCalibration(storage, calibration);
}

}  // namespace lineloc

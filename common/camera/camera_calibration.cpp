#include "common/camera/camera_calibration.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>
#include <optional>
#include <stdexcept>

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

// OpenCV's YAML, JSON and XML parsers recurse once per level of nesting with
// no limit of their own, so a file nested tens of thousands of levels deep
// overflows the stack. Nesting is at most the number of opening brackets and
// tags, whatever the format; a calibration file has a few dozen.
constexpr size_t kMaxCalibrationOpenings = 4096;

// Throws std::runtime_error naming `path` when it holds more openings ('[',
// '{', or '<' not followed by '/') than kMaxCalibrationOpenings.
void checkOpeningsBound(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  size_t openings = 0;
  bool after_angle = false;
  for (char c; file.get(c);) {
    openings += (c == '[' || c == '{' || (after_angle && c != '/')) ? 1 : 0;
    after_angle = c == '<';
    if (openings > kMaxCalibrationOpenings) {
      throw std::runtime_error(fmt::format(
          "{}: nested too deeply for a camera calibration (more than {} opening brackets and "
          "tags)",
          path, kMaxCalibrationOpenings));
    }
  }
}

cv::Mat readMatrix(const cv::FileStorage& storage, const std::string& key,
                   const std::string& path) {
  cv::Mat matrix;
  storage[key] >> matrix;
  if (matrix.empty()) {
    throw std::runtime_error(fmt::format("{}: missing or empty '{}'", path, key));
  }
  matrix.convertTo(matrix, CV_64F);
  if (!cv::checkRange(matrix)) {
    throw std::runtime_error(fmt::format("{}: '{}' has non-finite entries", path, key));
  }
  return matrix;
}

int readPositiveInt(const cv::FileStorage& storage, const std::string& key,
                    const std::string& path) {
  const cv::FileNode node = storage[key];
  if (node.empty() || !node.isInt() || static_cast<int>(node) <= 0) {
    throw std::runtime_error(fmt::format("{}: '{}' must be a positive integer", path, key));
  }
  return static_cast<int>(node);
}

}  // namespace

CameraCalibration readCameraCalibration(const std::string& path) {
  checkOpeningsBound(path);
  if (const std::optional<KalibrCamera> kalibr = readKalibrCamera(path)) {
    return kalibr->calibration;
  }
  cv::FileStorage storage;
  try {
    storage.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& error) {
    throw std::runtime_error(
        fmt::format("{}: not a readable OpenCV YAML file: {}", path, error.what()));
  }
  if (!storage.isOpened()) {
    throw std::runtime_error(fmt::format("cannot open camera calibration '{}'", path));
  }
  const cv::Mat K = readMatrix(storage, "camera_matrix", path);
  if (K.rows != 3 || K.cols != 3) {
    throw std::runtime_error(fmt::format("{}: camera_matrix must be 3x3", path));
  }
  CameraCalibration calibration;
  PinholeCamera& camera = calibration.camera;
  camera.fx = K.at<double>(0, 0);
  camera.skew = K.at<double>(0, 1);
  camera.cx = K.at<double>(0, 2);
  camera.fy = K.at<double>(1, 1);
  camera.cy = K.at<double>(1, 2);
  if (camera.fx <= 0.0 || camera.fy <= 0.0) {
    throw std::runtime_error(fmt::format("{}: focal lengths must be positive", path));
  }
  camera.width = readPositiveInt(storage, "image_width", path);
  camera.height = readPositiveInt(storage, "image_height", path);
  const cv::Mat distortion = readMatrix(storage, "distortion_coefficients", path);
  if (distortion.total() < 4 || distortion.total() > 8) {
    throw std::runtime_error(
        fmt::format("{}: distortion_coefficients must have 4 to 8 entries", path));
  }
  calibration.distortion.assign(distortion.begin<double>(), distortion.end<double>());
  return calibration;
}

void writeCameraCalibration(cv::FileStorage& storage, const CameraCalibration& calibration) {
  const PinholeCamera& camera = calibration.camera;
  storage << "image_width" << camera.width;
  storage << "image_height" << camera.height;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << camera.fx, camera.skew, camera.cx, 0.0, camera.fy,
                     camera.cy, 0.0, 0.0, 1.0);
  storage << "camera_matrix" << K;
  // No distortion is written as five zeros, the shortest list OpenCV reads.
  const std::vector<double> distortion =
      calibration.distortion.empty() ? std::vector<double>(5, 0.0) : calibration.distortion;
  storage << "distortion_coefficients" << cv::Mat(distortion, true);
}

cv::FileStorage openCalibrationFileForWriting(const std::string& path) {
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

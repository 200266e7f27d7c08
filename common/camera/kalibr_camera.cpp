#include "common/camera/kalibr_camera.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/config/yaml_document.h"
#include "common/geometry/pose.h"

namespace lineloc {
namespace {

std::vector<double> numbers(const YAML::Node& camera, const std::string& key, size_t count,
                            const std::string& source) {
  const YAML::Node node = camera[key];
  if (!node || !node.IsSequence() || node.size() != count) {
    throw std::runtime_error(fmt::format("{}: {} must hold {} numbers", source, key, count));
  }
  std::vector<double> values;
  for (const YAML::Node& value : node) {
    values.push_back(value.as<double>());
    if (!std::isfinite(values.back())) {
      throw std::runtime_error(fmt::format("{}: {} holds a non-finite number", source, key));
    }
  }
  return values;
}

std::string text(const YAML::Node& camera, const std::string& key, const std::string& source) {
  const YAML::Node node = camera[key];
  if (!node || !node.IsScalar()) {
    throw std::runtime_error(fmt::format("{}: {} is missing", source, key));
  }
  return node.as<std::string>();
}

// Calibration files are a few hundred bytes; a much larger one is not one.
constexpr std::streamoff kMaxCalibrationBytes = 1 << 20;

// Kalibr's and EuRoC's four radial-tangential coefficients, or up to OpenCV's
// eight in its order (k1 k2 p1 p2 [k3 [k4 k5 k6]]).
std::vector<double> distortionCoefficients(const YAML::Node& camera, const std::string& key,
                                           const std::string& source) {
  const YAML::Node node = camera[key];
  if (!node || !node.IsSequence() || node.size() < 4 || node.size() > 8) {
    throw std::runtime_error(
        fmt::format("{}: {} must hold 4 to 8 numbers (k1 k2 p1 p2 [k3 [k4 k5 k6]])", source, key));
  }
  return numbers(camera, key, node.size(), source);
}

// The 4x4 matrix Kalibr writes as a list of four rows.
Eigen::Isometry3d cameraImuPose(const YAML::Node& rows, const std::string& source) {
  if (!rows.IsSequence() || rows.size() != 4) {
    throw std::runtime_error(
        fmt::format("{}: T_cam_imu must be four rows of four numbers", source));
  }
  std::vector<double> entries;
  for (const YAML::Node& row : rows) {
    if (!row.IsSequence() || row.size() != 4) {
      throw std::runtime_error(
          fmt::format("{}: T_cam_imu must be four rows of four numbers", source));
    }
    for (const YAML::Node& value : row) {
      entries.push_back(value.as<double>());
    }
  }
  return rigidTransform(entries, source + ": T_cam_imu");
}

KalibrCamera readCamera(const YAML::Node& camera, bool camchain, const std::string& source) {
  const std::string model =
      camera["camera_model"] ? text(camera, "camera_model", source) : "pinhole";
  if (model != "pinhole") {
    throw std::runtime_error(
        fmt::format("{}: camera_model '{}' is not supported (only pinhole)", source, model));
  }
  const std::string distortion_model = text(camera, "distortion_model", source);
  KalibrCamera result;
  if (distortion_model == "equidistant" || distortion_model == "equi") {
    result.calibration.lens = LensModel::kEquidistant;
  } else if (distortion_model != "radtan" && distortion_model != "radial-tangential") {
    throw std::runtime_error(
        fmt::format("{}: distortion_model '{}' is not supported (radtan, radial-tangential, "
                    "equidistant)",
                    source, distortion_model));
  }
  const std::vector<double> intrinsics = numbers(camera, "intrinsics", 4, source);
  const std::vector<double> resolution = numbers(camera, "resolution", 2, source);
  PinholeCamera& pinhole = result.calibration.camera;
  pinhole.fx = intrinsics[0];
  pinhole.fy = intrinsics[1];
  pinhole.cx = intrinsics[2];
  pinhole.cy = intrinsics[3];
  if (!(pinhole.fx > 0.0 && pinhole.fy > 0.0)) {
    throw std::runtime_error(fmt::format("{}: intrinsics' focal lengths must be positive", source));
  }
  for (const double side : resolution) {
    if (!(side >= 1.0 && side <= 1e5 && side == std::floor(side))) {
      throw std::runtime_error(
          fmt::format("{}: resolution must be two positive whole numbers of pixels", source));
    }
  }
  pinhole.width = static_cast<int>(resolution[0]);
  pinhole.height = static_cast<int>(resolution[1]);
  const std::string coefficients = camchain ? "distortion_coeffs" : "distortion_coefficients";
  result.calibration.distortion = result.calibration.lens == LensModel::kEquidistant
                                      ? numbers(camera, coefficients, 4, source)
                                      : distortionCoefficients(camera, coefficients, source);
  if (camchain && camera["T_cam_imu"]) {
    result.T_cam_imu = cameraImuPose(camera["T_cam_imu"], source);
  }
  if (camchain && camera["timeshift_cam_imu"]) {
    result.timeshift_cam_imu_s = camera["timeshift_cam_imu"].as<double>();
    if (!std::isfinite(result.timeshift_cam_imu_s)) {
      throw std::runtime_error(fmt::format("{}: timeshift_cam_imu must be finite", source));
    }
  }
  return result;
}

}  // namespace

YAML::Node calibrationDocument(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot open camera calibration '{}'", path));
  }
  std::string text(std::istreambuf_iterator<char>(file), {});
  if (static_cast<std::streamoff>(text.size()) > kMaxCalibrationBytes) {
    throw std::runtime_error(
        fmt::format("{}: over {} bytes, not a camera calibration", path, kMaxCalibrationBytes));
  }
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '<') {
    throw std::runtime_error(fmt::format(
        "{}: an XML calibration is not read; write it as YAML or JSON (opencv_storage's keys)",
        path));
  }
  if (text.compare(first == std::string::npos ? 0 : first, 6, "%YAML:") == 0) {
    text.erase(0, text.find('\n', first));
  }
  std::istringstream stream(text);
  return loadYamlDocument(stream, path);
}

std::optional<KalibrCamera> kalibrCamera(const YAML::Node& root, const std::string& source) {
  try {
    if (!root.IsMap()) {
      return std::nullopt;
    }
    if (const YAML::Node cam0 = root["cam0"]) {
      if (!cam0.IsMap()) {
        throw std::runtime_error(
            fmt::format("{}: cam0 must be a map of the camera's keys", source));
      }
      return readCamera(cam0, true, source + ": cam0");
    }
    if (root["intrinsics"]) {
      return readCamera(root, false, source);
    }
    return std::nullopt;
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(fmt::format("{}: {}", source, error.what()));
  }
}

std::optional<KalibrCamera> parseKalibrCamera(std::istream& yaml, const std::string& source) {
  return kalibrCamera(loadYamlDocument(yaml, source), source);
}

std::optional<KalibrCamera> readKalibrCamera(const std::string& path) {
  return kalibrCamera(calibrationDocument(path), path);
}

}  // namespace lineloc

// A calibrated camera: pinhole intrinsics plus lens distortion, read and written
// in OpenCV's YAML layout (camera_matrix, distortion_coefficients, image_width,
// image_height) so files from cv::calibrateCamera and lineloc-calibrate are
// interchangeable.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace cv {
class FileStorage;
}

namespace lineloc {

// Pinhole intrinsics: u = fx x/z + skew y/z + cx, v = fy y/z + cy.
struct PinholeCamera {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  double skew = 0.0;
  int width = 0;
  int height = 0;

  Eigen::Matrix3d K() const;
  // Projects a point in the camera frame (z > 0) to pixels.
  Eigen::Vector2d project(const Eigen::Vector3d& p_camera) const;

  bool operator==(const PinholeCamera&) const = default;
};

// How the lens bends rays (lens_distortion.h).
enum class LensModel { kRadialTangential, kEquidistant };

// Undistorted image points, lines and corners are in `camera`, the pinhole
// camera with the lens's focal length and principal point, for either lens:
// a fisheye keeps its angular resolution at the centre, and its rays further
// off the axis than the image's rectangle reaches (atan of half the width
// over f) are left out.
struct CameraCalibration {
  PinholeCamera camera;
  // Radial-tangential: OpenCV order, k1 k2 p1 p2 [k3 [k4 k5 k6]]; equidistant:
  // k1 k2 k3 k4. Empty means no distortion.
  std::vector<double> distortion;
  LensModel lens = LensModel::kRadialTangential;
};

// Reads OpenCV's YAML or JSON (camera_matrix, distortion_coefficients,
// image_width, image_height, as writeCameraCalibration writes them, and
// distortion_model: "equidistant" or "fisheye" for a fisheye lens), a
// Kalibr camchain.yaml (its cam0) or an EuRoC sensor.yaml (kalibr_camera.h),
// all with yaml-cpp; OpenCV's XML is refused, as its parser crashes on some
// damaged files. Throws std::runtime_error naming the file and the missing
// or invalid key, or saying it nests too deeply to be parsed safely.
CameraCalibration readCameraCalibration(const std::string& path);

// Opens an OpenCV YAML (or, for a .json path, JSON) file for writing; throws
// std::runtime_error naming it when it cannot be created, or is an .xml
// path (XML is not read back).
cv::FileStorage openCalibrationFileForWriting(const std::string& path);

// Writes image_width, image_height, camera_matrix and distortion_coefficients
// into `storage` (open for writing), so a caller can add its own keys.
void writeCameraCalibration(cv::FileStorage& storage, const CameraCalibration& calibration);

// Writes the calibration as a new OpenCV YAML file; throws std::runtime_error
// naming the file when it cannot be written.
void writeCameraCalibration(const std::string& path, const CameraCalibration& calibration);

}  // namespace lineloc

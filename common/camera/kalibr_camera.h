// Camera calibrations in the YAML of Kalibr (camchain.yaml, its cam0) and of
// the EuRoC/ASL datasets (cam0/sensor.yaml), which share Kalibr's camera
// keys: camera_model (pinhole), intrinsics [fu, fv, cu, cv], resolution
// [width, height], distortion_model (radtan, or EuRoC's radial-tangential:
// k1 k2 p1 p2, OpenCV's first four, or more of OpenCV's, as lineloc-sim
// writes them; equidistant, Kalibr's pinhole-equi fisheye: k1 k2 k3 k4) and
// its coefficients (Kalibr's distortion_coeffs, EuRoC's
// distortion_coefficients). A camchain's cam0
// also holds the IMU's pose in the camera frame (T_cam_imu, 4x4) and the
// camera clock's shift (timeshift_cam_imu, s: t_imu = t_cam + shift).
// Furgale, Rehder & Siegwart, "Unified temporal and spatial calibration for
// multi-sensor systems", IROS 2013.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <istream>
#include <optional>
#include <string>

#include "common/camera/camera_calibration.h"

namespace lineloc {

struct KalibrCamera {
  CameraCalibration calibration;
  // A camchain's; none from a sensor.yaml.
  std::optional<Eigen::Isometry3d> T_cam_imu;
  double timeshift_cam_imu_s = 0.0;
};

// The YAML document of a calibration file in any format
// readCameraCalibration takes: OpenCV's YAML (after its "%YAML:1.0" header,
// which is not YAML to other parsers) or JSON, a camchain, a sensor.yaml.
// OpenCV's own parsers crash on some damaged files (a truncated XML
// prolog), so none reads one: XML is refused. Throws std::runtime_error
// naming the file when it cannot be read, is larger than 1 MB, is XML, or
// is not valid YAML (nested too deeply among others).
YAML::Node calibrationDocument(const std::string& path);

// The camera of a document in either format; nullopt for one in neither (no
// cam0 block, no intrinsics key), so another format may hold it. Throws
// std::runtime_error naming `source` and the key when the camera is
// incomplete or invalid: not a pinhole, a distortion model other than
// radial-tangential (radtan) or equidistant (equi, Kalibr's pinhole-equi
// fisheye), a non-positive focal length or size, radial-tangential
// coefficients fewer than 4 or more than 8, equidistant ones other than 4, a
// T_cam_imu that is not a rigid transform.
std::optional<KalibrCamera> kalibrCamera(const YAML::Node& root, const std::string& source);

// The same of YAML text, and of the file at `path` (calibrationDocument).
std::optional<KalibrCamera> parseKalibrCamera(std::istream& yaml, const std::string& source);
std::optional<KalibrCamera> readKalibrCamera(const std::string& path);

}  // namespace lineloc

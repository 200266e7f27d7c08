// The mounting of a sensor in an EuRoC/ASL dataset: the T_BS block of its
// sensor.yaml, the sensor's pose in the body frame as a row-major 4x4 matrix
// (Burri et al., "The EuRoC micro aerial vehicle datasets", IJRR 2016).
#pragma once

#include <Eigen/Geometry>
#include <istream>
#include <string>

namespace lineloc {

// Parses T_BS (rows: 4, cols: 4, data: 16 numbers) from sensor.yaml text;
// `source` names it in errors. Throws std::runtime_error when the block is
// missing or malformed, the last row is not 0 0 0 1, or the rotation is not
// orthonormal with determinant +1 (within 1e-6).
Eigen::Isometry3d parseEurocSensorPose(std::istream& yaml, const std::string& source);

// The same for a file.
Eigen::Isometry3d readEurocSensorPose(const std::string& path);

}  // namespace lineloc

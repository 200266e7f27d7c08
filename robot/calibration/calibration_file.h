// The calibration file lineloc-calibrate writes: OpenCV's YAML layout, as its
// calibration sample writes it (image_width, image_height, camera_matrix,
// distortion_coefficients, avg_reprojection_error,
// per_view_reprojection_errors, extrinsic_parameters as rows of rvec and
// tvec), plus the standard deviations of every parameter, the estimated image
// noise, the options used, the view names and any degeneracy warnings. Every
// lineloc program and cv::FileStorage read it.
#pragma once

#include <string>
#include <vector>

#include "robot/calibration/zhang_calibration.h"

namespace lineloc {

// Writes to a temporary file next to `path` and renames it, so a failed write
// leaves no partial file. Throws std::runtime_error naming the file.
void writeCalibrationFile(const std::string& path, const CalibrationResult& result,
                          const CalibrationOptions& options,
                          const std::vector<std::string>& view_names);

}  // namespace lineloc

// lineloc-calibrate: camera calibration from chessboard images or from point
// correspondence files, or the reprojection error of an existing calibration
// on new views. The program's main only parses options and calls runCalibrateTool.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace lineloc {

struct CalibrateToolConfig {
  std::string images;               // shell pattern of chessboard images
  std::string board = "9x6";        // inner corners COLUMNSxROWS
  double square_m = 0.025;          // chessboard square side
  std::vector<std::string> points;  // MODEL VIEW1 VIEW2 ... point files
  std::string image_size;           // WxH, with --points
  std::string out = "camera.yml";   // calibration file written
  std::string check;                // existing calibration to check instead of calibrating
  std::string report;               // residual plot PNG (empty: none)
  double report_magnification = 30.0;
  bool fix_skew = false;
  bool fix_aspect_ratio = false;
  double aspect_ratio = 1.0;
  bool fix_principal_point = false;
  std::string distortion = "k1k2";  // k1k2 or opencv5
  int max_iterations = 100;
};

// Minimum number of usable views the tool calibrates from.
inline constexpr int kMinCalibrationViews = 3;

// Runs the tool, printing a report to `log`. Throws std::runtime_error naming
// the file or option for bad input (nothing is written then). Returns 0, or 1
// when the calibration itself fails.
int runCalibrateTool(const CalibrateToolConfig& config, std::ostream& log);

}  // namespace lineloc

// A picture of where a calibration fits badly: every view's residual vectors
// (measured minus predicted point, magnified) drawn from the measured points
// over the image area, one colour per view, with a scale bar.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "robot/calibration/calibration_problem.h"

namespace lineloc {

// `magnification`: image pixels drawn per pixel of residual.
cv::Mat drawResidualPlot(const PlanarViews& views,
                         const std::vector<std::vector<Eigen::Vector2d>>& residuals_px,
                         double magnification);

// Writes the plot as PNG; throws std::runtime_error naming the file on failure.
void writeResidualPlot(const std::string& path, const PlanarViews& views,
                       const std::vector<std::vector<Eigen::Vector2d>>& residuals_px,
                       double magnification);

}  // namespace lineloc

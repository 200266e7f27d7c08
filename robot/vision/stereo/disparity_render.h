// Picture of a disparity map for the user: disparity / max disparity through
// OpenCV's "turbo" colour map, pixels without an estimate black.
#pragma once

#include <opencv2/core.hpp>

#include "robot/vision/stereo/sad_stereo_matcher.h"

namespace lineloc {

cv::Mat renderDisparity(const DisparityMap& map, double max_disparity_px);

}  // namespace lineloc

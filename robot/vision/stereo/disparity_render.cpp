#include "robot/vision/stereo/disparity_render.h"

#include <opencv2/imgproc.hpp>

namespace lineloc {

cv::Mat renderDisparity(const DisparityMap& map, double max_disparity_px) {
  cv::Mat scaled, picture;
  map.disparity_px.convertTo(scaled, CV_8U, 255.0 / std::max(max_disparity_px, 1.0));
  cv::applyColorMap(scaled, picture, cv::COLORMAP_TURBO);
  picture.setTo(cv::Scalar(0, 0, 0), map.valid == 0);
  return picture;
}

}  // namespace lineloc

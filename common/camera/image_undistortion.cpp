#include "common/camera/image_undistortion.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace lineloc {

cv::Mat undistortImage(const cv::Mat& image, const CameraCalibration& calibration) {
  if (calibration.distortion.empty()) {
    return image.clone();
  }
  cv::Mat K;
  cv::eigen2cv(calibration.camera.K(), K);
  cv::Mat undistorted;
  if (calibration.lens == LensModel::kEquidistant) {
    cv::fisheye::undistortImage(image, undistorted, K, calibration.distortion, K);
  } else {
    cv::undistort(image, undistorted, K, calibration.distortion);
  }
  return undistorted;
}

}  // namespace lineloc

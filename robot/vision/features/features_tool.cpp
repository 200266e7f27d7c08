#include "robot/vision/features/features_tool.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/camera/image_undistortion.h"
#include "robot/input/image_sequence.h"
#include "robot/vision/features/feature_report.h"

namespace lineloc {
namespace {

CameraCalibration calibrationFor(const FeaturesToolConfig& config, const cv::Mat& image) {
  if (!config.camera_calibration.empty()) {
    return readCameraCalibration(config.camera_calibration);
  }
  CameraCalibration calibration;
  calibration.camera.width = image.cols;
  calibration.camera.height = image.rows;
  calibration.camera.fx = calibration.camera.fy = std::max(image.cols, image.rows);
  calibration.camera.cx = 0.5 * (image.cols - 1);
  calibration.camera.cy = 0.5 * (image.rows - 1);
  return calibration;
}

}  // namespace

FeaturesToolSummary runFeaturesTool(const FeaturesToolConfig& config, std::ostream& out) {
  const cv::Mat image = readGreyImage(config.image);
  const CameraCalibration calibration = calibrationFor(config, image);
  FeatureExtractor extractor(calibration, config.extractor);
  const FrameFeatures& features = extractor.extract(image);
  writeFeaturesText(out, features);
  if (!config.out.empty() &&
      !cv::imwrite(config.out, drawFeatures(undistortImage(image, calibration), features))) {
    throw std::runtime_error("cannot write overlay '" + config.out + "'");
  }
  return {features.noise_sigma, features.segments.size(), features.rejected_segments,
          features.corners.size()};
}

}  // namespace lineloc

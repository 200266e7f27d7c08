#include "backbone/tracker/tracking_overlay.h"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "common/camera/image_undistortion.h"

namespace lineloc {
namespace {

const cv::Scalar kImageSegmentColour(40, 40, 230);
const cv::Scalar kAlignedColour(60, 220, 60);
const cv::Scalar kPredictedColour(0, 160, 255);
const cv::Scalar kImageCornerColour(0, 230, 230);
const cv::Scalar kUsedCornerColour(230, 230, 0);

cv::Point2f toPoint(const Eigen::Vector2d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y())};
}

cv::Mat undistortedColour(const cv::Mat& image, const CameraCalibration& calibration) {
  cv::Mat colour;
  if (image.channels() == 1) {
    cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  } else {
    colour = image;
  }
  return undistortImage(colour, calibration);
}

}  // namespace

cv::Mat drawTrackingOverlay(const cv::Mat& image, const std::vector<ImageSegment>& segments,
                            const std::vector<ImageCorner>& corners, const TrackedFrame& frame,
                            const CameraCalibration& calibration) {
  const PinholeCamera& camera = calibration.camera;
  cv::Mat overlay = undistortedColour(image, calibration);
  for (const ImageSegment& segment : segments) {
    cv::line(overlay, toPoint(segment.start.cast<double>()), toPoint(segment.end.cast<double>()),
             kImageSegmentColour, 1, cv::LINE_AA);
  }
  for (const ImageCorner& corner : corners) {
    cv::circle(overlay, toPoint(corner.position.cast<double>()), 3, kImageCornerColour, 1,
               cv::LINE_AA);
  }
  const bool aligned = frame.alignment.status == AlignmentStatus::kOk;
  if (aligned) {
    for (const int used : frame.alignment.inlier_corners) {
      cv::circle(overlay, toPoint(corners.at(static_cast<size_t>(used)).position.cast<double>()), 4,
                 kUsedCornerColour, cv::FILLED, cv::LINE_AA);
    }
  }
  // Whatever lies in front of the lens is drawn, in a scene of any size.
  VisibilityOptions frustum;
  frustum.near_m = 1e-6;
  const Eigen::Isometry3d T_camera_world = frame.T_world_camera.pose.inverse();
  for (const VisibleSegment& line : frame.visible) {
    Eigen::Vector3d a = T_camera_world * line.start_world;
    Eigen::Vector3d b = T_camera_world * line.end_world;
    if (!clipToFrustum(a, b, camera, frustum)) {
      continue;
    }
    cv::line(overlay, toPoint(camera.project(a)), toPoint(camera.project(b)),
             aligned ? kAlignedColour : kPredictedColour, 2, cv::LINE_AA);
  }
  const std::string caption = fmt::format("{}: {} matches, {} inliers, rms {:.2f} px",
                                          toString(frame.alignment.status), frame.alignment.matches,
                                          frame.alignment.inliers, frame.alignment.rms_residual_px);
  cv::putText(overlay, caption, {10, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255),
              1, cv::LINE_AA);
  return overlay;
}

}  // namespace lineloc

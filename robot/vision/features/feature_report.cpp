#include "robot/vision/features/feature_report.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lineloc {
namespace {

const cv::Scalar kLeftBrighterBgr(0, 200, 0);
const cv::Scalar kRightBrighterBgr(200, 0, 200);
const cv::Scalar kCornerBgr(0, 0, 255);
constexpr int kCrossSizePx = 7;
constexpr double kDegreesPerRadian = 180.0 / M_PI;

cv::Point2f toCv(const Eigen::Vector2f& p) {
  return {p.x(), p.y()};
}

}  // namespace

void writeFeaturesText(std::ostream& out, const FrameFeatures& features) {
  for (size_t i = 0; i < features.segments.size(); ++i) {
    const ImageSegment& s = features.segments[i];
    const SegmentFitQuality& q = features.segment_quality[i];
    fmt::print(out, "segment {:.3f} {:.3f} {:.3f} {:.3f} {:.4f} {:.4f} {:.1f} {:+d} {}\n",
               s.start.x(), s.start.y(), s.end.x(), s.end.y(), q.sigma_offset_px,
               q.sigma_angle_rad * kDegreesPerRadian, s.contrast, s.polarity, q.point_count);
  }
  for (const ImageCorner& c : features.corners) {
    fmt::print(out, "corner {:.3f} {:.3f} {:.5f} {:.5f} {:.5f} {:.1f}\n", c.position.x(),
               c.position.y(), c.covariance(0, 0), c.covariance(0, 1), c.covariance(1, 1),
               c.strength);
  }
}

cv::Mat drawFeatures(const cv::Mat& undistorted, const FrameFeatures& features) {
  cv::Mat overlay;
  if (undistorted.channels() == 1) {
    cv::cvtColor(undistorted, overlay, cv::COLOR_GRAY2BGR);
  } else {
    overlay = undistorted.clone();
  }
  for (const ImageSegment& s : features.segments) {
    const cv::Scalar& colour = s.polarity >= 0 ? kLeftBrighterBgr : kRightBrighterBgr;
    cv::line(overlay, toCv(s.start), toCv(s.end), colour, 1, cv::LINE_AA);
  }
  for (const ImageCorner& c : features.corners) {
    cv::drawMarker(overlay, toCv(c.position), kCornerBgr, cv::MARKER_CROSS, kCrossSizePx, 1);
  }
  return overlay;
}

}  // namespace lineloc

#include "robot/vision/features/feature_extractor.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "segment_scoring.h"
#include "synthetic_scene.h"

namespace lineloc {
namespace {

using testing::renderRectangles;
using testing::SceneOptions;

CameraCalibration idealCamera(cv::Size size) {
  CameraCalibration calibration;
  calibration.camera = {
      400.0, 400.0, 0.5 * (size.width - 1), 0.5 * (size.height - 1), 0.0, size.width, size.height};
  return calibration;
}

// Accuracy on rendered rectangles (90 degree corners, contrast 48..98 grey
// levels, lens blur sigma 1 px, sensor noise sigma_n = 2 grey levels).
//
// Tolerances from the noise model. Total blur s = sqrt(1^2 + 1^2) px (lens +
// pre-smoothing); for contrast C the gradient peaks at C / (sqrt(2 pi) s)
// with curvature C / (sqrt(2 pi) s^3) >= 48 / 7.1 ~ 6.8 grey levels / px^3.
// The smoothed gradient's noise slope is ~0.2 sigma_n = 0.4, so one edge
// point's normal error is ~0.4 / 6.8 ~ 0.06 px. A side of L >= 40 px has
// ~L/2 independent points (neighbours share the smoothing): the angle sigma
// is 0.06 / sqrt(20 * 40^2 / 12) rad = 0.07 deg, 0.2 deg is ~3 sigma; the
// normal offset sigma is 0.06 / sqrt(20) = 0.013 px. Endpoints and corners
// are intersections of two such lines at 90 degrees: ~0.02 px per axis,
// plus the renderer's 1/32 px edge placement and the sub-pixel estimator's
// phase-dependent bias (measured noise-free: <= 0.18 deg, <= 0.1 px), so
// 0.5 px for endpoints and 0.2 px for corners hold with a wide margin.
// Recall >= 95 % and spurious <= 5 % are the numbers; with 56
// sides of >= 40 px at contrast >= 48 (>= 6 sigma_n per point after
// smoothing) none should be missed.
TEST(FeatureExtractor, FindsRenderedSegmentsAndCornersAccurately) {
  const SceneOptions options;
  int true_segments = 0, found = 0, detected = 0, spurious = 0;
  double max_endpoint_error = 0.0, max_angle_error = 0.0;
  int true_corners = 0, found_corners = 0;
  double max_corner_error = 0.0;
  FeatureExtractor extractor(idealCamera(options.size));
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const testing::SyntheticScene scene = renderRectangles(options, 5, seed);
    const FrameFeatures& features = extractor.extract(scene.image);
    const testing::SegmentScore score = testing::scoreSegments(scene, features.segments);
    true_segments += score.true_segments;
    found += score.found;
    detected += score.detected;
    spurious += score.spurious;
    max_endpoint_error = std::max(max_endpoint_error, score.max_endpoint_error_px);
    max_angle_error = std::max(max_angle_error, score.max_angle_error_deg);
    const testing::CornerScore corners = testing::scoreCorners(scene, features.corners);
    true_corners += corners.true_corners;
    found_corners += corners.found;
    max_corner_error = std::max(max_corner_error, corners.max_error_px);
  }
  ASSERT_GT(true_segments, 100);
  EXPECT_GE(found, 0.95 * true_segments) << found << " of " << true_segments;
  EXPECT_LE(spurious, 0.05 * detected) << spurious << " of " << detected;
  EXPECT_LE(max_endpoint_error, 0.5);
  EXPECT_LE(max_angle_error, 0.2);
  EXPECT_GE(found_corners, 0.95 * true_corners) << found_corners << " of " << true_corners;
  EXPECT_LE(max_corner_error, 0.2);
}

// The scene seen through a lens with barrel distortion: each distorted pixel
// p shows the rendered (undistorted) image at u(p), from OpenCV's own
// inverse of the model. Segments must come back straight, in undistorted
// coordinates. Same tolerances as above: bilinear resampling of an image
// already blurred by 1 px adds well under 0.05 px of edge shift.
TEST(FeatureExtractor, UndistortsEdgePointsBeforeFittingLines) {
  const SceneOptions options;
  CameraCalibration calibration = idealCamera(options.size);
  calibration.camera.fx = calibration.camera.fy = 260.0;
  calibration.distortion = {-0.25, 0.05, 0.0, 0.0};
  std::vector<cv::Point2f> pixels;
  for (int y = 0; y < options.size.height; ++y) {
    for (int x = 0; x < options.size.width; ++x) {
      pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
    }
  }
  const cv::Matx33d K(260.0, 0.0, calibration.camera.cx, 0.0, 260.0, calibration.camera.cy, 0.0,
                      0.0, 1.0);
  std::vector<cv::Point2f> sources;
  cv::undistortPoints(pixels, sources, K, calibration.distortion, cv::noArray(), K,
                      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-9));
  const cv::Mat map = cv::Mat(sources, true).reshape(2, options.size.height);
  FeatureExtractor extractor(calibration);
  int true_segments = 0, found = 0, detected = 0, spurious = 0;
  double max_endpoint_error = 0.0, max_angle_error = 0.0;
  for (uint32_t seed = 21; seed <= 23; ++seed) {
    const testing::SyntheticScene scene = renderRectangles(options, 5, seed);
    cv::Mat distorted;
    cv::remap(scene.image, distorted, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    const testing::SegmentScore score =
        testing::scoreSegments(scene, extractor.extract(distorted).segments);
    true_segments += score.true_segments;
    found += score.found;
    detected += score.detected;
    spurious += score.spurious;
    max_endpoint_error = std::max(max_endpoint_error, score.max_endpoint_error_px);
    max_angle_error = std::max(max_angle_error, score.max_angle_error_deg);
  }
  ASSERT_GT(true_segments, 40);
  EXPECT_GE(found, 0.95 * true_segments) << found << " of " << true_segments;
  EXPECT_LE(spurious, 0.05 * detected) << spurious << " of " << detected;
  EXPECT_LE(max_endpoint_error, 0.5);
  EXPECT_LE(max_angle_error, 0.2);
}

}  // namespace
}  // namespace lineloc

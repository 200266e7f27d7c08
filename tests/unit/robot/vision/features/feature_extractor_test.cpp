#include "robot/vision/features/feature_extractor.h"

#include <gtest/gtest.h>

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
// levels, lens blur sigma 1 px, sensor noise sigma 2 grey levels).
//
// Tolerances from the noise model: an edge point's normal error is about
// sigma_n / |g'| where the smoothed gradient's slope across the edge at
// its peak, for contrast C and total blur s = sqrt(1 + 1) px, is
// C / (sqrt(2 pi) s^2) >= 48 / 5.0 ~ 9.6 grey levels / px^2, and the
// derivative-of-gradient noise after smoothing is ~0.3 sigma_n: point
// sigma ~ 0.6 / 9.6 ~ 0.06 px. A 40 px side has >= 20 independent points,
// so its line's normal offset sigma ~ 0.015 px and angle sigma
// ~ 0.06 / sqrt(20 * 40^2 / 12) rad ~ 0.07 deg: 0.2 deg is 3 sigma.
// Endpoints come from the intersection of two such lines at 90 degrees:
// sigma ~ 0.03 px per coordinate plus the renderer's 1/32 px edge
// placement; 0.5 px leaves room for the corner blur bias of the line fits.
// Corners: Förstner's estimate on a blurred 90 degree corner is biased
// along the bisector by a fraction of the blur; 0.2 px is the bound.
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

}  // namespace
}  // namespace lineloc

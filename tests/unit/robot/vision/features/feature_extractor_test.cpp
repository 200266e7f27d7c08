#include "robot/vision/features/feature_extractor.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// Scores summed over several scenes: counts added, errors their maximum.
struct Tally {
  int true_segments = 0, found = 0, detected = 0, spurious = 0;
  double max_endpoint_error = 0.0, max_angle_error = 0.0;
  int true_corners = 0, found_corners = 0;
  double max_corner_error = 0.0;

  void add(const testing::SegmentScore& score) {
    true_segments += score.true_segments;
    found += score.found;
    detected += score.detected;
    spurious += score.spurious;
    max_endpoint_error = std::max(max_endpoint_error, score.max_endpoint_error_px);
    max_angle_error = std::max(max_angle_error, score.max_angle_error_deg);
  }
  void add(const testing::CornerScore& score) {
    true_corners += score.true_corners;
    found_corners += score.found;
    max_corner_error = std::max(max_corner_error, score.max_error_px);
  }
};

// The front end on `scenes` scenes of `count` rectangles with sides in `sides`.
Tally rectangleTally(const testing::SideRange& sides, int count, uint32_t first_seed, int scenes) {
  const SceneOptions options;
  FeatureExtractor extractor(idealCamera(options.size));
  Tally tally;
  for (uint32_t seed = first_seed; seed < first_seed + scenes; ++seed) {
    const testing::SyntheticScene scene = renderRectangles(options, count, seed, sides);
    const FrameFeatures& features = extractor.extract(scene.image);
    tally.add(testing::scoreSegments(scene, features.segments));
    tally.add(testing::scoreCorners(scene, features.corners));
  }
  return tally;
}

// The numbers: recall >= 95 %, spurious <= 5 %, endpoints within
// 0.5 px, corners (where scored) within 0.2 px; angles within max_angle_deg.
void expectAccurate(const Tally& tally, double max_angle_deg) {
  EXPECT_GE(tally.found, 0.95 * tally.true_segments)
      << tally.found << " of " << tally.true_segments;
  EXPECT_LE(tally.spurious, 0.05 * tally.detected) << tally.spurious << " of " << tally.detected;
  EXPECT_LE(tally.max_endpoint_error, 0.5);
  EXPECT_LE(tally.max_angle_error, max_angle_deg);
  EXPECT_GE(tally.found_corners, 0.95 * tally.true_corners)
      << tally.found_corners << " of " << tally.true_corners;
  EXPECT_LE(tally.max_corner_error, 0.2);
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
// Recall >= 95 % and spurious <= 5 % are the numbers; with over 100
// sides of >= 40 px at contrast >= 48 (>= 6 sigma_n per point after
// smoothing) none should be missed.
TEST(FeatureExtractor, FindsRenderedSegmentsAndCornersAccurately) {
  const Tally tally = rectangleTally({40.0, 110.0}, 5, 1, 6);
  ASSERT_GT(tally.true_segments, 100);
  expectAccurate(tally, 0.2);
}

// The shortest segments the issue counts: sides of 21..40 px, the same
// scenes and tolerances otherwise, but for the angle. By the noise model
// above the angle sigma of a side of L px is 0.06 px sqrt(24) / L^1.5 rad:
// 0.17 deg at 21 px, so 0.2 deg (3 sigma) is only reachable from L = 40 px
// up. Here 3 sigma at 21 px (0.52 deg) plus the sub-pixel estimator's
// phase-dependent bias, which a short side does not average out (measured
// noise-free: <= 0.33 deg at 21..24 px), gives 0.9 deg. Endpoints and
// corners stay within 0.5 and 0.2 px: they are the intersections of the
// long lines of the neighbouring sides too.
TEST(FeatureExtractor, FindsShortRenderedSegments) {
  const Tally tally = rectangleTally({21.0, 40.0}, 10, 101, 6);
  ASSERT_GT(tally.true_segments, 200);
  expectAccurate(tally, 0.9);
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
  Tally tally;
  for (uint32_t seed = 21; seed <= 23; ++seed) {
    const testing::SyntheticScene scene = renderRectangles(options, 5, seed);
    cv::Mat distorted;
    cv::remap(scene.image, distorted, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    tally.add(testing::scoreSegments(scene, extractor.extract(distorted).segments));
  }
  ASSERT_GT(tally.true_segments, 40);
  expectAccurate(tally, 0.2);
}

}  // namespace
}  // namespace lineloc

// A frame's reference view: the pinhole camera of the reference focal length
// that sees the frame's image, scaled as a whole.
#include <gtest/gtest.h>

#include "backbone/matching/reference_view.h"

namespace lineloc {
namespace {

// A 5 megapixel camera, 62 degrees across.
const PinholeCamera kFiveMegapixel{2063.28, 2060.0, 1232.0, 1028.0, 0.5, 2464, 2056};

ImageSegment segmentFrom(const Eigen::Vector2f& start, const Eigen::Vector2f& end) {
  ImageSegment segment;
  segment.start = start;
  segment.end = end;
  segment.start_covariance << 0.25f, 0.05f, 0.05f, 0.5f;
  segment.end_covariance << 1.0f, 0.0f, 0.0f, 0.25f;
  segment.contrast = 33.0f;
  segment.polarity = -1;
  return segment;
}

TEST(ReferenceView, SeesEveryPointWhereTheFramesCameraDoesScaled) {
  const ReferenceView view = referenceView({}, kFiveMegapixel, 536.0);
  const double s = 536.0 / 2063.28;
  EXPECT_DOUBLE_EQ(view.scale, s);
  EXPECT_DOUBLE_EQ(view.camera.fx, 536.0);
  EXPECT_EQ(view.camera.width, 640);
  EXPECT_EQ(view.camera.height, 534);
  for (const Eigen::Vector3d& p_camera :
       {Eigen::Vector3d(0.0, 0.0, 5.0), Eigen::Vector3d(-3.0, 1.0, 7.0),
        Eigen::Vector3d(2.0, -2.5, 4.0)}) {
    EXPECT_TRUE(view.camera.project(p_camera).isApprox(s * kFiveMegapixel.project(p_camera), 1e-12))
        << p_camera.transpose();
  }
}

TEST(ReferenceView, ScalesTheSegmentsEndsAndCovariancesOnly) {
  const ImageSegment seen = segmentFrom({100.0f, 2000.0f}, {2400.0f, 30.0f});
  const ReferenceView view = referenceView({seen}, kFiveMegapixel, 536.0);
  ASSERT_EQ(view.segments.size(), 1u);
  const ImageSegment& scaled = view.segments[0];
  const auto s = static_cast<float>(view.scale);
  EXPECT_TRUE(scaled.start.isApprox(s * seen.start));
  EXPECT_TRUE(scaled.end.isApprox(s * seen.end));
  EXPECT_TRUE(scaled.start_covariance.isApprox(s * s * seen.start_covariance));
  EXPECT_TRUE(scaled.end_covariance.isApprox(s * s * seen.end_covariance));
  EXPECT_EQ(scaled.contrast, seen.contrast);
  EXPECT_EQ(scaled.polarity, seen.polarity);
}

TEST(ReferenceView, AReferenceViewIsItsOwn) {
  const ReferenceView once =
      referenceView({segmentFrom({10.0f, 20.0f}, {300.0f, 40.0f})}, kFiveMegapixel, 536.0);
  const ReferenceView twice = referenceView(once.segments, once.camera, 536.0);
  EXPECT_NEAR(twice.scale, 1.0, 1e-12);
  EXPECT_EQ(twice.camera.width, once.camera.width);
  EXPECT_EQ(twice.camera.height, once.camera.height);
  EXPECT_TRUE(twice.segments[0].end.isApprox(once.segments[0].end));
}

}  // namespace
}  // namespace lineloc

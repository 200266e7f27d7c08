// Image edges in open sky, seen from a camera 1.5 m up looking north along a
// street with one 10 m building on its east side: an edge on the roof line
// (even a few pixels above it) or on the façade is no sky edge, one well above
// the roof line is; over open land nothing below the horizon or low over it
// counts.
#include <gtest/gtest.h>

#include "backbone/matching/line_matcher.h"
#include "backbone/matching/sky_edges.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

class SkyEdges : public ::testing::Test {
 protected:
  SkyEdges() : street_(oneBuilding()), scene_(street_.faces, street_.face_building_ids) {
    Eigen::Matrix3d R_world_camera;  // looking north, level
    R_world_camera << 1, 0, 0, 0, 0, 1, 0, -1, 0;
    T_world_camera_.linear() = R_world_camera;
    T_world_camera_.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  }

  static Street oneBuilding() {
    Street street;
    addBox(street, 8, 30, 20, 90, 10);
    return street;
  }

  // The image segment between the projections of two world points, moved
  // by `shift_px`.
  ImageSegment imageOf(const Eigen::Vector3d& start_world, const Eigen::Vector3d& end_world,
                       const Eigen::Vector2d& shift_px = Eigen::Vector2d::Zero()) const {
    const ProjectedSegment projected =
        projectSegment(start_world, end_world, {T_world_camera_, Matrix6d::Zero()}, kCamera);
    ImageSegment segment;
    segment.start = (projected.start_px + shift_px).cast<float>();
    segment.end = (projected.end_px + shift_px).cast<float>();
    return segment;
  }

  double skyPx(const ImageSegment& segment) const {
    return skyEdgeLength({segment}, T_world_camera_, kCamera, scene_, SkyEdgeOptions{});
  }

  static double length(const ImageSegment& segment) { return (segment.end - segment.start).norm(); }

  // The roof line facing the street, and the façade's middle under it.
  const Eigen::Vector3d roof_start_{8, 30, 10}, roof_end_{8, 90, 10};
  const Eigen::Vector3d facade_start_{8, 30, 5}, facade_end_{8, 90, 5};

  Street street_;
  OcclusionScene scene_;
  Eigen::Isometry3d T_world_camera_ = Eigen::Isometry3d::Identity();
};

TEST_F(SkyEdges, TheRoofLineAndTheFacadeAreNoSky) {
  EXPECT_EQ(skyPx(imageOf(roof_start_, roof_end_)), 0.0);
  // Two pixels of noise above the roof line: within the margin.
  EXPECT_EQ(skyPx(imageOf(roof_start_, roof_end_, {0.0, -2.0})), 0.0);
  EXPECT_EQ(skyPx(imageOf(facade_start_, facade_end_)), 0.0);
}

TEST_F(SkyEdges, AnEdgeWellAboveTheRoofLineIsSky) {
  const ImageSegment above = imageOf(roof_start_, roof_end_, {0.0, -30.0});
  ASSERT_GT(length(above), 100.0);
  EXPECT_NEAR(skyPx(above), length(above), 1e-3);
  // Segments add up.
  const ImageSegment half = imageOf(roof_start_, {8, 60, 10}, {0.0, -30.0});
  EXPECT_NEAR(skyEdgeLength({above, half}, T_world_camera_, kCamera, scene_, SkyEdgeOptions{}),
              length(above) + length(half), 1e-3);
}

TEST_F(SkyEdges, NothingBelowTheHorizonOrLowOverItCounts) {
  // Over open land to the west of the street, 50 m ahead.
  const auto across = [&](double elevation_rad) {
    const double z = 1.5 + 50.0 * std::tan(elevation_rad);
    return imageOf({-30, 50, z}, {-10, 50, z});
  };
  EXPECT_EQ(skyPx(across(-0.05)), 0.0);
  EXPECT_EQ(skyPx(across(0.05)), 0.0);
  const ImageSegment high = across(0.3);
  EXPECT_NEAR(skyPx(high), length(high), 1e-3);
}

TEST_F(SkyEdges, ShortSegmentsAreNotSampled) {
  const ImageSegment above = imageOf(roof_start_, roof_end_, {0.0, -30.0});
  ImageSegment short_piece = above;
  short_piece.end = short_piece.start + (above.end - above.start).normalized() * 10.0f;
  EXPECT_EQ(skyPx(short_piece), 0.0);
}

}  // namespace
}  // namespace lineloc

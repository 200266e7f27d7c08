// Image edges in open sky, seen from a camera 1.5 m up looking north along a
// street with one 10 m building on its east side: an edge on the roof line
// (even a few pixels above it) or on the façade is no sky edge, one well above
// the roof line is, and in clear sky only when more than a storey above it;
// over open land nothing below the horizon or low over it counts. The clear
// sky's area, its clutter density, and the edges weighed by the evidence
// they carry.
#include <gtest/gtest.h>

#include "backbone/matching/line_matcher.h"
#include "backbone/matching/sky_edges.h"
#include "synthetic_street.h"

namespace lineloc {
namespace {

using namespace lineloc::testing;

class SkyOfOneBuilding : public ::testing::Test {
 protected:
  SkyOfOneBuilding() : street_(oneBuilding()), scene_(street_.faces, street_.face_building_ids) {
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

  double skyPx(const ImageSegment& segment) const { return sky({segment}).edge_px; }

  SkyEdges sky(const std::vector<ImageSegment>& image) const {
    return measureSkyEdges(image, T_world_camera_, kCamera, scene_, SkyEdgeOptions{});
  }

  static double length(const ImageSegment& segment) { return (segment.end - segment.start).norm(); }

  // The roof line facing the street, and the façade's middle under it.
  const Eigen::Vector3d roof_start_{8, 30, 10}, roof_end_{8, 90, 10};
  const Eigen::Vector3d facade_start_{8, 30, 5}, facade_end_{8, 90, 5};

  Street street_;
  OcclusionScene scene_;
  Eigen::Isometry3d T_world_camera_ = Eigen::Isometry3d::Identity();
};

TEST_F(SkyOfOneBuilding, TheRoofLineAndTheFacadeAreNoSky) {
  EXPECT_EQ(skyPx(imageOf(roof_start_, roof_end_)), 0.0);
  // Two pixels of noise above the roof line: within the margin.
  EXPECT_EQ(skyPx(imageOf(roof_start_, roof_end_, {0.0, -2.0})), 0.0);
  EXPECT_EQ(skyPx(imageOf(facade_start_, facade_end_)), 0.0);
}

TEST_F(SkyOfOneBuilding, AnEdgeWellAboveTheRoofLineIsSky) {
  const ImageSegment above = imageOf(roof_start_, roof_end_, {0.0, -30.0});
  ASSERT_GT(length(above), 100.0);
  EXPECT_NEAR(skyPx(above), length(above), 1e-3);
  // Segments add up.
  const ImageSegment half = imageOf(roof_start_, {8, 60, 10}, {0.0, -30.0});
  EXPECT_NEAR(sky({above, half}).edge_px, length(above) + length(half), 1e-3);
}

TEST_F(SkyOfOneBuilding, ClearSkyIsMoreThanAStoreyAboveTheRoofLine) {
  // 30 px above the roof line's near half: 0.06 rad, under the clear margin.
  const ImageSegment near_roof = imageOf(roof_start_, {8, 60, 10}, {0.0, -30.0});
  const SkyEdges open = sky({near_roof});
  EXPECT_NEAR(open.edge_px, length(near_roof), 1e-3);
  EXPECT_EQ(open.clear_edge_px, 0.0);
  // 200 px above it: 0.4 rad, still above the roof when lowered by the margin.
  const ImageSegment high = imageOf(roof_start_, roof_end_, {0.0, -200.0});
  const SkyEdges clear = sky({high});
  EXPECT_GT(clear.clear_edge_px, 0.5 * length(high));
  EXPECT_NEAR(clear.clear_edge_px, clear.edge_px, 1e-3);
}

TEST_F(SkyOfOneBuilding, TheClearSkyOfAViewOfOpenSkyIsTheImage) {
  // Looking west, away from the building, 40 degrees up: every ray rises
  // more than min_elevation_rad, and none meets a face, lowered or not.
  const Eigen::Matrix3d looking_west_level =
      (Eigen::Matrix3d() << 0, 0, -1, 1, 0, 0, 0, -1, 0).finished();
  const Eigen::Isometry3d up_west(Eigen::Translation3d(0.0, 0.0, 1.5) *
                                  Eigen::AngleAxisd(40.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
                                  looking_west_level);
  const double image_area = kCamera.width * kCamera.height;
  EXPECT_NEAR(clearSkyArea(up_west, kCamera, scene_, SkyEdgeOptions{}), image_area, 1e-6);
  // Looking north, the façade, the ground and the sky within a storey of
  // the roof line are not clear sky.
  const double north = clearSkyArea(T_world_camera_, kCamera, scene_, SkyEdgeOptions{});
  EXPECT_GT(north, 0.1 * image_area);
  EXPECT_LT(north, 0.5 * image_area);
}

TEST(ClearSkyEdgeDensity, IsMeasuredInEnoughClearSkyOnly) {
  SkyEdgeOptions options;
  options.min_clear_area_px2 = 2e4;
  const SkyEdges sky{1000.0, 900.0};
  EXPECT_EQ(clearSkyEdgeDensity(sky, 9e4, options), 0.01);
  EXPECT_EQ(clearSkyEdgeDensity(sky, 1.9e4, options), std::nullopt);
}

TEST(WeighedSkyEdges, ATypicalStreetSkyCountsInFull) {
  const SkyEdgeOptions options;
  const SkyEdges sky{1000.0, 900.0};
  EXPECT_EQ(weighedSkyEdgeLength(sky, 0.0, options), 1000.0);
  EXPECT_EQ(weighedSkyEdgeLength(sky, options.typical_clutter_density, options), 1000.0);
}

TEST(WeighedSkyEdges, EdgesWeighAsTheEvidenceTheyCarry) {
  SkyEdgeOptions options;
  options.facade_edge_density = 0.04;
  options.typical_clutter_density = 0.01;
  const SkyEdges sky{1000.0, 900.0};
  // log(0.04 / 0.02) / log(0.04 / 0.01) = 1/2.
  EXPECT_NEAR(weighedSkyEdgeLength(sky, 0.02, options), 500.0, 1e-9);
  // A sky as dense in edges as a façade tells nothing.
  EXPECT_EQ(weighedSkyEdgeLength(sky, 0.04, options), 0.0);
  EXPECT_EQ(weighedSkyEdgeLength(sky, 0.08, options), 0.0);
}

}  // namespace
}  // namespace lineloc

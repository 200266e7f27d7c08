// Segments of a drive past a wall associated into lines: the window's outer
// and inner frame edges (8 cm apart, bright on opposite sides) and its top
// each become one line, within their uncertainty of the truth; a lamp post in
// front of the wall, which lands on the wall at a place that moves with the
// viewpoint, becomes none; too few views give none.
#include <gtest/gtest.h>

#include "backbone/enrichment/surface_line_tracks.h"
#include "wall_drive.h"

namespace lineloc {
namespace {

using namespace wall_drive;

constexpr double kPixelSigma = 0.5;

class SurfaceLineTracksTest : public ::testing::Test {
 protected:
  SurfaceLineTracksTest() : scene_(wallFaces(), {kBuilding}) {}

  // The surface segments of frames from y = 0, 1, ... (views of them).
  void drive(SurfaceLineTracks& tracks, int views, const std::string& robot = "r1") {
    for (int k = 0; k < views; ++k) {
      EnrichmentFrame frame = frameAt(cameraAt(k), kPixelSigma, random_);
      frame.robot_id = robot;
      frame.stamp_ns = 1'000'000'000LL * k;
      for (const SurfaceSegment& segment :
           observeSurfaceSegments(frame, scene_, SurfaceObservationOptions{}).segments) {
        tracks.add(segment);
      }
    }
  }

  OcclusionScene scene_;
  std::mt19937 random_{11};
};

// The candidate whose line passes nearest the middle of start -> end.
const LineCandidate* nearest(const std::vector<LineCandidate>& candidates,
                             const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
  const LineCandidate* found = nullptr;
  double best = 1e9;
  for (const LineCandidate& candidate : candidates) {
    const double distance =
        distanceFromLine(0.5 * (start + end), candidate.line.start_world, candidate.line.end_world);
    if (distance < best) {
      best = distance;
      found = &candidate;
    }
  }
  return found;
}

TEST_F(SurfaceLineTracksTest, WindowEdgesBecomeLinesAndThePostNone) {
  SurfaceLineTracks tracks(SurfaceLineTrackOptions{});
  drive(tracks, 8);
  const std::vector<LineCandidate> candidates = tracks.candidates();
  ASSERT_EQ(candidates.size(), 3u);
  for (const auto& [start, end] :
       {std::pair{kWindowSideStart, kWindowSideEnd}, std::pair{kFrameInnerStart, kFrameInnerEnd},
        std::pair{kWindowTopStart, kWindowTopEnd}}) {
    const LineCandidate* candidate = nearest(candidates, start, end);
    ASSERT_NE(candidate, nullptr);
    EXPECT_EQ(candidate->building_id, kBuilding);
    EXPECT_EQ(candidate->views, 8);
    EXPECT_EQ(candidate->robots, 1);
    EXPECT_EQ(candidate->first_stamp_ns, 0);
    EXPECT_EQ(candidate->last_stamp_ns, 7'000'000'000LL);
    // In the wall, and within three standard deviations of the true line.
    for (const Eigen::Vector3d& end_point :
         {candidate->line.start_world, candidate->line.end_world}) {
      EXPECT_NEAR(end_point.x(), kWall_x, 1e-6);
    }
    const double sigma = std::sqrt(candidate->line.start_covariance.trace());
    EXPECT_LT(sigma, 0.01);
    EXPECT_LT(distanceFromLine(candidate->line.start_world, start, end), 3.0 * sigma + 1e-3);
    EXPECT_LT(distanceFromLine(candidate->line.end_world, start, end), 3.0 * sigma + 1e-3);
  }
  // The post's placements on the wall move 0.43 m per metre driven: each
  // starts a track of its own.
  EXPECT_GE(tracks.trackCount(), 3u + 8u);
}

TEST_F(SurfaceLineTracksTest, TwoViewsAreTooFew) {
  SurfaceLineTracks tracks(SurfaceLineTrackOptions{});
  drive(tracks, 2);
  EXPECT_TRUE(tracks.candidates().empty());
}

TEST_F(SurfaceLineTracksTest, RobotsAreCounted) {
  SurfaceLineTracks tracks(SurfaceLineTrackOptions{});
  drive(tracks, 4, "r1");
  drive(tracks, 4, "r2");
  const std::vector<LineCandidate> candidates = tracks.candidates();
  ASSERT_EQ(candidates.size(), 3u);
  EXPECT_EQ(candidates.front().robots, 2);
  EXPECT_EQ(candidates.front().views, 8);
}

}  // namespace
}  // namespace lineloc

// A pass's learning past a wall: the window's three edges become lines, the
// eave (a model line the frames' visible lines do not list) is recognised as
// the model's and the post as nothing; a known line in view is expected;
// forgetting stale tracks drops the post's lone views and keeps the lines.
#include <gtest/gtest.h>

#include "backbone/enrichment/line_learner.h"
#include "wall_drive.h"

namespace lineloc {
namespace {

using namespace wall_drive;

const Plane kWall{-Eigen::Vector3d::UnitX(), -kWall_x};

ModelSegment eave() {
  ModelSegment line;
  line.id = 1;
  line.start_world = kEaveStart;
  line.end_world = kEaveEnd;
  return line;
}

class LineLearnerTest : public ::testing::Test {
 protected:
  LineLearnerTest() : scene_(wallFaces(), {kBuilding}) {}

  // Frames from y = 0, 0.5, ..., one a second, as the fixes placed them.
  void drive(LineLearner& learner, int frames, int first = 0) {
    for (int k = first; k < first + frames; ++k) {
      EnrichmentFrame frame = frameAt(cameraAt(0.5 * k), 0.5, random_);
      frame.stamp_ns = 1'000'000'000LL * k;
      frame.visible.clear();
      learner.observe(frame, scene_);
    }
  }

  OcclusionScene scene_;
  std::mt19937 random_{5};
};

TEST_F(LineLearnerTest, LearnsTheWindowsEdgesAndExpectsTheKnownLineInView) {
  LineLearner learner({{9, kWindowTopStart, kWindowTopEnd, kWall}}, LineLearnerOptions{});
  drive(learner, 12);
  EXPECT_EQ(learner.counts().frames, 12);
  EXPECT_EQ(learner.counts().segments, 5 * 12);
  EXPECT_GT(learner.counts().on_surface, 3 * 12);
  const LearntPass pass = learner.finish({eave()});
  ASSERT_EQ(pass.lines.size(), 3u);
  EXPECT_EQ(pass.model_lines_seen, 1);
  for (const LineCandidate& line : pass.lines) {
    EXPECT_EQ(line.building_id, kBuilding);
    EXPECT_GT(std::abs(line.line.start_world.z() - kEaveStart.z()), 1.0);  // not the eave
  }
  ASSERT_EQ(pass.expected.size(), 1u);
  EXPECT_EQ(pass.expected[0].id, 9);
  EXPECT_EQ(pass.expected[0].expected_at_ns, 11'000'000'000LL);
}

TEST_F(LineLearnerTest, ForgettingStaleTracksKeepsTheLinesAndDropsTheLoneViews) {
  LineLearner learner({}, LineLearnerOptions{});
  drive(learner, 12);
  // Every view placed is kept (fewer than max_views per track). The post's
  // placements on the wall move 0.2 m between frames: each is a track alone.
  const size_t held = static_cast<size_t>(learner.counts().on_surface);
  EXPECT_EQ(learner.heldViews(), held);
  learner.forgetStaleTracks(0);
  EXPECT_EQ(learner.heldViews(), held);
  const size_t lines = learner.finish({eave()}).lines.size();
  learner.forgetStaleTracks(12'000'000'000LL);
  EXPECT_EQ(learner.heldViews(), held - 12u);
  EXPECT_EQ(learner.finish({eave()}).lines.size(), lines);
}

}  // namespace
}  // namespace lineloc

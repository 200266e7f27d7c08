#include "segment_precision_recall.h"

#include <gtest/gtest.h>

namespace lineloc::testing {
namespace {

const Eigen::AlignedBox2d kRegion(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(200.0, 200.0));

Segment2d segment(double x1, double y1, double x2, double y2) {
  return {{x1, y1}, {x2, y2}};
}

TEST(ScoreCoverage, IdenticalSetsScoreOne) {
  const std::vector<Segment2d> labels = {segment(10, 10, 110, 10), segment(50, 20, 50, 120)};
  const CoverageScore score = scoreCoverage(labels, labels, kRegion);
  EXPECT_DOUBLE_EQ(score.precision, 1.0);
  EXPECT_DOUBLE_EQ(score.recall, 1.0);
  EXPECT_DOUBLE_EQ(score.labelled_length_px, 200.0);
  EXPECT_EQ(score.labelled_segments, 2);
  EXPECT_EQ(score.detected_segments, 2);
}

TEST(ScoreCoverage, CountsTheLengthThatIsNear) {
  const std::vector<Segment2d> labels = {segment(0, 50, 100, 50)};
  // Half the label, 2 px beside it (within 3 px), and a piece far from it.
  const std::vector<Segment2d> detected = {segment(0, 52, 50, 52), segment(0, 150, 50, 150)};
  const CoverageScore score = scoreCoverage(labels, detected, kRegion);
  // The 50 samples beside it, and 2 past its end that are within 3 px of it
  // (1 px samples at 50.5 and 51.5: sqrt(1.5^2 + 2^2) = 2.5 px).
  EXPECT_NEAR(score.recall, 0.52, 1e-12);
  EXPECT_NEAR(score.precision, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(score.detected_length_px, 100.0);
}

TEST(ScoreCoverage, IgnoresHowALineIsCut) {
  const std::vector<Segment2d> labels = {segment(0, 50, 100, 50)};
  const std::vector<Segment2d> detected = {segment(0, 50, 40, 50), segment(40, 50, 100, 50)};
  const CoverageScore score = scoreCoverage(labels, detected, kRegion);
  EXPECT_DOUBLE_EQ(score.recall, 1.0);
  EXPECT_DOUBLE_EQ(score.precision, 1.0);
}

TEST(ScoreCoverage, RejectsFarOrTurnedSegments) {
  const std::vector<Segment2d> labels = {segment(0, 50, 100, 50)};
  const CoverageOptions options;  // 3 px, 5 degrees
  const double turn = std::tan(10.0 * M_PI / 180.0);
  for (const Segment2d& wrong : {segment(0, 54, 100, 54),  // 4 px off
                                 segment(0, 50 - 50 * turn, 100, 50 + 50 * turn)}) {
    const CoverageScore score = scoreCoverage(labels, {wrong}, kRegion, options);
    EXPECT_LT(score.recall, 0.1);
    EXPECT_LT(score.precision, 0.1);
  }
}

TEST(ScoreCoverage, ClipsToTheRegionAndDropsShortSegments) {
  const Eigen::AlignedBox2d region(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(100.0, 100.0));
  const std::vector<Segment2d> labels = {segment(50, 50, 150, 50)};  // half inside
  // Inside only 15 px (below the 20 px minimum), and one wholly outside.
  const std::vector<Segment2d> detected = {segment(85, 60, 115, 60), segment(120, 50, 200, 50)};
  const CoverageScore score = scoreCoverage(labels, detected, region);
  EXPECT_DOUBLE_EQ(score.labelled_length_px, 50.0);
  EXPECT_EQ(score.detected_segments, 0);
  EXPECT_DOUBLE_EQ(score.recall, 0.0);
  EXPECT_DOUBLE_EQ(score.precision, 0.0);
}

TEST(ScoreEndpoints, MatchesEitherOrderOneToOne) {
  const std::vector<Segment2d> labels = {segment(10, 10, 110, 10), segment(10, 100, 10, 190)};
  // The first label reversed and 3 px short, twice; the second cut in two.
  const std::vector<Segment2d> detected = {segment(107, 11, 10, 10), segment(107, 11, 10, 10),
                                           segment(10, 100, 10, 140), segment(10, 140, 10, 190)};
  const EndpointScore score = scoreEndpoints(labels, detected, kRegion);
  EXPECT_EQ(score.matched, 1);
  EXPECT_DOUBLE_EQ(score.recall, 0.5);
  EXPECT_DOUBLE_EQ(score.precision, 0.25);
}

TEST(ScoreEndpoints, HonoursTheEndpointTolerance) {
  const std::vector<Segment2d> labels = {segment(10, 10, 110, 10)};
  const std::vector<Segment2d> detected = {segment(10, 10, 104, 10)};  // 6 px short
  EXPECT_EQ(scoreEndpoints(labels, detected, kRegion).matched, 0);
  EndpointOptions loose;
  loose.max_endpoint_distance_px = 8.0;
  EXPECT_EQ(scoreEndpoints(labels, detected, kRegion, loose).matched, 1);
}

TEST(ScorePrecisionRecall, EmptySetsScoreZero) {
  const std::vector<Segment2d> labels = {segment(10, 10, 110, 10)};
  EXPECT_DOUBLE_EQ(scoreCoverage(labels, {}, kRegion).precision, 0.0);
  EXPECT_DOUBLE_EQ(scoreCoverage(labels, {}, kRegion).recall, 0.0);
  EXPECT_DOUBLE_EQ(scoreEndpoints({}, labels, kRegion).recall, 0.0);
  EXPECT_DOUBLE_EQ(scoreEndpoints({}, labels, kRegion).precision, 0.0);
}

}  // namespace
}  // namespace lineloc::testing

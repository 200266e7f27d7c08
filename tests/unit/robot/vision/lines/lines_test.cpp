#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "robot/vision/lines/collinear_merger.h"
#include "robot/vision/lines/endpoint_snapper.h"
#include "robot/vision/lines/line_moments.h"
#include "robot/vision/lines/split_and_merge.h"

namespace lineloc {
namespace {

std::vector<Eigen::Vector2f> pointsOnLine(const Eigen::Vector2f& from, const Eigen::Vector2f& to,
                                          int count, float noise_sigma, std::mt19937& random) {
  std::normal_distribution<float> noise(0.0f, noise_sigma);
  const Eigen::Vector2f d = (to - from).normalized();
  const Eigen::Vector2f n(-d.y(), d.x());
  std::vector<Eigen::Vector2f> points;
  for (int i = 0; i < count; ++i) {
    const float t = static_cast<float>(i) / (count - 1);
    points.push_back(from + t * (to - from) + noise(random) * n);
  }
  return points;
}

TEST(LineMoments, FitsAndReportsTooFewPointsOrDegenerateInput) {
  PointMoments moments;
  moments.add({1.0f, 2.0f});
  moments.add({3.0f, 4.0f});
  EXPECT_EQ(fitLine(moments, {}).status, LineFitStatus::kTooFewPoints);
  PointMoments same;
  for (int i = 0; i < 5; ++i)
    same.add({7.0f, 7.0f});
  EXPECT_EQ(fitLine(same, {}).status, LineFitStatus::kDegenerate);
  moments.add({5.0f, 6.0f});
  const LineFit fit = fitLine(moments, {});
  ASSERT_EQ(fit.status, LineFitStatus::kOk);
  EXPECT_NEAR(std::abs(fit.direction.dot(Eigen::Vector2d(1, 1).normalized())), 1.0, 1e-9);
  EXPECT_NEAR(fit.distance({3.0, 4.0}), 0.0, 1e-9);
  PointMoments last;
  last.add({5.0f, 6.0f});
  EXPECT_EQ(fitLine(moments - last, {}).status, LineFitStatus::kTooFewPoints);
}

TEST(LineMoments, RunningSumsGiveTheMomentsOfAnyRun) {
  std::mt19937 random(5);
  const std::vector<Eigen::Vector2f> points = pointsOnLine({3, 4}, {200, 90}, 50, 0.3f, random);
  std::vector<PointMoments> prefix;
  cumulativeMoments(points, prefix);
  ASSERT_EQ(prefix.size(), points.size() + 1);
  PointMoments run;
  for (int i = 7; i < 31; ++i) {
    run.add(points[i]);
  }
  const PointMoments from_prefix = prefix[31] - prefix[7];
  EXPECT_EQ(from_prefix.n, run.n);
  EXPECT_NEAR(from_prefix.sxx, run.sxx, 1e-9 * run.sxx);
  EXPECT_NEAR(from_prefix.sxy, run.sxy, 1e-9 * run.sxy);
  const LineFit a = fitLine(from_prefix, {}), b = fitLine(run, {});
  EXPECT_NEAR(a.direction.dot(b.direction), 1.0, 1e-12);
  EXPECT_NEAR(a.distance(b.centroid), 0.0, 1e-9);
}

// With independent points (points_per_sample = 1) the reported sigmas are
// the true ones: over 400 trials the RMS offset and angle errors are within
// 15 % of the predicted sigma (the RMS of 400 normal samples is within
// 3 x 1/sqrt(2 x 400) = 11 % of sigma with 99.7 % probability).
TEST(LineMoments, ReportedSigmasMatchTheScatterOfTheFit) {
  std::mt19937 random(3);
  const LineFitOptions options{1.0, 1e-6};
  const Eigen::Vector2f from(10.0f, 20.0f), to(90.0f, 50.0f);
  const Eigen::Vector2d truth_direction = (to - from).cast<double>().normalized();
  const Eigen::Vector2d centre = (0.5f * (from + to)).cast<double>();
  double offset_sq = 0.0, angle_sq = 0.0, predicted_offset = 0.0, predicted_angle = 0.0;
  const int trials = 400;
  for (int trial = 0; trial < trials; ++trial) {
    PointMoments moments;
    for (const Eigen::Vector2f& p : pointsOnLine(from, to, 60, 0.3f, random))
      moments.add(p);
    const LineFit fit = fitLine(moments, options);
    offset_sq += std::pow(fit.distance(centre), 2);
    angle_sq += std::pow(std::asin(fit.direction.x() * truth_direction.y() -
                                   fit.direction.y() * truth_direction.x()),
                         2);
    predicted_offset += fit.sigma_offset_px / trials;
    predicted_angle += fit.sigma_angle_rad / trials;
  }
  EXPECT_NEAR(std::sqrt(offset_sq / trials), predicted_offset, 0.15 * predicted_offset);
  EXPECT_NEAR(std::sqrt(angle_sq / trials), predicted_angle, 0.15 * predicted_angle);
}

TEST(SplitAndMerge, SplitsAPolylineAtItsCornersOnly) {
  std::mt19937 random(4);
  std::vector<Eigen::Vector2f> points = pointsOnLine({0, 0}, {60, 0}, 61, 0.1f, random);
  const std::vector<Eigen::Vector2f> second = pointsOnLine({60, 0}, {60, 40}, 41, 0.1f, random);
  points.insert(points.end(), second.begin() + 1, second.end());
  SplitAndMerge split_and_merge(1.0, 5);
  std::vector<PointRange> pieces;
  split_and_merge.approximate(points, pieces);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(points[pieces[0].end - 1].x(), 60.0f, 1.5f);
  EXPECT_NEAR(points[pieces[1].begin].y(), 0.0f, 1.5f);

  std::vector<PointRange> straight;
  split_and_merge.approximate(pointsOnLine({0, 0}, {100, 30}, 101, 0.2f, random), straight);
  EXPECT_EQ(straight.size(), 1u);
}

LineSegment segmentOf(const std::vector<Eigen::Vector2f>& points) {
  LineSegment segment;
  for (const Eigen::Vector2f& p : points) {
    segment.moments.add(p);
    segment.gradient_sum += Eigen::Vector2d(0.0, 10.0);
  }
  segment.fit = fitLine(segment.moments, {});
  segment.setExtent(points.front().cast<double>(), points.back().cast<double>());
  return segment;
}

TEST(CollinearMerger, BridgesAnOccluderButNotARowOfWindows) {
  std::mt19937 random(6);
  // A 200 px edge cut by a 15 px pole: one segment again.
  std::vector<LineSegment> occluded = {
      segmentOf(pointsOnLine({0, 100}, {90, 100.5f}, 91, 0.1f, random)),
      segmentOf(pointsOnLine({105, 100.5f}, {200, 101}, 96, 0.1f, random))};
  CollinearMerger merger({});
  merger.merge(occluded, {});
  ASSERT_EQ(occluded.size(), 1u);
  EXPECT_NEAR(occluded[0].length(), 200.0, 1.0);
  // Window tops 40 px wide, 30 px apart: the gap is large for their length.
  std::vector<LineSegment> windows = {
      segmentOf(pointsOnLine({0, 50}, {40, 50}, 41, 0.1f, random)),
      segmentOf(pointsOnLine({70, 50}, {110, 50}, 41, 0.1f, random))};
  merger.merge(windows, {});
  EXPECT_EQ(windows.size(), 2u);
  // Opposite polarity never merges.
  std::vector<LineSegment> flipped = {
      segmentOf(pointsOnLine({0, 10}, {90, 10}, 91, 0.1f, random)),
      segmentOf(pointsOnLine({95, 10}, {190, 10}, 96, 0.1f, random))};
  flipped[1].gradient_sum = -flipped[1].gradient_sum;
  merger.merge(flipped, {});
  EXPECT_EQ(flipped.size(), 2u);
}

// Two lines end near the corner of a third: its end point snaps to the one
// whose end is closest to the intersection, though the other comes first in x.
TEST(EndpointSnapper, SnapsTheClosestPairFirst) {
  std::mt19937 random(7);
  std::vector<LineSegment> segments = {
      segmentOf(pointsOnLine({0, 50}, {97, 50}, 98, 0.0f, random)),   // ends 3 px short
      segmentOf(pointsOnLine({95, 0}, {95, 44}, 45, 0.0f, random)),   // 5 px from x = (95, 50)
      segmentOf(pointsOnLine({101, 48}, {101, 0}, 49, 0.0f, random))  // 2 px from (101, 50)
  };
  EndpointSnapper snapper({});
  snapper.snap(segments);
  ASSERT_EQ(snapper.junctions().size(), 1u);
  EXPECT_LT((snapper.junctions()[0].position - Eigen::Vector2d(101.0, 50.0)).norm(), 1e-6);
  EXPECT_LT((segments[0].end() - Eigen::Vector2d(101.0, 50.0)).norm(), 1e-6);
  EXPECT_LT((segments[2].end() - Eigen::Vector2d(101.0, 50.0)).norm(), 1e-6);
  EXPECT_LT((segments[1].end() - Eigen::Vector2d(95.0, 44.0)).norm(), 1e-6);
}

}  // namespace
}  // namespace lineloc

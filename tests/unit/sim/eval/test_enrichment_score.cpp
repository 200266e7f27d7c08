#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/eval/enrichment_score.h"

namespace lineloc {
namespace {

// A window's sides, 1.2 m apart, 1.5 m high, on the wall x = 10.
const std::vector<FacadeEdge> kWindow = {{1, {10.0, 5.0, 2.0}, {10.0, 5.0, 3.5}},
                                         {1, {10.0, 6.2, 2.0}, {10.0, 6.2, 3.5}}};

TEST(EnrichmentScore, ALineScoresItsPointsMeanDistanceToTheNearestEdges) {
  const std::vector<LearntLine> lines = {
      {{10.0, 5.03, 2.1}, {10.0, 5.03, 3.4}},  // 3 cm off the left side
      {{10.0, 6.2, 2.5}, {10.0, 6.3, 3.0}},    // 0 to 10 cm off the right: 5 cm on average
      {{10.0, 5.6, 2.0}, {10.0, 5.6, 3.5}},    // between them, 0.6 m from each
      {{30.0, 5.0, 2.0}, {30.0, 5.0, 3.5}}};   // nowhere near
  const EnrichmentScore score = scoreEnrichment(lines, kWindow);
  ASSERT_EQ(score.distances_m.size(), 4u);
  EXPECT_NEAR(score.distances_m[0], 0.03, 1e-9);
  EXPECT_NEAR(score.distances_m[1], 0.05, 1e-3);
  EXPECT_NEAR(score.distances_m[2], 0.6, 1e-9);
  EXPECT_TRUE(std::isinf(score.distances_m[3]));
  EXPECT_EQ(score.lines, 4);
  EXPECT_NEAR(score.median_distance_m, 0.6, 1e-9);
  EXPECT_DOUBLE_EQ(score.within_fraction, 0.5);
}

TEST(EnrichmentScore, ALineAlongARowOfPiecesIsOnThem) {
  // A sign's top edge in three pieces, one per bay.
  const std::vector<FacadeEdge> pieces = {{1, {10.0, 0.0, 2.8}, {10.0, 3.0, 2.8}},
                                          {1, {10.0, 3.0, 2.8}, {10.0, 6.0, 2.8}},
                                          {1, {10.0, 6.0, 2.8}, {10.0, 9.0, 2.8}}};
  const EnrichmentScore score = scoreEnrichment({{{10.0, 0.5, 2.82}, {10.0, 8.5, 2.82}}}, pieces);
  EXPECT_NEAR(score.median_distance_m, 0.02, 1e-9);
}

TEST(EnrichmentScore, LinesOnTheStreetsClutterAreCounted) {
  // A parked car 1.5 m in front of the wall; a line along its roof edge and
  // the window's side on the wall.
  const std::vector<ClutterBox> clutter = {
      {1'000'000, "car",
       Eigen::AlignedBox3d(Eigen::Vector3d(7.0, 3.0, 0.0), Eigen::Vector3d(8.5, 7.5, 1.5))}};
  const EnrichmentScore score = scoreEnrichment(
      {{{8.5, 3.5, 1.5}, {8.5, 7.0, 1.5}}, {{10.0, 5.0, 2.0}, {10.0, 5.0, 3.5}}}, kWindow, clutter);
  EXPECT_EQ(score.on_clutter, 1);
  EXPECT_NEAR(score.distances_m[1], 0.0, 1e-9);
}

TEST(EnrichmentScore, LearntLinesAreReadAndAMalformedRowIsNamed) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("learnt_lines_" + std::to_string(getpid()) + ".txt");
  std::ofstream(path) << "# header\n1 2 3 4 5 6 17 8 1 0.01 0.01\n";
  const std::vector<LearntLine> lines = readLearntLines(path.string());
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].end, Eigen::Vector3d(4, 5, 6));
  for (const std::string row : {"1 2 3 4 5", "1 2 3 4 5 inf", "a 2 3 4 5 6"}) {
    std::ofstream(path) << "1 2 3 4 5 6\n" << row << "\n";
    try {
      readLearntLines(path.string());
      ADD_FAILURE() << "accepted '" << row << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string() + ":2"), std::string::npos)
          << error.what();
    }
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace lineloc

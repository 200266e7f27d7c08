// A learnt line on a model line is that line seen again; one beside it, across
// it or past its end is new.
#include <gtest/gtest.h>

#include "backbone/enrichment/known_lines.h"

namespace lineloc {
namespace {

LineCandidate candidate(const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
  LineCandidate learnt;
  learnt.line.start_world = start;
  learnt.line.end_world = end;
  learnt.line.direction = (end - start).normalized();
  return learnt;
}

// A building's corner: vertical at (10, 0) from 0 to 6 m.
const std::vector<ModelSegment> kCorner = {{1, 1, {10.0, 0.0, 0.0}, {10.0, 0.0, 6.0}}};

TEST(KnownLines, OnlyLinesTheModelLacksAreKept) {
  const std::vector<LineCandidate> candidates = {
      candidate({10.0, 0.05, 0.5}, {10.0, 0.04, 2.5}),  // the corner, 5 cm off
      candidate({10.0, 0.2, 0.5}, {10.0, 0.2, 2.5}),    // a window's side beside it
      candidate({10.0, -1.0, 3.0}, {10.0, 1.0, 3.0}),   // across it
      candidate({10.0, 0.0, 6.5}, {10.0, 0.0, 8.0}),    // above its end
  };
  const std::vector<LineCandidate> kept = withoutModelLines(candidates, kCorner);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0].line.start_world, candidates[1].line.start_world);
  EXPECT_EQ(kept[1].line.start_world, candidates[2].line.start_world);
  EXPECT_EQ(kept[2].line.start_world, candidates[3].line.start_world);
}

}  // namespace
}  // namespace lineloc

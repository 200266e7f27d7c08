#include "robot/inertial/navigation_state.h"

#include <gtest/gtest.h>

namespace lineloc {
namespace {

// The 15-state covariance with entry (i, j) = 100 i + j: every block tells
// where it came from.
ErrorCovariance numberedCovariance() {
  ErrorCovariance covariance;
  for (int i = 0; i < covariance.rows(); ++i) {
    for (int j = 0; j < covariance.cols(); ++j) {
      covariance(i, j) = 100.0 * i + j;
    }
  }
  return covariance;
}

bool isPoseIndex(int k) {
  return (k >= kPosition && k < kPosition + 3) || (k >= kAttitude && k < kAttitude + 3);
}

TEST(PoseBlock, ReadsThePositionAndAttitudeRowsAndColumns) {
  const Matrix6d pose = poseBlock(numberedCovariance());
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const int row = i < 3 ? kPosition + i : kAttitude + i - 3;
      const int col = j < 3 ? kPosition + j : kAttitude + j - 3;
      EXPECT_EQ(pose(i, j), 100.0 * row + col) << i << "," << j;
    }
  }
}

TEST(PoseBlock, WritingItBackChangesNothingElse) {
  const ErrorCovariance before = numberedCovariance();
  const Matrix6d pose = Matrix6d::Constant(-1.0);
  ErrorCovariance after = before;
  setPoseBlock(pose, after);
  EXPECT_EQ(poseBlock(after), pose);
  for (int i = 0; i < after.rows(); ++i) {
    for (int j = 0; j < after.cols(); ++j) {
      if (!(isPoseIndex(i) && isPoseIndex(j))) {
        EXPECT_EQ(after(i, j), before(i, j)) << i << "," << j;
      }
    }
  }
}

}  // namespace
}  // namespace lineloc

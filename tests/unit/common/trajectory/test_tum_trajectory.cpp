#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/trajectory/tum_trajectory.h"
#include "tests/unit/common/trajectory/log_line_checks.h"

namespace lineloc {
namespace {

TEST(TumTrajectory, WriteThenReadKeepsNanosecondStampsAndPoses) {
  const std::string path = testing::temporaryPath("tum_roundtrip");
  StampedPose a;
  a.stamp_ns = 1'403'636'579'763'555'584;  // EuRoC-sized stamp: beyond double precision in ns
  a.pose.translation() = Eigen::Vector3d(1.25, -2.5, 3.0);
  a.pose.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  StampedPose b;
  b.stamp_ns = 5;
  {
    TumWriter writer(path);
    writer.write(a);
    writer.write(b);
  }
  const std::vector<StampedPose> poses = readTumFile(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].stamp_ns, a.stamp_ns);
  EXPECT_EQ(poses[1].stamp_ns, 5);
  EXPECT_TRUE(poses[0].pose.translation().isApprox(a.pose.translation(), 1e-6));
  EXPECT_TRUE(poses[0].pose.linear().isApprox(a.pose.linear(), 1e-8));
  std::filesystem::remove(path);
}

TEST(TumTrajectory, FormatsSecondsWithNineDecimals) {
  StampedPose pose;
  pose.stamp_ns = 12'000'000'001;
  EXPECT_EQ(formatTumLine(pose).substr(0, 12), "12.000000001");
}

TEST(TumTrajectory, MalformedLinesNameTheLine) {
  const char* bad_lines[] = {
      "1.0 1 2 3 0 0 0",                    // seven fields
      "1.0 1 2 3 0 0 0 1 9",                // nine fields
      "abc 1 2 3 0 0 0 1",                  // time not a number
      "1.0 1 nan 3 0 0 0 1",                // non-finite
      "1.0 1 2 3 0 0 0 5",                  // quaternion not unit
      "1.0000000001 1 2 3 0 0 0 1",         // sub-nanosecond digits
      "1403636579763555584 1 2 3 0 0 0 1",  // nanoseconds given as seconds: beyond int64
      "--5 1 2 3 0 0 0 1",                  // two signs
      "1-2 1 2 3 0 0 0 1",                  // sign inside
  };
  for (const char* line : bad_lines) {
    try {
      parseTumLine(line, "poses.tum:7");
      ADD_FAILURE() << "accepted: " << line;
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("poses.tum:7"), std::string::npos) << line;
    }
  }
}

TEST(TumTrajectory, ReadReportsFileAndLineNumber) {
  const std::string path = testing::temporaryPath("tum_bad");
  std::ofstream(path) << "# comment\n\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0\n";
  try {
    readTumFile(path);
    FAIL() << "malformed file accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path + ":4"), std::string::npos) << error.what();
  }
  std::filesystem::remove(path);
  EXPECT_THROW(readTumFile(path), std::runtime_error);
}

}  // namespace
}  // namespace lineloc

// The pose log with covariance: round trip, and malformed lines named.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/trajectory/pose_covariance_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "tests/unit/common/trajectory/log_line_checks.h"

namespace lineloc {
namespace {

StampedPoseWithCovariance samplePose() {
  StampedPoseWithCovariance stamped;
  stamped.stamp_ns = 1'776'159'005'033'333'333;
  stamped.pose.pose.translation() = Eigen::Vector3d(22.3, -69.06, 1.68);
  stamped.pose.pose.linear() =
      Eigen::AngleAxisd(-1.2, Eigen::Vector3d(0.2, 1, -0.4).normalized()).toRotationMatrix();
  const Matrix6d square = Matrix6d::Random();
  stamped.pose.covariance = 1e-4 * (square * square.transpose()) + 1e-6 * Matrix6d::Identity();
  return stamped;
}

TEST(PoseCovarianceLog, WriteThenReadKeepsPoseAndCovariance) {
  const std::string path = testing::temporaryPath("pose_covariance_log");
  const StampedPoseWithCovariance written = samplePose();
  {
    PoseCovarianceLogWriter writer(path);
    writer.write(written);
    writer.write(written);
  }
  const std::vector<StampedPoseWithCovariance> read = readPoseCovarianceLog(path);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].stamp_ns, written.stamp_ns);
  EXPECT_TRUE(read[0].pose.pose.isApprox(written.pose.pose, 1e-6));
  EXPECT_TRUE(read[0].pose.covariance.isApprox(written.pose.covariance, 1e-8));
  std::filesystem::remove(path);
}

TEST(PoseCovarianceLog, TheFirstEightFieldsAreATumLine) {
  const StampedPoseWithCovariance stamped = samplePose();
  EXPECT_EQ(formatPoseCovarianceLine(stamped).rfind(
                formatTumLine({stamped.stamp_ns, stamped.pose.pose}), 0),
            0u);
}

// A good line with field `index` (0-based) replaced.
std::string withField(int index, const std::string& value) {
  return testing::withField(formatPoseCovarianceLine(samplePose()), index, value);
}

void expectError(const std::string& line, const std::string& expected) {
  testing::expectParseError(parsePoseCovarianceLine, line, expected);
}

TEST(PoseCovarianceLog, MalformedLinesNameTheLineAndTheField) {
  expectError("", "expected 29 fields");
  expectError(formatPoseCovarianceLine(samplePose()) + " 0.5", "got 30");
  expectError(withField(0, "yesterday"), "log.txt:3");
  expectError(withField(2, "north"), "expected 8 numbers");
  expectError(withField(7, "3.0"), "quaternion norm");
  expectError(withField(8, "inf"), "covariance entry 'inf'");
  expectError(withField(14, "wide"), "covariance entry 'wide'");
  expectError(withField(8, "-1e-4"), "not positive definite");
}

TEST(PoseCovarianceLog, MissingFileIsNamed) {
  try {
    readPoseCovarianceLog("/nonexistent/states.txt");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/states.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace lineloc

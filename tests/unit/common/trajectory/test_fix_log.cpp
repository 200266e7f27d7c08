#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/trajectory/fix_log.h"
#include "common/trajectory/tum_trajectory.h"
#include "tests/unit/common/trajectory/log_line_checks.h"

namespace lineloc {
namespace {

LoggedFix sampleFix() {
  LoggedFix fix;
  fix.stamp_ns = 1'700'000'009'533'333'238;
  fix.T_world_camera.pose.translation() = Eigen::Vector3d(8.18, -79.75, 1.68);
  fix.T_world_camera.pose.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix<double, 6, 6> square = Eigen::Matrix<double, 6, 6>::Random();
  fix.T_world_camera.covariance =
      1e-4 * (square * square.transpose()) + 1e-6 * Eigen::Matrix<double, 6, 6>::Identity();
  fix.status = "ok";
  fix.inliers = 17;
  fix.model_lines = 412;
  fix.residual_rms_px = 1.25;
  fix.latency_ms = 4.75;
  fix.front_end_ms = 1.5;
  fix.to_backbone_ms = -0.25;
  fix.backbone_ms = 2.25;
  fix.back_ms = 1.25;
  return fix;
}

TEST(FixLog, WriteThenReadKeepsPoseCovarianceAndCounts) {
  const std::string path = testing::temporaryPath("fix_log_roundtrip");
  const LoggedFix written = sampleFix();
  LoggedFix not_ok = written;
  not_ok.status = "too_few_matches";
  {
    FixLogWriter writer(path);
    writer.write(written);
    writer.write(not_ok);
  }
  const std::vector<LoggedFix> fixes = readFixLog(path);
  ASSERT_EQ(fixes.size(), 2u);
  EXPECT_EQ(fixes[0].stamp_ns, written.stamp_ns);
  EXPECT_TRUE(fixes[0].T_world_camera.pose.isApprox(written.T_world_camera.pose, 1e-6));
  EXPECT_TRUE(fixes[0].T_world_camera.covariance.isApprox(written.T_world_camera.covariance, 1e-8));
  EXPECT_EQ(fixes[0].status, "ok");
  EXPECT_EQ(fixes[0].inliers, 17u);
  EXPECT_EQ(fixes[0].model_lines, 412u);
  EXPECT_DOUBLE_EQ(fixes[0].residual_rms_px, 1.25);
  EXPECT_DOUBLE_EQ(fixes[0].latency_ms, 4.75);
  EXPECT_DOUBLE_EQ(fixes[0].front_end_ms, 1.5);
  EXPECT_DOUBLE_EQ(fixes[0].to_backbone_ms, -0.25);
  EXPECT_DOUBLE_EQ(fixes[0].backbone_ms, 2.25);
  EXPECT_DOUBLE_EQ(fixes[0].back_ms, 1.25);
  EXPECT_EQ(fixes[1].status, "too_few_matches");
  std::filesystem::remove(path);
}

TEST(FixLog, TheFirstEightFieldsAreATumLine) {
  const std::string line = formatFixLogLine(sampleFix());
  EXPECT_EQ(line.rfind(formatTumLine({sampleFix().stamp_ns, sampleFix().T_world_camera.pose}), 0),
            0u);
}

// A good line with field `index` (0-based) replaced.
std::string withField(int index, const std::string& value) {
  return testing::withField(formatFixLogLine(sampleFix()), index, value);
}

void expectError(const std::string& line, const std::string& expected) {
  testing::expectParseError(parseFixLogLine, line, expected);
}

TEST(FixLog, MalformedLinesNameTheLineAndTheField) {
  expectError("", "expected 38 fields");
  expectError(formatFixLogLine(sampleFix()) + " 0.5", "got 39");
  expectError(withField(4, "2.0"), "quaternion norm");
  expectError(withField(8, "OK"), "status 'OK'");
  expectError(withField(9, "-3"), "inliers '-3'");
  expectError(withField(10, "4.5"), "model_lines '4.5'");
  expectError(withField(11, "-1"), "residual_rms_px is negative");
  expectError(withField(11, "nan"), "residual_rms_px 'nan'");
  expectError(withField(12, "-0.5"), "latency_ms is negative");
  expectError(withField(12, "soon"), "latency_ms 'soon'");
  expectError(withField(13, "-0.1"), "front_end_ms is negative");
  expectError(withField(14, "nan"), "to_backbone_ms 'nan'");
  expectError(withField(15, "-2"), "backbone_ms is negative");
  expectError(withField(16, "later"), "back_ms 'later'");
  expectError(withField(17, "inf"), "covariance entry 'inf'");
  expectError(withField(17, "-1e-4"), "not positive definite");
}

TEST(FixLog, MissingFileIsNamed) {
  try {
    readFixLog("/nonexistent/fixes.txt");
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/fixes.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace lineloc

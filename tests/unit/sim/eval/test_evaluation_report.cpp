// lineloc-eval's report on a drive whose estimate, fixes and truth are known:
// the first OK fix's time, the fixes beyond three sigma and the accuracy from
// the first fix on must be the ones built in.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "common/trajectory/fix_log.h"
#include "sim/eval/evaluation_report.h"
#include "tests/unit/sim/eval/circle_drive.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

class EvaluationReport : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("evaluation_report_" + std::to_string(getpid()));
    fs::create_directories(folder_);
    config_.ground_truth = (folder_ / "truth.tum").string();
    config_.estimate = (folder_ / "estimate.tum").string();
    config_.fix_log = (folder_ / "fixes.txt").string();
    config_.plot = (folder_ / "plot.png").string();
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_;
  EvaluationReportConfig config_;
};

// A 20 s circle drive from t = 1 s: the estimate is the truth 2 cm off in x
// from the first OK fix on (t = 5 s; answered 40 ms after its exposure) and
// 1 m off before it; one OK fix is 0.3 m off with a 1 cm sigma.
TEST_F(EvaluationReport, ReportsTheFirstFixAndTheAccuracyFromItOn) {
  const std::vector<StampedPose> truth = circleDrive(30.0, 20.0);
  TumWriter truth_file(config_.ground_truth);
  TumWriter estimate_file(config_.estimate);
  FixLogWriter fixes(config_.fix_log);
  constexpr int64_t kFirstOkNs = 5'000'000'000;
  for (size_t i = 0; i < truth.size(); ++i) {
    truth_file.write(truth[i]);
    StampedPose estimate = truth[i];
    const bool fixed = truth[i].stamp_ns >= kFirstOkNs;
    estimate.pose.translation().x() += fixed ? 0.02 : 1.0;
    estimate_file.write(estimate);
    LoggedFix fix;
    fix.stamp_ns = truth[i].stamp_ns;
    fix.T_world_camera.pose = estimate.pose;
    fix.T_world_camera.covariance = Matrix6d::Identity() * 0.05 * 0.05;
    fix.status = fixed ? "ok" : "too_few_matches";
    fix.latency_ms = 40.0;
    if (i == truth.size() - 10) {
      fix.T_world_camera.pose.translation().y() += 0.3;
      fix.T_world_camera.covariance = Matrix6d::Identity() * 0.01 * 0.01;
    }
    fixes.write(fix);
  }
  std::ostringstream out;
  EXPECT_EQ(runEvaluationReport(config_, out), EvaluationStatus::kOk);
  const std::string report = out.str();
  EXPECT_NE(report.find("after the first OK fix (received 4.040 s after the ground truth starts)"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("1 beyond chi2_6(0.9973)"), std::string::npos) << report;
  // From the first fix on, every position is 2 cm off: RMSE, mean, median and max.
  const size_t after = report.find("after the first OK fix");
  ASSERT_NE(after, std::string::npos) << report;
  EXPECT_NE(report.find("position                      0.0200      0.0200      0.0200      0.0200",
                        after),
            std::string::npos)
      << report.substr(after);
  EXPECT_TRUE(fs::exists(config_.plot));
}

TEST_F(EvaluationReport, NamesWhatIsMissing) {
  std::ostringstream out;
  config_.estimate.clear();
  EXPECT_THROW(runEvaluationReport(config_, out), std::runtime_error);
  config_.estimate = (folder_ / "no_such.tum").string();
  TumWriter(config_.ground_truth).write(circleDrive(30.0, 1.0).front());
  try {
    runEvaluationReport(config_, out);
    FAIL() << "a missing estimate accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("no_such.tum"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc

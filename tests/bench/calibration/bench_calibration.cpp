// Calibration of OpenCV's 13 chessboard views (opencv-doc left01..14.jpg) with
// lineloc's Zhang calibration and with cv::calibrateCamera, on the very same
// detected corners, in one run; and the homography of one view with lineloc
// and with cv::findHomography (least squares + Levenberg-Marquardt). Prints
// the median times and the ratios lineloc / OpenCV at the end.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <opencv2/calib3d.hpp>
#include <string>

#include "common/homography/homography.h"
#include "robot/calibration/chessboard_detection.h"
#include "robot/calibration/zhang_calibration.h"
#include "tests/unit/robot/calibration/opencv_baseline.h"

namespace {

const lineloc::ChessboardViews& chessboardViews() {
  static const lineloc::ChessboardViews views = lineloc::detectChessboards(
      lineloc::expandImagePattern(std::string(LINELOC_OPENCV_SAMPLE_DATA_DIR) +
                                  "/left[0-9][0-9].jpg"),
      {9, 6}, 0.025);
  return views;
}

void BM_LinelocCalibrate(benchmark::State& state) {
  const lineloc::PlanarViews& views = chessboardViews().views;
  const lineloc::CalibrationOptions options = lineloc::openCvCompatibleOptions();
  double rms_px = 0.0;
  for (auto _ : state) {
    const lineloc::CalibrationResult result = lineloc::calibrateCamera(views, options);
    rms_px = result.rms_error_px;
    benchmark::DoNotOptimize(result);
  }
  state.counters["rms_px"] = rms_px;
}

void BM_OpenCvCalibrateCamera(benchmark::State& state) {
  const lineloc::testing::OpenCvViews views = lineloc::testing::toOpenCv(chessboardViews().views);
  double rms_px = 0.0;
  for (auto _ : state) {
    rms_px = lineloc::testing::calibrateWithOpenCv(views).rms_px;
  }
  state.counters["rms_px"] = rms_px;
}

void BM_LinelocHomography(benchmark::State& state) {
  const lineloc::PlanarViews& views = chessboardViews().views;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        lineloc::estimateHomography(views.model_points, views.image_points.front()));
  }
}

void BM_OpenCvFindHomography(benchmark::State& state) {
  const lineloc::testing::OpenCvViews views = lineloc::testing::toOpenCv(chessboardViews().views);
  std::vector<cv::Point2f> model;
  for (const cv::Point3f& M : views.object_points.front()) {
    model.emplace_back(M.x, M.y);
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(cv::findHomography(model, views.image_points.front(), 0));
  }
}

constexpr int kRepetitions = 7;
BENCHMARK(BM_LinelocCalibrate)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(kRepetitions)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvCalibrateCamera)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(kRepetitions)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_LinelocHomography)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(kRepetitions)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_OpenCvFindHomography)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(kRepetitions)
    ->ReportAggregatesOnly(true);

// Collects the median real time of each benchmark for the ratio summary.
class MedianCollector : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.aggregate_name == "median") {
        medians_[run.run_name.function_name] = run.GetAdjustedRealTime();
        units_[run.run_name.function_name] = benchmark::GetTimeUnitString(run.time_unit);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  void printRatio(const std::string& lineloc, const std::string& opencv) const {
    if (medians_.count(lineloc) == 0 || medians_.count(opencv) == 0) {
      return;
    }
    std::printf("%-22s median %10.3f %s   %-26s median %10.3f %s   ratio lineloc/OpenCV %.3f\n",
                lineloc.c_str(), medians_.at(lineloc), units_.at(lineloc).c_str(), opencv.c_str(),
                medians_.at(opencv), units_.at(opencv).c_str(),
                medians_.at(lineloc) / medians_.at(opencv));
  }

 private:
  std::map<std::string, double> medians_;
  std::map<std::string, std::string> units_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  chessboardViews();
  MedianCollector reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatio("BM_LinelocCalibrate", "BM_OpenCvCalibrateCamera");
  reporter.printRatio("BM_LinelocHomography", "BM_OpenCvFindHomography");
  benchmark::Shutdown();
  return 0;
}

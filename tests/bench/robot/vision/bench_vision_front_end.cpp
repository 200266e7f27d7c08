// The robot's vision front end (lines + Förstner corners) against the line
// detectors a user would pick instead: OpenCV's LSD, ximgproc's
// FastLineDetector and EdgeDrawing (EDLines), on the same 640x480 images:
// building.jpg from opencv-doc (resized) and a synthetic street view rendered
// here (no simulator images exist yet). One core; medians of repetitions;
// a summary prints each detector's median time and segment count, and its
// time ratio to lineloc.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <stdexcept>
#include <string>

#include "robot/vision/features/feature_extractor.h"
#include "synthetic_scene.h"

namespace {

const cv::Size kImageSize(640, 480);
constexpr int kRepetitions = 9;

cv::Mat buildingImage() {
  const std::string path = std::string(LINELOC_OPENCV_EXAMPLES_DATA) + "/building.jpg";
  const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    throw std::runtime_error("cannot read " + path + " (install opencv-doc)");
  }
  cv::Mat resized;
  cv::resize(image, resized, kImageSize, 0.0, 0.0, cv::INTER_AREA);
  return resized;
}

cv::Mat streetImage() {
  lineloc::testing::SceneOptions options;
  options.size = kImageSize;
  options.supersampling = 8;
  return lineloc::testing::renderStreetView(options, 7).image;
}

const cv::Mat& image(int which) {
  static const cv::Mat building = buildingImage();
  static const cv::Mat street = streetImage();
  return which == 0 ? building : street;
}

const char* imageName(int which) {
  return which == 0 ? "building" : "street";
}

lineloc::CameraCalibration idealCamera() {
  lineloc::CameraCalibration calibration;
  calibration.camera = {500.0, 500.0, 319.5, 239.5, 0.0, kImageSize.width, kImageSize.height};
  return calibration;
}

template <typename Detect>
void run(benchmark::State& state, Detect detect) {
  const cv::Mat& grey = image(static_cast<int>(state.range(0)));
  size_t segments = 0;
  for (auto _ : state) {
    segments = detect(grey);
    benchmark::ClobberMemory();
  }
  state.counters["segments"] = static_cast<double>(segments);
  state.SetLabel(imageName(static_cast<int>(state.range(0))));
}

void BM_LinelocLinesAndCorners(benchmark::State& state) {
  lineloc::FeatureExtractor extractor(idealCamera());
  size_t corners = 0;
  run(state, [&](const cv::Mat& grey) {
    const lineloc::FrameFeatures& features = extractor.extract(grey);
    corners = features.corners.size();
    return features.segments.size();
  });
  state.counters["corners"] = static_cast<double>(corners);
}

void BM_LinelocLinesOnly(benchmark::State& state) {
  lineloc::FeatureExtractorOptions options;
  options.detect_corners = false;
  lineloc::FeatureExtractor extractor(idealCamera(), options);
  run(state, [&](const cv::Mat& grey) { return extractor.extract(grey).segments.size(); });
}

void BM_OpenCvLsd(benchmark::State& state) {
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  std::vector<cv::Vec4f> lines;
  run(state, [&](const cv::Mat& grey) {
    lsd->detect(grey, lines);
    return lines.size();
  });
}

void BM_FastLineDetector(benchmark::State& state) {
  const cv::Ptr<cv::ximgproc::FastLineDetector> fld = cv::ximgproc::createFastLineDetector();
  std::vector<cv::Vec4f> lines;
  run(state, [&](const cv::Mat& grey) {
    fld->detect(grey, lines);
    return lines.size();
  });
}

void BM_EdLines(benchmark::State& state) {
  const cv::Ptr<cv::ximgproc::EdgeDrawing> ed = cv::ximgproc::createEdgeDrawing();
  std::vector<cv::Vec4f> lines;
  run(state, [&](const cv::Mat& grey) {
    ed->detectEdges(grey);
    ed->detectLines(lines);
    return lines.size();
  });
}

#define LINELOC_VISION_BENCHMARK(function) \
  BENCHMARK(function)                      \
      ->DenseRange(0, 1)                   \
      ->Unit(benchmark::kMillisecond)      \
      ->Repetitions(kRepetitions)          \
      ->ReportAggregatesOnly(true)

LINELOC_VISION_BENCHMARK(BM_LinelocLinesAndCorners);
LINELOC_VISION_BENCHMARK(BM_LinelocLinesOnly);
LINELOC_VISION_BENCHMARK(BM_OpenCvLsd);
LINELOC_VISION_BENCHMARK(BM_FastLineDetector);
LINELOC_VISION_BENCHMARK(BM_EdLines);

// Keeps the console output and records each median for the summary.
class MedianRecorder : public benchmark::ConsoleReporter {
 public:
  struct Result {
    double time_ms;
    double segments;
  };
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.aggregate_name != "median") {
        continue;
      }
      const auto segments = run.counters.find("segments");
      medians[run.run_name.function_name][run.report_label] = {
          run.GetAdjustedCPUTime(), segments == run.counters.end() ? 0.0 : segments->second.value};
    }
  }
  std::map<std::string, std::map<std::string, Result>> medians;
};

void printSummary(const MedianRecorder& recorder) {
  const auto reference = recorder.medians.find("BM_LinelocLinesAndCorners");
  if (reference == recorder.medians.end()) {
    return;
  }
  fmt::print(
      "\nmedian CPU time (ms), segments, and time / lineloc lines+corners, 640x480, one core\n");
  for (const auto& [name, by_image] : recorder.medians) {
    for (const auto& [label, result] : by_image) {
      const auto lineloc = reference->second.find(label);
      const double ratio =
          lineloc == reference->second.end() ? 0.0 : result.time_ms / lineloc->second.time_ms;
      fmt::print("  {:<28} {:<9} {:8.3f} ms  {:5.0f} segments  {:6.2f}x\n", name, label,
                 result.time_ms, result.segments, ratio);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  MedianRecorder recorder;
  benchmark::RunSpecifiedBenchmarks(&recorder);
  printSummary(recorder);
  benchmark::Shutdown();
  return 0;
}

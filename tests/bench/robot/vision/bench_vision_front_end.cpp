// The robot's vision front end (lines + Förstner corners) against the line
// detectors a user would pick instead: OpenCV's LSD, ximgproc's
// FastLineDetector and EdgeDrawing (EDLines), on the same 640x480 images:
// building.jpg from opencv-doc (resized) and a street view of Delft rendered
// by the project's simulator (OpenCV's sample lens, barrel distortion;
// lineloc undistorts its edge points with that calibration, the others take
// the image as it is). One core; medians of repetitions; a summary prints
// each detector's median time and segment count, and its time ratio to
// lineloc lines + corners on one thread. The robot runs the front end with
// its corners on a second thread beside the lines (corners_on_own_thread):
// that one is timed by the wall clock, the others by the CPU time of their
// one thread.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <stdexcept>
#include <string>

#include "robot/input/image_sequence.h"
#include "robot/vision/features/feature_extractor.h"
#include "sim/dataset/drive_simulation.h"
#include "tests/unit/robot/vision/sample_images.h"

namespace {

namespace fs = std::filesystem;

const cv::Size kImageSize(640, 480);
constexpr int kRepetitions = 9;

struct BenchImage {
  const char* name;
  cv::Mat grey;
  lineloc::CameraCalibration calibration;
};

BenchImage buildingImage() {
  BenchImage building{"building", {}, {}};
  cv::resize(lineloc::readSampleImage("building.jpg", cv::IMREAD_GRAYSCALE), building.grey,
             kImageSize, 0.0, 0.0, cv::INTER_AREA);
  building.calibration.camera = {
      500.0, 500.0, 319.5, 239.5, 0.0, kImageSize.width, kImageSize.height};
  return building;
}

// The simulator's frame 0.5 s into a drive through Delft (the city model
// bundled with lineloc), with its camera's calibration.
BenchImage streetImage() {
  const fs::path city = fs::path(LINELOC_SOURCE_DIR) / "data" / "citymodels" / "delft.json";
  const fs::path folder =
      fs::temp_directory_path() / fmt::format("lineloc-bench-vision-{}", ::getpid());
  lineloc::DriveSimulationConfig config;
  config.city_model = city.string();
  config.output = folder.string();
  config.duration_s = 0.6;
  config.camera_rate_hz = 2.0;
  lineloc::simulateDrive(config);
  const std::vector<lineloc::FrameRef> frames =
      lineloc::listImageSequence((folder / "cam0").string());
  BenchImage street{
      "street", lineloc::readGreyImage(frames.back().path),
      lineloc::readCameraCalibration((folder / "cam0" / "calibration.yaml").string())};
  fs::remove_all(folder);
  if (street.grey.size() != kImageSize) {
    throw std::runtime_error("the simulator's camera is not 640x480");
  }
  return street;
}

const BenchImage& image(int which) {
  static const BenchImage building = buildingImage();
  static const BenchImage street = streetImage();
  return which == 0 ? building : street;
}

template <typename Detect>
void run(benchmark::State& state, Detect detect) {
  const BenchImage& input = image(static_cast<int>(state.range(0)));
  size_t segments = 0;
  for (auto _ : state) {
    segments = detect(input.grey);
    benchmark::ClobberMemory();
  }
  state.counters["segments"] = static_cast<double>(segments);
  state.SetLabel(input.name);
}

// `threads`: 1 streams the corners with the gradient rows, 2 detects them on
// their own thread (the robot's setting).
void linelocLinesAndCorners(benchmark::State& state, int threads) {
  lineloc::FeatureExtractorOptions options;
  options.corners_on_own_thread = threads == 2;
  lineloc::FeatureExtractor extractor(image(static_cast<int>(state.range(0))).calibration, options);
  size_t corners = 0;
  run(state, [&](const cv::Mat& grey) {
    const lineloc::FrameFeatures& features = extractor.extract(grey);
    corners = features.corners.size();
    return features.segments.size();
  });
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["threads"] = threads;
}

void BM_LinelocLinesAndCorners(benchmark::State& state) {
  linelocLinesAndCorners(state, 1);
}

void BM_LinelocCornersOnOwnThread(benchmark::State& state) {
  linelocLinesAndCorners(state, 2);
}

void BM_LinelocLinesOnly(benchmark::State& state) {
  lineloc::FeatureExtractorOptions options;
  options.detect_corners = false;
  lineloc::FeatureExtractor extractor(image(static_cast<int>(state.range(0))).calibration, options);
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
LINELOC_VISION_BENCHMARK(BM_LinelocCornersOnOwnThread)->UseRealTime();
LINELOC_VISION_BENCHMARK(BM_LinelocLinesOnly);
LINELOC_VISION_BENCHMARK(BM_OpenCvLsd);
LINELOC_VISION_BENCHMARK(BM_FastLineDetector);
LINELOC_VISION_BENCHMARK(BM_EdLines);

// Keeps the console output and records each median for the summary: the
// wall time of a run on two threads, the CPU time of the others.
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
      const auto threads = run.counters.find("threads");
      const bool two_threads = threads != run.counters.end() && threads->second.value == 2.0;
      medians[run.run_name.function_name][run.report_label] = {
          two_threads ? run.GetAdjustedRealTime() : run.GetAdjustedCPUTime(),
          segments == run.counters.end() ? 0.0 : segments->second.value};
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
      "\nmedian time (ms), segments, and time / lineloc lines+corners on one thread, 640x480; "
      "CPU time of one core, wall time of BM_LinelocCornersOnOwnThread's two threads\n");
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

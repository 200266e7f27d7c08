// 16x16 full search +-16 px over a 640x480 frame (basketball1/2, OpenCV
// samples) on the scalar reference and each vector path of this processor,
// and the matching stereo job (640x480, 32 disparities, block 17) on the SAD
// stereo matcher and cv::StereoBM.
//
// Bound: the machine's psadbw-class throughput, measured here as independent
// psadbw instructions per time-stamp-counter cycle on registers (no loads),
// times the vector width: bytes of |a - b| per cycle. Full search throughput
// counts the pixel differences a full search needs, 256 per candidate.
//
// Timing: each benchmark iteration is timed in ns and RDTSC cycles; the
// summary at the end gives medians over all repetitions after Tukey-fence
// outlier removal. Cache state: "warm" runs reuse the same two frames (2 x
// 300 KB, resident in L2/L3 after the first run); "cold" runs evict the caches
// by streaming a 64 MB buffer before each run (outside the timed region).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "robot/vision/block_matching/block_matcher.h"
#include "robot/vision/block_matching/kernel_timing.h"
#include "robot/vision/stereo/sad_stereo_matcher.h"
#include "tests/unit/robot/vision/sample_images.h"

namespace lineloc {
namespace {

constexpr int kBlockPx = 16;
constexpr int kRadiusPx = 16;
constexpr int64_t kPsadbwLoops = 1 << 20;

cv::Mat readGrey(const std::string& name) {
  return readSampleImage(name, cv::IMREAD_GRAYSCALE);
}

struct Frames {
  Frames() : first(readGrey("basketball1.png")), second(readGrey("basketball2.png")) {
    cv::Mat left_half, right_half;
    cv::resize(readGrey("aloeL.jpg"), left_half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::resize(readGrey("aloeR.jpg"), right_half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    left = left_half(cv::Rect(0, 0, 640, 480)).clone();
    right = right_half(cv::Rect(0, 0, 640, 480)).clone();
  }
  cv::Mat first, second, left, right;
};

const Frames& frames() {
  static const Frames kFrames;
  return kFrames;
}

// Pixel differences of one full search: 256 per candidate inside the window
// clipped to the frame.
double pixelDifferencesPerFrame(int width, int height) {
  const auto candidates = [](int position, int size) {
    return std::min(kRadiusPx, size - kBlockPx - position) - std::max(-kRadiusPx, -position) + 1;
  };
  double total = 0.0;
  for (int y = 0; y + kBlockPx <= height; y += kBlockPx) {
    for (int x = 0; x + kBlockPx <= width; x += kBlockPx) {
      total += static_cast<double>(candidates(x, width)) * candidates(y, height) * 256.0;
    }
  }
  return total;
}

std::map<std::string, std::vector<RunSample>>& samples() {
  static std::map<std::string, std::vector<RunSample>> kSamples;
  return kSamples;
}

void evictCaches() {
  static std::vector<uint8_t> buffer(64 << 20);
  for (size_t i = 0; i < buffer.size(); i += 64) {
    buffer[i] = static_cast<uint8_t>(buffer[i] + 1);
  }
  benchmark::ClobberMemory();
}

template <typename Work>
void timeRuns(benchmark::State& state, const std::string& name, bool cold, Work&& work) {
  std::vector<RunSample>& runs = samples()[name];
  for (auto _ : state) {
    if (cold) {
      state.PauseTiming();
      evictCaches();
      state.ResumeTiming();
    }
    const RunTimer timer;
    work();
    runs.push_back(timer.elapsed());
  }
}

void fullSearch(benchmark::State& state, SimdPath path, bool cold) {
  const BlockMatcher matcher({kBlockPx, kBlockPx, kRadiusPx, SearchStrategy::kFull}, path);
  const Frames& f = frames();
  timeRuns(state, fmt::format("full search {} {}", simdPathName(path), cold ? "cold" : "warm"),
           cold, [&] { benchmark::DoNotOptimize(matcher.matchGrid(f.first, f.second)); });
  state.counters["pixel_diff_per_s"] =
      benchmark::Counter(pixelDifferencesPerFrame(f.first.cols, f.first.rows),
                         benchmark::Counter::kIsIterationInvariantRate);
}

constexpr StereoOptions kStereo{17, 0, 32, 15, 31, -1};

void sadStereo(benchmark::State& state, SimdPath path) {
  const SadStereoMatcher matcher(kStereo, path);
  const Frames& f = frames();
  timeRuns(state, fmt::format("stereo lineloc {}", simdPathName(path)), false,
           [&] { benchmark::DoNotOptimize(matcher.compute(f.left, f.right)); });
}

void stereoBm(benchmark::State& state) {
  const auto bm = cv::StereoBM::create(kStereo.num_disparities, kStereo.block_size_px);
  const Frames& f = frames();
  cv::Mat disparity;
  timeRuns(state, "stereo cv::StereoBM", false, [&] { bm->compute(f.left, f.right, disparity); });
}

// Independent psadbw per TSC cycle on registers.
double psadbwPerCycle(SimdPath path) {
  const RunTimer timer;
  benchmark::DoNotOptimize(sadKernels(path).psadbwProbe(kPsadbwLoops));
  return static_cast<double>(kPsadbwLoops * kPsadbwProbeChains) /
         static_cast<double>(timer.elapsed().duration_cycles);
}

// Best of five measurements (the bound is a peak).
double psadbwRate(SimdPath path) {
  double best = 0.0;
  for (int trial = 0; trial < 5; ++trial) {
    best = std::max(best, psadbwPerCycle(path));
  }
  return best;
}

void printSummary() {
  const Frames& f = frames();
  const double differences = pixelDifferencesPerFrame(f.first.cols, f.first.rows);
  double machine_bytes_per_cycle = 0.0;
  fmt::print("\npsadbw-class bound (independent psadbw on registers, per TSC cycle):\n");
  std::map<SimdPath, double> bound_bytes_per_cycle;
  for (SimdPath path : supportedSimdPaths()) {
    if (path == SimdPath::kScalar) {
      continue;
    }
    const double rate = psadbwRate(path);
    bound_bytes_per_cycle[path] = rate * simdPathWidthBytes(path);
    machine_bytes_per_cycle = std::max(machine_bytes_per_cycle, bound_bytes_per_cycle[path]);
    fmt::print("  {:>9}: {:5.2f} instr/cycle x {:2d} B = {:6.1f} B/cycle\n", simdPathName(path),
               rate, simdPathWidthBytes(path), bound_bytes_per_cycle[path]);
  }
  const auto& scalar = samples()["full search scalar warm"];
  const double scalar_ns = summarizeRuns(scalar).median_ns;
  fmt::print("\n16x16 full search +-16 px, 640x480 ({:.1f} M pixel differences per frame)\n",
             differences * 1e-6);
  fmt::print("{:<28} {:>6} {:>11} {:>13} {:>8} {:>8} {:>10} {:>9}\n", "run", "kept", "median ms",
             "median Mcyc", "GB/s", "B/cycle", "of bound", "x scalar");
  for (const auto& [name, runs] : samples()) {
    const RunStatistics stats = summarizeRuns(runs);
    if (name.rfind("full search", 0) != 0 || stats.kept == 0) {
      continue;
    }
    const double bytes_per_cycle = differences / stats.median_cycles;
    fmt::print("{:<28} {:>3}/{:<3} {:>10.3f} {:>13.3f} {:>8.1f} {:>8.2f} {:>9.1f}% {:>9.1f}\n",
               name, stats.kept, stats.runs, stats.median_ns * 1e-6, stats.median_cycles * 1e-6,
               differences / stats.median_ns, bytes_per_cycle,
               100.0 * bytes_per_cycle / machine_bytes_per_cycle, scalar_ns / stats.median_ns);
  }
  fmt::print(
      "(of bound: of the machine's widest psadbw bound, {:.1f} B/cycle; cycles are TSC "
      "cycles)\n\nstereo 640x480, block {}, {} disparities\n",
      machine_bytes_per_cycle, kStereo.block_size_px, kStereo.num_disparities);
  const double opencv_ns = summarizeRuns(samples()["stereo cv::StereoBM"]).median_ns;
  for (const auto& [name, runs] : samples()) {
    const RunStatistics stats = summarizeRuns(runs);
    if (name.rfind("stereo", 0) == 0) {
      fmt::print("{:<28} {:>3}/{:<3} {:>10.3f} ms {:>10.3f} Mcyc  {:.2f} x cv::StereoBM's time\n",
                 name, stats.kept, stats.runs, stats.median_ns * 1e-6, stats.median_cycles * 1e-6,
                 stats.median_ns / opencv_ns);
    }
  }
}

void registerBenchmarks() {
  for (SimdPath path : supportedSimdPaths()) {
    benchmark::RegisterBenchmark(fmt::format("FullSearch16x16/{}/warm", simdPathName(path)).c_str(),
                                 fullSearch, path, false)
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  }
  benchmark::RegisterBenchmark(
      fmt::format("FullSearch16x16/{}/cold", simdPathName(bestSimdPath())).c_str(), fullSearch,
      bestSimdPath(), true)
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true);
  for (SimdPath path : {SimdPath::kScalar, bestSimdPath()}) {
    benchmark::RegisterBenchmark(fmt::format("Stereo/lineloc/{}", simdPathName(path)).c_str(),
                                 sadStereo, path)
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  }
  benchmark::RegisterBenchmark("Stereo/cv::StereoBM", stereoBm)
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(5)
      ->ReportAggregatesOnly(true);
}

}  // namespace
}  // namespace lineloc

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  lineloc::registerBenchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  lineloc::printSummary();
  return 0;
}

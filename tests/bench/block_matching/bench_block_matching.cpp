// 16x16 full search +-16 px over a 640x480 frame (basketball1/2, OpenCV
// samples) on the scalar reference and each vector path of this processor,
// and the matching stereo job (640x480, 32 disparities, block 17) on the SAD
// stereo matcher and cv::StereoBM.
//
// Bound: the machine's psadbw-class throughput, measured here as independent
// psadbw instructions per time-stamp-counter cycle on registers (no loads),
// times the vector width: bytes of |a - b| per cycle. Full search throughput
// counts the pixel differences a full search needs, 256 per candidate of the
// window clipped to the frame (work a kernel spends beyond that, e.g. whole
// batches of candidates, is not counted).
//
// Timing: each benchmark iteration is timed in ns, RDTSC cycles and process
// CPU time; the summary at the end gives medians over all repetitions after
// Tukey-fence outlier removal. "cpu/wall" is CPU time over wall time: 1.00
// for a single-threaded run that had a core to itself, below 1 when it was
// preempted (this machine's 2 cores are shared with other builds: then
// Google Benchmark's wall "Time" exceeds its "CPU"), near the thread count
// for cv::StereoBM, which runs in OpenCV's thread pool; it also runs with one
// thread for a like-for-like comparison with the single-threaded matcher.
// Cache state: "warm" runs reuse the same two frames (2 x 300 KB, resident in
// L2/L3 after the first run); "cold" runs evict the caches by streaming a
// 64 MB buffer before each run (outside the timed region).
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

void fullSearch(benchmark::State& state, SimdPath path, SearchStrategy strategy, bool cold) {
  const BlockMatcher matcher({kBlockPx, kBlockPx, kRadiusPx, strategy}, path);
  const Frames& f = frames();
  const bool early = strategy == SearchStrategy::kFullEarlyTermination;
  timeRuns(state,
           fmt::format("full search {}{} {}", simdPathName(path), early ? " early-term" : "",
                       cold ? "cold" : "warm"),
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

void stereoBm(benchmark::State& state, int threads) {
  const auto bm = cv::StereoBM::create(kStereo.num_disparities, kStereo.block_size_px);
  bm->setUniquenessRatio(kStereo.uniqueness_percent);
  const Frames& f = frames();
  cv::Mat disparity;
  const int default_threads = cv::getNumThreads();
  if (threads > 0) {
    cv::setNumThreads(threads);
  }
  timeRuns(state, threads > 0 ? "stereo cv::StereoBM 1 thread" : "stereo cv::StereoBM", false,
           [&] { bm->compute(f.left, f.right, disparity); });
  cv::setNumThreads(default_threads);
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

// Percent of a bound; 0 where there is none (no vector path).
double fractionOf(double bytes_per_cycle, double bound_bytes_per_cycle) {
  return bound_bytes_per_cycle > 0 ? 100.0 * bytes_per_cycle / bound_bytes_per_cycle : 0.0;
}

double cpuPerWall(const RunStatistics& stats) {
  return stats.median_cpu_ns / stats.median_ns;
}

void printSummary() {
  const Frames& f = frames();
  const double differences = pixelDifferencesPerFrame(f.first.cols, f.first.rows);
  fmt::print("\npsadbw-class bound (independent psadbw on registers, per TSC cycle):\n");
  std::map<std::string_view, double> bound_bytes_per_cycle;
  double machine_bytes_per_cycle = 0.0;
  for (SimdPath path : supportedSimdPaths()) {
    if (path == SimdPath::kScalar) {
      continue;
    }
    const double rate = psadbwRate(path);
    const double bytes = rate * simdPathWidthBytes(path);
    bound_bytes_per_cycle[simdPathName(path)] = bytes;
    machine_bytes_per_cycle = std::max(machine_bytes_per_cycle, bytes);
    fmt::print("  {:>9}: {:5.2f} instr/cycle x {:2d} B = {:6.1f} B/cycle\n", simdPathName(path),
               rate, simdPathWidthBytes(path), bytes);
  }
  const RunStatistics scalar = summarizeRuns(samples()["full search scalar warm"]);
  const double tsc_ghz = scalar.median_cycles / scalar.median_ns;
  fmt::print("  machine: {:.1f} B/cycle = {:.0f} GB/s at the {:.3f} GHz TSC\n",
             machine_bytes_per_cycle, machine_bytes_per_cycle * tsc_ghz, tsc_ghz);
  fmt::print("\n16x16 full search +-16 px, 640x480 ({:.1f} M pixel differences per frame)\n",
             differences * 1e-6);
  fmt::print("{:<36} {:>9} {:>9} {:>8} {:>5} {:>7} {:>7} {:>8} {:>8} {:>8}\n", "run", "kept",
             "median ms", "Mcyc", "cpu/w", "GB/s", "B/cycle", "of bound", "of path", "x scalar");
  for (const auto& [name, runs] : samples()) {
    const RunStatistics stats = summarizeRuns(runs);
    if (name.rfind("full search", 0) != 0 || stats.kept == 0) {
      continue;
    }
    const double bytes_per_cycle = differences / stats.median_cycles;
    const std::string_view path = std::string_view(name).substr(12, name.find(' ', 12) - 12);
    const double path_bound = bound_bytes_per_cycle.count(path) ? bound_bytes_per_cycle[path] : 0;
    fmt::print(
        "{:<36} {:>4}/{:<4} {:>9.3f} {:>8.3f} {:>5.2f} {:>7.1f} {:>7.2f} {:>7.1f}% {:>7.1f}% "
        "{:>8.1f}\n",
        name, stats.kept, stats.runs, stats.median_ns * 1e-6, stats.median_cycles * 1e-6,
        cpuPerWall(stats), differences / stats.median_ns, bytes_per_cycle,
        fractionOf(bytes_per_cycle, machine_bytes_per_cycle),
        fractionOf(bytes_per_cycle, path_bound), scalar.median_ns / stats.median_ns);
  }
  fmt::print(
      "(of bound: of the machine's widest psadbw bound; of path: of that path's own; cycles are "
      "TSC cycles)\n\nstereo 640x480, block {}, {} disparities, uniqueness {} %\n",
      kStereo.block_size_px, kStereo.num_disparities, kStereo.uniqueness_percent);
  const double opencv_ns = summarizeRuns(samples()["stereo cv::StereoBM 1 thread"]).median_ns;
  for (const auto& [name, runs] : samples()) {
    const RunStatistics stats = summarizeRuns(runs);
    if (name.rfind("stereo", 0) == 0) {
      fmt::print(
          "{:<36} {:>4}/{:<4} {:>9.3f} ms {:>8.3f} Mcyc  cpu/wall {:.2f}  {:.2f} x the time of "
          "cv::StereoBM on 1 thread\n",
          name, stats.kept, stats.runs, stats.median_ns * 1e-6, stats.median_cycles * 1e-6,
          cpuPerWall(stats), stats.median_ns / opencv_ns);
    }
  }
}

void registerBenchmarks() {
  const auto configure = [](benchmark::internal::Benchmark* benchmark) {
    benchmark->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
  };
  for (SimdPath path : supportedSimdPaths()) {
    configure(benchmark::RegisterBenchmark(
        fmt::format("FullSearch16x16/{}/warm", simdPathName(path)).c_str(), fullSearch, path,
        SearchStrategy::kFull, false));
  }
  const std::string best(simdPathName(bestSimdPath()));
  configure(benchmark::RegisterBenchmark(fmt::format("FullSearch16x16/{}/cold", best).c_str(),
                                         fullSearch, bestSimdPath(), SearchStrategy::kFull, true));
  configure(benchmark::RegisterBenchmark(
      fmt::format("FullSearch16x16/{}/early-termination/warm", best).c_str(), fullSearch,
      bestSimdPath(), SearchStrategy::kFullEarlyTermination, false));
  for (SimdPath path : {SimdPath::kScalar, bestSimdPath()}) {
    configure(benchmark::RegisterBenchmark(
        fmt::format("Stereo/lineloc/{}", simdPathName(path)).c_str(), sadStereo, path));
  }
  configure(benchmark::RegisterBenchmark("Stereo/cv::StereoBM", stereoBm, 0));
  configure(benchmark::RegisterBenchmark("Stereo/cv::StereoBM/1 thread", stereoBm, 1));
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

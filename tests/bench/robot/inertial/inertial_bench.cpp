// Cost of the navigator's two hot paths against what a user would write with
// the usual tools: one IMU propagation step (state + 15x15 covariance), and one
// vision fix arriving 300 ms late (rewind + 60 steps of re-propagation + the
// 6-D update). Baselines: the same error-state propagation with a dense Eigen
// product, and cv::KalmanFilter (OpenCV's linear Kalman filter, dense cv::Mat)
// doing predict() with the same transition matrix and, for the late fix, 60
// predicts and one correct(). A summary of median CPU times and ratios is
// printed at the end.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <opencv2/video/tracking.hpp>
#include <random>
#include <string>

#include "robot/inertial/inertial_navigator.h"
#include "robot/inertial/strapdown.h"
#include "sim/sensors/sensor_synthesis.h"

namespace lineloc {
namespace {

constexpr int64_t kImuPeriod_ns = 5'000'000;
constexpr int kStepsIn300ms = 60;

ImuSample sampleAt(int64_t stamp_ns) {
  const double t = static_cast<double>(stamp_ns) * 1e-9;
  return {stamp_ns, Eigen::Vector3d(0.01 * std::sin(t), 0.02, 0.3 * std::cos(0.5 * t)),
          Eigen::Vector3d(0.3 * std::sin(2 * t), 0.1, 9.81)};
}

ErrorCovariance startCovariance() {
  return ErrorCovariance::Identity() * 1e-2;
}

void BM_PropagationStep_lineloc(benchmark::State& state) {
  const Strapdown strapdown(ImuNoiseDensities{}, Eigen::Vector3d(0, 0, -9.80665));
  NavigationState nav;
  ErrorCovariance P = startCovariance();
  ImuSample previous = sampleAt(0);
  for (auto _ : state) {
    const ImuSample next = sampleAt(previous.stamp_ns + kImuPeriod_ns);
    strapdown.propagate(previous, next, nav, P);
    previous = next;
    benchmark::DoNotOptimize(P.data());
  }
}

void BM_PropagationStep_denseEigen(benchmark::State& state) {
  const Strapdown strapdown(ImuNoiseDensities{}, Eigen::Vector3d(0, 0, -9.80665));
  NavigationState nav;
  ErrorCovariance P = startCovariance();
  ErrorCovariance Q = ErrorCovariance::Zero();
  ProcessNoise(ImuNoiseDensities{}).addTo(kImuPeriod_ns * 1e-9, Q);
  ImuSample previous = sampleAt(0);
  for (auto _ : state) {
    const ImuSample next = sampleAt(previous.stamp_ns + kImuPeriod_ns);
    const ErrorCovariance phi = strapdown.propagate(previous, next, nav).toMatrix();
    P = phi * P * phi.transpose() + Q;
    previous = next;
    benchmark::DoNotOptimize(P.data());
  }
}

cv::Mat toCv(const ErrorCovariance& m) {
  cv::Mat out(kErrorStateSize, kErrorStateSize, CV_64F);
  for (int r = 0; r < kErrorStateSize; ++r) {
    for (int c = 0; c < kErrorStateSize; ++c) {
      out.at<double>(r, c) = m(r, c);
    }
  }
  return out;
}

cv::KalmanFilter makeOpenCvFilter() {
  cv::KalmanFilter filter(kErrorStateSize, 6, 0, CV_64F);
  ErrorCovariance Q = ErrorCovariance::Zero();
  ProcessNoise(ImuNoiseDensities{}).addTo(kImuPeriod_ns * 1e-9, Q);
  filter.processNoiseCov = toCv(Q);
  filter.errorCovPost = toCv(startCovariance());
  filter.measurementMatrix = cv::Mat::zeros(6, kErrorStateSize, CV_64F);
  for (int i = 0; i < 3; ++i) {
    filter.measurementMatrix.at<double>(i, kPosition + i) = 1.0;
    filter.measurementMatrix.at<double>(3 + i, kAttitude + i) = 1.0;
  }
  filter.measurementNoiseCov = cv::Mat::eye(6, 6, CV_64F) * 1e-4;
  return filter;
}

// The nominal strapdown step is the same; OpenCV then does P = F P F^T + Q densely.
void openCvStep(const Strapdown& strapdown, cv::KalmanFilter& filter, NavigationState& nav,
                ImuSample& previous) {
  const ImuSample next = sampleAt(previous.stamp_ns + kImuPeriod_ns);
  filter.transitionMatrix = toCv(strapdown.propagate(previous, next, nav).toMatrix());
  filter.predict();
  previous = next;
}

void BM_PropagationStep_opencvKalman(benchmark::State& state) {
  const Strapdown strapdown(ImuNoiseDensities{}, Eigen::Vector3d(0, 0, -9.80665));
  cv::KalmanFilter filter = makeOpenCvFilter();
  NavigationState nav;
  ImuSample previous = sampleAt(0);
  for (auto _ : state) {
    openCvStep(strapdown, filter, nav, previous);
    benchmark::DoNotOptimize(filter.errorCovPre.data);
  }
}

// A navigator running on a simulated drive, a fix 300 ms late per iteration;
// the 20 IMU samples (100 ms) between fixes are added outside the timing.
void BM_DelayedUpdate300ms_lineloc(benchmark::State& state) {
  sim::TrajectoryConfig config;
  config.duration_s = 250.0;
  const sim::GroundTruthTrajectory trajectory(config);
  const auto imu = sim::synthesiseImu(trajectory, sim::ImuModel{}, 1);
  InertialNavigator navigator(InertialNavigatorConfig{});
  navigator.addImu({imu[0].stamp_ns, imu[0].gyro_radps, imu[0].accel_mps2});
  NavigationState start;
  start.stamp_ns = imu[0].stamp_ns;
  start.p_world_body = trajectory.at(start.stamp_ns).p_world_body;
  start.q_world_body = trajectory.at(start.stamp_ns).q_world_body;
  navigator.initialise(start, startCovariance());
  size_t next = 1;
  for (auto _ : state) {
    state.PauseTiming();
    if (next + 20 >= imu.size()) {
      state.SkipWithError("simulated drive too short for this many iterations");
      break;
    }
    for (const size_t end = next + 20; next < end; ++next) {
      navigator.addImu({imu[next].stamp_ns, imu[next].gyro_radps, imu[next].accel_mps2});
    }
    const int64_t fix_stamp = imu[next - 1].stamp_ns - 300'000'000 + 2'500'000;
    PoseWithCovariance fix;
    fix.pose.linear() = trajectory.at(fix_stamp).q_world_body.toRotationMatrix() *
                        InertialNavigatorConfig::defaultBodyCamera().linear();
    fix.pose.translation() = trajectory.at(fix_stamp).p_world_body;
    fix.covariance = diagonalPoseCovariance(0.03, 0.002);
    state.ResumeTiming();
    benchmark::DoNotOptimize(navigator.applyVisionFix(fix_stamp, fix));
  }
}

void BM_DelayedUpdate300ms_opencvKalman(benchmark::State& state) {
  const Strapdown strapdown(ImuNoiseDensities{}, Eigen::Vector3d(0, 0, -9.80665));
  cv::KalmanFilter filter = makeOpenCvFilter();
  const cv::Mat measurement = cv::Mat::zeros(6, 1, CV_64F);
  NavigationState nav;
  ImuSample previous = sampleAt(0);
  for (auto _ : state) {
    filter.correct(measurement);
    for (int step = 0; step < kStepsIn300ms; ++step) {
      openCvStep(strapdown, filter, nav, previous);
    }
    benchmark::DoNotOptimize(filter.errorCovPre.data);
  }
}

BENCHMARK(BM_PropagationStep_lineloc)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_PropagationStep_denseEigen)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_PropagationStep_opencvKalman)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_DelayedUpdate300ms_lineloc)
    ->Iterations(2000)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_DelayedUpdate300ms_opencvKalman)->Repetitions(5)->ReportAggregatesOnly(true);

// Records the medians to print lineloc's time against each baseline's.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median") {
        medians_ns_[run.run_name.function_name] = run.GetAdjustedCPUTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  void printSummary() const {
    std::printf(
        "\nmedian CPU ns per operation (CPU, not wall, time: build machines are shared);"
        " ratio = baseline / lineloc:\n");
    for (const char* operation : {"BM_PropagationStep", "BM_DelayedUpdate300ms"}) {
      const auto ours = medians_ns_.find(std::string(operation) + "_lineloc");
      if (ours == medians_ns_.end()) {
        continue;
      }
      std::printf("  %-24s lineloc %10.1f\n", operation, ours->second);
      for (const auto& [name, ns] : medians_ns_) {
        if (name.rfind(operation, 0) == 0 && name != ours->first) {
          std::printf("  %-24s %-14s %10.1f  ratio %.2f\n", "",
                      name.substr(name.rfind('_') + 1).c_str(), ns, ns / ours->second);
        }
      }
    }
  }

 private:
  std::map<std::string, double> medians_ns_;
};

}  // namespace
}  // namespace lineloc

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  lineloc::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printSummary();
  benchmark::Shutdown();
  return 0;
}

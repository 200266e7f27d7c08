#include "tests/bench/backbone/delft_frames.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "common/time/clock.h"
#include "robot/vision/features/feature_extractor.h"
#include "tests/support/delft_drive.h"

namespace fs = std::filesystem;

namespace lineloc::test {

DelftFrames simulateDelftFrames(double duration_s, double camera_rate_hz) {
  const fs::path folder = fs::temp_directory_path() / fmt::format("bench_delft_{}", getpid());
  fs::remove_all(folder);
  DriveSimulationConfig config;
  config.duration_s = duration_s;
  config.drive.initial_still_s = 0.5;
  config.camera_rate_hz = camera_rate_hz;
  const SimulatedFrames simulated = simulateDelftDrive(config, folder);
  DelftFrames result{simulated.calibration, {}, drivingSunlight(config)};
  FeatureExtractor extractor(result.calibration);
  for (size_t i = 0; i < simulated.images.size(); ++i) {
    DelftFrame frame;
    frame.image = cv::imread(simulated.images[i], cv::IMREAD_GRAYSCALE);
    frame.truth = simulated.truth[i];
    const int64_t start_ns = steadyClockNs();
    FrameFeatures features = extractor.extract(frame.image);
    frame.front_end_ns = steadyClockNs() - start_ns;
    frame.segments = std::move(features.segments);
    frame.corners = std::move(features.corners);
    result.frames.push_back(std::move(frame));
  }
  fs::remove_all(folder);
  return result;
}

PoseWithCovariance predictedAround(const Eigen::Isometry3d& truth, double position_sigma_m,
                                   double rotation_sigma_rad, std::mt19937& random) {
  std::normal_distribution<double> n(0.0, 1.0);
  PoseWithCovariance prediction;
  prediction.pose.linear() =
      Eigen::AngleAxisd(rotation_sigma_rad * n(random), Eigen::Vector3d::UnitZ()) * truth.linear();
  prediction.pose.translation() =
      truth.translation() + position_sigma_m * Eigen::Vector3d(n(random), n(random), 0.0);
  prediction.covariance = diagonalPoseCovariance(position_sigma_m, rotation_sigma_rad);
  return prediction;
}

}  // namespace lineloc::test

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim/render/auto_exposure.h"
#include "tests/unit/sim/render/quarter_camera.h"

namespace lineloc {
namespace {

struct Frame {
  ExposureSettings settings;
  double mean_dn = 0.0;
};

// A camera under auto-exposure filming flat scenes of the given radiances,
// frame by frame: each frame is exposed, metered and fed back.
std::vector<Frame> film(const std::vector<float>& scene_radiance,
                        const AutoExposureOptions& options, const ExposureSettings& initial) {
  const CameraSensor sensor(CameraRays(quarterCamera()), CameraSensorOptions{});
  AutoExposure auto_exposure(options, initial);
  std::vector<Frame> frames;
  for (size_t i = 0; i < scene_radiance.size(); ++i) {
    const cv::Mat radiance(120, 160, CV_32FC1, cv::Scalar(scene_radiance[i]));
    const ExposureSettings settings = auto_exposure.settings();
    const double mean_dn = cv::mean(sensor.expose(radiance, settings, i))[0];
    auto_exposure.update(mean_dn);
    frames.push_back({settings, mean_dn});
  }
  return frames;
}

// Frames after a step in the scene's radiance by `step` before the log error
// ln(step) falls inside the deadband: ln(step) damping^n <= ln(1 + tolerance).
int framesToConverge(double step, const AutoExposureOptions& options) {
  return static_cast<int>(std::ceil(std::log(std::log(1.0 + options.tolerance) / std::log(step)) /
                                    std::log(1.0 - options.damping)));
}

TEST(AutoExposure, FromSunIntoShadeTheExposureThenTheGainRiseOverAFewFrames) {
  const AutoExposureOptions options;
  constexpr int kStep = 20;
  std::vector<float> scene(kStep, 0.6f);
  scene.resize(2 * kStep, 0.08f);
  const std::vector<Frame> frames = film(scene, options, {options.max_exposure_time_s, 0.0});
  // In the sun: settled on the target in short exposures with no gain.
  const Frame& sunlit = frames[kStep - 1];
  EXPECT_NEAR(sunlit.mean_dn, options.target_mean_dn, options.tolerance * options.target_mean_dn);
  EXPECT_LT(sunlit.settings.exposure_time_s, 0.5 * options.max_exposure_time_s);
  EXPECT_EQ(sunlit.settings.gain_db, 0.0);
  // The first shaded frame is still exposed for the sun; the camera then
  // reacts over several frames, not in one jump.
  EXPECT_EQ(frames[kStep].settings.exposure_time_s, sunlit.settings.exposure_time_s);
  EXPECT_LT(frames[kStep].mean_dn, 0.2 * options.target_mean_dn);
  for (int i = kStep + 1; i < kStep + 4; ++i) {
    const double product =
        frames[i].settings.exposure_time_s * std::pow(10.0, frames[i].settings.gain_db / 20.0);
    const double before = frames[i - 1].settings.exposure_time_s *
                          std::pow(10.0, frames[i - 1].settings.gain_db / 20.0);
    EXPECT_GT(product, 1.2 * before) << "frame " << i;
  }
  // A 7.5 times darker scene is at the target within framesToConverge (6
  // at damping 0.5) of the first shaded frame's metering, the exposure time
  // at its cap and the gain up to make the rest.
  const int converged = kStep + 1 + framesToConverge(0.6 / 0.08, options);
  for (int i = converged; i < 2 * kStep; ++i) {
    EXPECT_NEAR(frames[i].mean_dn, options.target_mean_dn,
                options.tolerance * options.target_mean_dn)
        << "frame " << i;
    EXPECT_EQ(frames[i].settings.exposure_time_s, options.max_exposure_time_s);
    EXPECT_GT(frames[i].settings.gain_db, 3.0);
  }
}

TEST(AutoExposure, AConstantSceneKeepsItsSettings) {
  const AutoExposureOptions options;
  const std::vector<Frame> frames = film(std::vector<float>(40, 0.3f), options, {1e-4, 0.0});
  const int settled = framesToConverge(10.0, options) + 1;
  for (int i = settled + 1; i < 40; ++i) {
    EXPECT_EQ(frames[i].settings.exposure_time_s, frames[settled].settings.exposure_time_s);
    EXPECT_EQ(frames[i].settings.gain_db, frames[settled].settings.gain_db);
  }
  EXPECT_NEAR(frames.back().mean_dn, options.target_mean_dn,
              options.tolerance * options.target_mean_dn);
}

TEST(AutoExposure, GainStopsAtItsLimit) {
  AutoExposureOptions options;
  options.max_gain_db = 12.0;
  AutoExposure auto_exposure(options, {options.max_exposure_time_s, 0.0});
  for (int i = 0; i < 20; ++i) {
    auto_exposure.update(0.0);
  }
  EXPECT_EQ(auto_exposure.settings().exposure_time_s, options.max_exposure_time_s);
  EXPECT_DOUBLE_EQ(auto_exposure.settings().gain_db, 12.0);
}

void expectRejected(const AutoExposureOptions& options, const std::string& named) {
  try {
    AutoExposure(options, {0.001, 0.0});
    ADD_FAILURE() << "accepted " << named;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(AutoExposure, RejectsInvalidOptionsNamingThem) {
  AutoExposureOptions options;
  options.target_mean_dn = 300.0;
  expectRejected(options, "target_mean_dn must be in (0, 255) (got 300)");
  options = AutoExposureOptions{};
  options.damping = 0.0;
  expectRejected(options, "damping must be in (0, 1] (got 0)");
  options = AutoExposureOptions{};
  options.tolerance = -0.1;
  expectRejected(options, "tolerance must be >= 0 (got -0.1)");
  options = AutoExposureOptions{};
  options.max_exposure_time_s = 1e-6;
  expectRejected(options, "max_exposure_time_s must be >= min_exposure_time_s (1e-05) (got 1e-06)");
  options = AutoExposureOptions{};
  options.min_exposure_time_s = 0.0;
  expectRejected(options, "min_exposure_time_s must be > 0 (got 0)");
  options = AutoExposureOptions{};
  options.max_gain_db = -1.0;
  expectRejected(options, "max_gain_db must be >= 0 (got -1)");
}

}  // namespace
}  // namespace lineloc

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <string>

#include "sim/render/camera_sensor.h"
#include "sim/render/sample_camera.h"
#include "tests/unit/sim/render/quarter_camera.h"

namespace lineloc {
namespace {

// Radiance that lights every pixel of the sensor alike: `level` / V, so that
// mu_e = full_well_e level at the saturation exposure time.
cv::Mat flatOnTheSensor(const CameraSensor& sensor, float level) {
  cv::Mat radiance;
  cv::divide(level, sensor.vignetting(), radiance);
  return radiance;
}

TEST(CameraSensor, PhotonTransferFollowsTheEmvaModel) {
  const CameraSensorOptions options;
  const CameraSensor sensor(CameraRays(opencvSampleCamera()), options);
  const double n = 640.0 * 480.0;
  // (gain, fraction of the full well): the DN variance spans 2 to 17 DN^2,
  // from the signal at 0 dB and from the gain at 24 dB.
  for (const auto& [gain_db, level] : {std::pair{0.0, 0.3f}, std::pair{0.0, 0.8f},
                                       std::pair{12.0, 0.05f}, std::pair{24.0, 0.01f}}) {
    SCOPED_TRACE("gain " + std::to_string(gain_db) + " dB, level " + std::to_string(level));
    const ExposureSettings settings{options.saturation_exposure_time_s, gain_db};
    const cv::Mat image = sensor.expose(flatOnTheSensor(sensor, level), settings, 7);
    const double K = sensor.systemGain_dn_per_e(gain_db);
    const double mu_e = options.full_well_e * level;
    const double mu_y = K * mu_e;
    const double variance_y =
        K * K * options.read_noise_e * options.read_noise_e + K * mu_y + 1.0 / 12.0;
    cv::Scalar mean;
    cv::Scalar sigma;
    cv::meanStdDev(image, mean, sigma);
    // Five standard errors of n = 307,200 samples: sigma / sqrt(n) for the
    // mean, sigma^2 sqrt(2 / (n - 1)) for the variance (a normal sample's).
    EXPECT_NEAR(mean[0], mu_y, 5.0 * std::sqrt(variance_y / n));
    EXPECT_NEAR(sigma[0] * sigma[0], variance_y, 5.0 * variance_y * std::sqrt(2.0 / (n - 1.0)));
  }
}

TEST(CameraSensor, SaturatesAtTheFullWell) {
  const CameraSensorOptions options;
  const CameraSensor sensor(CameraRays(quarterCamera()), options);
  const cv::Mat image =
      sensor.expose(flatOnTheSensor(sensor, 1.5f), {options.saturation_exposure_time_s, 6.0}, 3);
  EXPECT_EQ(cv::countNonZero(image != 255), 0);
}

TEST(CameraSensor, VignettingIsCosineFourthOfTheCalibratedRay) {
  const CameraCalibration calibration = quarterCamera();
  const CameraSensorOptions options;
  const CameraSensor sensor(CameraRays(calibration), options);
  const PinholeCamera& camera = calibration.camera;
  const cv::Matx33d K(camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  // A flat radiance at 80 % of the full well on the axis, averaged over 100
  // exposures.
  const cv::Mat radiance(camera.height, camera.width, CV_32FC1, cv::Scalar(0.8f));
  const ExposureSettings settings{options.saturation_exposure_time_s, 0.0};
  constexpr int kFrames = 100;
  cv::Mat sum = cv::Mat::zeros(radiance.size(), CV_64FC1);
  for (int frame = 0; frame < kFrames; ++frame) {
    cv::Mat image;
    sensor.expose(radiance, settings, frame).convertTo(image, CV_64FC1);
    sum += image;
  }
  const cv::Mat mean_dn = sum / kFrames;
  // cos(theta) of pixel (u, v) from OpenCV's undistortion of the calibration.
  const auto cosTheta = [&](int u, int v) {
    std::vector<cv::Point2d> undistorted;
    cv::undistortPoints(
        std::vector<cv::Point2d>{{static_cast<double>(u), static_cast<double>(v)}}, undistorted, K,
        calibration.distortion, cv::noArray(), cv::noArray(),
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15));
    const cv::Point2d& p = undistorted[0];
    return 1.0 / std::sqrt(p.x * p.x + p.y * p.y + 1.0);
  };
  const int centre_u = static_cast<int>(std::lround(camera.cx));
  const int centre_v = static_cast<int>(std::lround(camera.cy));
  const double centre =
      mean_dn.at<double>(centre_v, centre_u) / std::pow(cosTheta(centre_u, centre_v), 4);
  for (const auto& [u, v] :
       {std::pair{0, 0}, std::pair{camera.width - 1, 0}, std::pair{0, camera.height - 1},
        std::pair{camera.width - 1, camera.height - 1}}) {
    const double expected = std::pow(cosTheta(u, v), 4);
    SCOPED_TRACE("corner " + std::to_string(u) + "," + std::to_string(v) +
                 ", cos^4 = " + std::to_string(expected));
    // A pixel's DN has sigma K sqrt(mu_e + read_noise_e^2) at 0 dB: 2.2 DN
    // at the centre's 204 DN, 1.1 DN at a corner's 50 DN or more. Over 100
    // frames the ratio's relative standard error is under
    // sqrt(0.11^2 + 0.22^2) % = 0.25 %: five of them is 1.25 %.
    EXPECT_LT(expected, 0.5);
    EXPECT_NEAR(mean_dn.at<double>(v, u) / centre, expected, 0.0125 * expected);
  }
}

TEST(CameraSensor, SameSeedSameBytesOtherSeedOtherNoise) {
  const CameraSensor sensor(CameraRays(quarterCamera()), CameraSensorOptions{});
  const cv::Mat radiance(120, 160, CV_32FC1, cv::Scalar(0.4f));
  const ExposureSettings settings{0.001, 6.0};
  const cv::Mat a = sensor.expose(radiance, settings, 42);
  EXPECT_EQ(cv::norm(a, sensor.expose(radiance, settings, 42), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, sensor.expose(radiance, settings, 43), cv::NORM_INF), 0.0);
}

TEST(CameraSensor, MeanSignalIsTheNoiseFreeMean) {
  const CameraSensorOptions options;
  const CameraSensor sensor(CameraRays(quarterCamera()), options);
  const ExposureSettings settings{options.saturation_exposure_time_s, 6.0};
  // 0.2 of the well at 6 dB: K mu_e = 1.995 x 0.2 x 255 = 101.8 DN everywhere.
  EXPECT_NEAR(sensor.meanSignal_dn(flatOnTheSensor(sensor, 0.2f), settings),
              sensor.systemGain_dn_per_e(6.0) * 0.2 * options.full_well_e, 1e-3);
  // Past the well every pixel reads 255.
  EXPECT_NEAR(sensor.meanSignal_dn(flatOnTheSensor(sensor, 2.0f), settings), 255.0, 1e-3);
}

// The exception names the option and its value.
void expectRejected(const CameraSensorOptions& options, const ExposureSettings& settings,
                    const std::string& named) {
  try {
    const CameraSensor sensor(CameraRays(quarterCamera()), options);
    sensor.expose(cv::Mat(120, 160, CV_32FC1, cv::Scalar(0.5f)), settings, 1);
    ADD_FAILURE() << "accepted " << named;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(CameraSensor, RejectsInvalidOptionsNamingThem) {
  const ExposureSettings valid{0.001, 0.0};
  CameraSensorOptions options;
  options.full_well_e = 0.0;
  expectRejected(options, valid, "full_well_e must be > 0 (got 0)");
  options = CameraSensorOptions{};
  options.read_noise_e = -1.0;
  expectRejected(options, valid, "read_noise_e must be >= 0 (got -1)");
  options = CameraSensorOptions{};
  options.saturation_exposure_time_s = -0.001;
  expectRejected(options, valid, "saturation_exposure_time_s must be > 0 (got -0.001)");
  expectRejected(CameraSensorOptions{}, {0.0, 0.0}, "exposure_time_s must be > 0 (got 0)");
  expectRejected(CameraSensorOptions{}, {0.001, -3.0}, "gain_db must be >= 0 (got -3)");
}

}  // namespace
}  // namespace lineloc

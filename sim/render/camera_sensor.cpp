#include "sim/render/camera_sensor.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string_view>

namespace lineloc {
namespace {

constexpr double kMaxDn = 255.0;

void require(bool valid, std::string_view option, double value, std::string_view bound) {
  if (!valid) {
    throw std::invalid_argument(
        fmt::format("camera sensor: {} must be {} (got {})", option, bound, value));
  }
}

const CameraSensorOptions& validated(const CameraSensorOptions& options) {
  require(options.full_well_e > 0.0, "full_well_e", options.full_well_e, "> 0");
  require(options.read_noise_e >= 0.0, "read_noise_e", options.read_noise_e, ">= 0");
  require(options.saturation_exposure_time_s > 0.0, "saturation_exposure_time_s",
          options.saturation_exposure_time_s, "> 0");
  return options;
}

cv::Mat cosineFourth(const CameraRays& rays) {
  cv::Mat vignetting(rays.height(), rays.width(), CV_32FC1);
  for (int v = 0; v < rays.height(); ++v) {
    for (int u = 0; u < rays.width(); ++u) {
      const float cos_theta = rays.direction(u, v).z();
      vignetting.at<float>(v, u) = cos_theta * cos_theta * cos_theta * cos_theta;
    }
  }
  return vignetting;
}

}  // namespace

CameraSensor::CameraSensor(const CameraRays& rays, const CameraSensorOptions& options)
    : options_(validated(options)), vignetting_(cosineFourth(rays)) {}

double CameraSensor::systemGain_dn_per_e(double gain_db) const {
  return std::pow(10.0, gain_db / 20.0) * kMaxDn / options_.full_well_e;
}

cv::Mat CameraSensor::photoElectrons(const cv::Mat& radiance,
                                     const ExposureSettings& settings) const {
  require(settings.exposure_time_s > 0.0, "exposure_time_s", settings.exposure_time_s, "> 0");
  require(settings.gain_db >= 0.0, "gain_db", settings.gain_db, ">= 0");
  if (radiance.type() != CV_32FC1 || radiance.size() != vignetting_.size()) {
    throw std::invalid_argument(fmt::format("camera sensor: radiance must be {}x{} CV_32FC1",
                                            vignetting_.cols, vignetting_.rows));
  }
  const double electrons_per_radiance =
      options_.full_well_e * settings.exposure_time_s / options_.saturation_exposure_time_s;
  return radiance.mul(vignetting_, electrons_per_radiance);
}

double CameraSensor::meanSignal_dn(const cv::Mat& radiance,
                                   const ExposureSettings& settings) const {
  cv::Mat signal_dn;
  cv::min(photoElectrons(radiance, settings), options_.full_well_e, signal_dn);
  signal_dn *= systemGain_dn_per_e(settings.gain_db);
  cv::min(signal_dn, kMaxDn, signal_dn);
  return cv::mean(signal_dn)[0];
}

cv::Mat CameraSensor::expose(const cv::Mat& radiance, const ExposureSettings& settings,
                             uint64_t noise_seed) const {
  const cv::Mat mean_e = photoElectrons(radiance, settings);
  cv::Mat shot(mean_e.size(), CV_32FC1);
  cv::Mat read(mean_e.size(), CV_32FC1);
  cv::RNG rng(noise_seed);
  rng.fill(shot, cv::RNG::NORMAL, 0.0, 1.0);
  rng.fill(read, cv::RNG::NORMAL, 0.0, options_.read_noise_e);
  cv::Mat shot_sigma_e;
  cv::sqrt(mean_e, shot_sigma_e);
  cv::Mat electrons = mean_e + shot.mul(shot_sigma_e);
  cv::min(electrons, options_.full_well_e, electrons);
  electrons += read;
  // convertTo rounds to nearest and saturates to [0, 255].
  cv::Mat image;
  electrons.convertTo(image, CV_8UC1, systemGain_dn_per_e(settings.gain_db));
  return image;
}

}  // namespace lineloc

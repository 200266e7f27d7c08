#include "sim/render/camera_sensor.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
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

// Omega at (u, v): |d_u x d_v . d| by central differences (one-sided at the
// border); 0 where a neighbour has no ray.
float solidAngle(const CameraRays& rays, int u, int v) {
  const int u0 = std::max(u - 1, 0), u1 = std::min(u + 1, rays.width() - 1);
  const int v0 = std::max(v - 1, 0), v1 = std::min(v + 1, rays.height() - 1);
  const Eigen::Vector3f& d = rays.direction(u, v);
  for (const Eigen::Vector3f* neighbour : {&rays.direction(u0, v), &rays.direction(u1, v),
                                           &rays.direction(u, v0), &rays.direction(u, v1)}) {
    if (neighbour->isZero() || d.isZero()) {
      return 0.0f;
    }
  }
  const Eigen::Vector3f d_u =
      (rays.direction(u1, v) - rays.direction(u0, v)) / static_cast<float>(u1 - u0);
  const Eigen::Vector3f d_v =
      (rays.direction(u, v1) - rays.direction(u, v0)) / static_cast<float>(v1 - v0);
  return std::abs(d_u.cross(d_v).dot(d));
}

cv::Mat relativeIllumination(const CameraRays& rays) {
  cv::Mat vignetting(rays.height(), rays.width(), CV_32FC1);
  if (rays.lens() == LensModel::kRadialTangential) {
    for (int v = 0; v < rays.height(); ++v) {
      for (int u = 0; u < rays.width(); ++u) {
        const float cos_theta = rays.direction(u, v).z();
        vignetting.at<float>(v, u) = cos_theta * cos_theta * cos_theta * cos_theta;
      }
    }
    return vignetting;
  }
  float on_axis = 0.0f;
  for (int v = 0; v < rays.height(); ++v) {
    for (int u = 0; u < rays.width(); ++u) {
      const float cos_theta = std::max(rays.direction(u, v).z(), 0.0f);
      const float omega = solidAngle(rays, u, v);
      vignetting.at<float>(v, u) = cos_theta * omega;
      on_axis = std::max(on_axis, cos_theta > 0.9999f ? omega : 0.0f);
    }
  }
  // The principal point need not fall on a pixel: the brightest pixel near
  // the axis stands for Omega_0 when none is within 0.8 degrees of it.
  if (on_axis == 0.0f) {
    double largest = 0.0;
    cv::minMaxLoc(vignetting, nullptr, &largest);
    return vignetting / largest;
  }
  return vignetting / on_axis;
}

}  // namespace

CameraSensor::CameraSensor(const CameraRays& rays, const CameraSensorOptions& options)
    : options_(validated(options)), vignetting_(relativeIllumination(rays)) {}

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

// A CMOS machine-vision sensor after the linear camera model of EMVA Standard
// 1288 (Release 3.1, §2): radiance in, 8-bit digital numbers (DN) out.
//
//   mu_e = full_well_e V (L t / saturation_exposure_time_s)   photo-electrons,
//   e    = min(full_well_e, mu_e + sqrt(mu_e) n_shot) + read_noise_e n_read,
//   y    = clamp(round(K e), 0, 255),  K = 10^(gain_db / 20) 255 / full_well_e,
//
// with L the scene radiance (1 = a white Lambertian surface in full sun), t the
// exposure time, V the relative illumination of the pixel (vignetting, below),
// n_shot, n_read independent standard normal draws (the Gaussian limit of the
// Poisson shot noise, variance mu_e), and K the system gain in DN per electron:
// at 0 dB the full well spans the 8-bit range, an analogue gain of g dB scales
// it by 10^(g/20). Below saturation the DN follow EMVA 1288's mean and photon
// transfer with no dark signal (mu_y.dark = 0),
//   mu_y = K mu_e,  sigma_y^2 = K^2 read_noise_e^2 + K (mu_y - mu_y.dark) + 1/12,
// 1/12 DN^2 the quantisation noise: the noise grows with the signal and the gain.
//
// The defaults are the EMVA 1288 results that camera makers publish for Sony's
// Pregius second generation 3.45 um global-shutter sensors (IMX250, IMX264,
// IMX273): saturation capacity about 10,500 e-, temporal dark noise about
// 2.3 e-, quantum efficiency about 0.7. A white surface under 100 klx of sun
// has the luminance 100,000 / pi cd/m^2 and lights the image through an f/8
// lens with pi L / (4 N^2) = 390 lx; at 555 nm one lux is 4.1e15 photons per
// s and m^2, so a 11.9 um^2 pixel at QE 0.7 collects 1.3e7 e-/s and fills its
// well in 0.8 ms: saturation_exposure_time_s.
//
// Vignetting is a lens's natural falloff: a pixel collects the light of the
// solid angle Omega it sees, through the entrance pupil foreshortened by
// cos(theta) (Kerr, "Derivation of the cosine fourth law for falloff of
// illuminance across a camera image", 2007):
//   V = cos(theta) Omega / Omega_0,  cos(theta) = d_z,
// theta the angle between the pixel's unit ray d (CameraRays, the calibrated
// lens model) and the optical axis, Omega_0 the solid angle on the axis. A
// rectilinear lens (radial-tangential) sees Omega = cos^3(theta) / f^2, the
// cosine-fourth law V = cos^4(theta), which the sensor applies (its
// distortion's change of Omega left out); a fisheye (equidistant) spreads
// its solid angle more evenly and falls off far less: its Omega = |d_u x d_v
// . d| is taken from the rays' change across each pixel.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "sim/render/camera_rays.h"

namespace lineloc {

struct CameraSensorOptions {
  // Saturation capacity of a pixel (e-).
  double full_well_e = 10'500.0;
  // Temporal dark noise (e-).
  double read_noise_e = 2.3;
  // Exposure time in which radiance 1 on the optical axis fills the well (s).
  double saturation_exposure_time_s = 0.0008;
};

// What the camera exposes one frame with.
struct ExposureSettings {
  double exposure_time_s = 0.0;
  // Analogue gain, >= 0 dB.
  double gain_db = 0.0;
};

class CameraSensor {
 public:
  // The sensor behind the lens whose rays are `rays`. Throws
  // std::invalid_argument naming the option for a non-positive full_well_e or
  // saturation_exposure_time_s or a negative read_noise_e.
  CameraSensor(const CameraRays& rays, const CameraSensorOptions& options);

  // The 8-bit image (CV_8UC1) of a radiance image (CV_32FC1, the rays' size);
  // the noise is drawn from `noise_seed`, so equal inputs give equal bytes.
  // Throws std::invalid_argument for a non-positive exposure time or a
  // negative gain.
  cv::Mat expose(const cv::Mat& radiance, const ExposureSettings& settings,
                 uint64_t noise_seed) const;
  // The mean over the image of the noise-free DN, clamp(K mu_e, 0, 255).
  double meanSignal_dn(const cv::Mat& radiance, const ExposureSettings& settings) const;
  // K (DN per electron) at an analogue gain.
  double systemGain_dn_per_e(double gain_db) const;
  // V per pixel (CV_32FC1): the falloff above, 0
  // where the lens model has no ray.
  const cv::Mat& vignetting() const { return vignetting_; }

 private:
  // mu_e per pixel (CV_32FC1).
  cv::Mat photoElectrons(const cv::Mat& radiance, const ExposureSettings& settings) const;

  CameraSensorOptions options_;
  cv::Mat vignetting_;
};

}  // namespace lineloc

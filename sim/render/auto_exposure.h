// Auto-exposure of a machine-vision camera: meters each frame by its mean DN
// and sets the next frame's exposure time, then its analogue gain, so that the
// mean moves towards a target. The control variable is the exposure product
//   P = t 10^(g / 20)   (s),
// to which the mean DN is proportional below saturation. A frame metered at m
// DN under P gives the next frame
//   P' = clamp(P (target / max(m, 1))^damping, min_exposure_time_s,
//              max_exposure_time_s 10^(max_gain_db / 20)),
// a damped step in log P (damping 1: the whole correction at once; 0.5: the
// log error halves each frame), or P' = P while |m / target - 1| <= tolerance,
// the deadband that keeps a camera from hunting on a steady scene. P' is
// exposed with the longest exposure time it allows,
//   t' = clamp(P', min_exposure_time_s, max_exposure_time_s),
//   g' = 20 log10(P' / t'),
// so the gain, and the noise with it, rises only once the exposure time has
// reached its cap (the motion-blur limit or the frame period).
#pragma once

#include "sim/render/camera_sensor.h"

namespace lineloc {

struct AutoExposureOptions {
  // Mean DN the controller steers each frame to.
  double target_mean_dn = 100.0;
  // Relative deadband around the target.
  double tolerance = 0.05;
  // Fraction of the log error corrected per frame, (0, 1].
  double damping = 0.5;
  double min_exposure_time_s = 1e-5;
  double max_exposure_time_s = 0.002;
  double max_gain_db = 24.0;
};

class AutoExposure {
 public:
  // Starts at `initial`, clamped to the limits. Throws std::invalid_argument
  // naming the option for a target outside (0, 255), a negative tolerance, a
  // damping outside (0, 1], exposure limits not 0 < min <= max, or a negative
  // max_gain_db.
  AutoExposure(const AutoExposureOptions& options, const ExposureSettings& initial);

  // What the next frame is exposed with.
  const ExposureSettings& settings() const { return settings_; }
  // Takes the mean DN of the frame exposed with settings() and sets the next
  // frame's.
  void update(double mean_dn);

 private:
  // Sets settings_ for the exposure product P (s).
  void expose(double exposure_product_s);

  AutoExposureOptions options_;
  ExposureSettings settings_;
};

}  // namespace lineloc

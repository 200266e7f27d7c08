#include "robot/inertial/gnss_error_model.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace lineloc {
namespace {

void requirePositive(double value, const char* name) {
  if (!(value > 0.0 && std::isfinite(value))) {
    throw std::invalid_argument(fmt::format("gnss_{} must be positive, got {}", name, value));
  }
}

}  // namespace

void validate(const GnssErrorModel& model) {
  requirePositive(model.gps_sigma_m, "gps_sigma_m");
  requirePositive(model.dgps_sigma_m, "dgps_sigma_m");
  requirePositive(model.rtk_fixed_sigma_m, "rtk_fixed_sigma_m");
  requirePositive(model.rtk_float_sigma_m, "rtk_float_sigma_m");
  requirePositive(model.vertical_ratio, "vertical_ratio");
}

std::optional<GnssSigmas> gnssSigmas(int quality, double hdop, const GnssErrorModel& model) {
  double sigma_q = 0.0;
  switch (static_cast<GnssFixQuality>(quality)) {
    case GnssFixQuality::kGps:
      sigma_q = model.gps_sigma_m;
      break;
    case GnssFixQuality::kDgps:
      sigma_q = model.dgps_sigma_m;
      break;
    case GnssFixQuality::kRtkFixed:
      sigma_q = model.rtk_fixed_sigma_m;
      break;
    case GnssFixQuality::kRtkFloat:
      sigma_q = model.rtk_float_sigma_m;
      break;
    default:
      return std::nullopt;
  }
  if (!(hdop > 0.0 && std::isfinite(hdop))) {
    return std::nullopt;
  }
  const double horizontal_m = hdop * sigma_q;
  return GnssSigmas{horizontal_m, model.vertical_ratio * horizontal_m};
}

}  // namespace lineloc

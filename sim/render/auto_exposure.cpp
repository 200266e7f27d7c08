#include "sim/render/auto_exposure.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

namespace lineloc {
namespace {

void require(bool valid, std::string_view option, double value, std::string_view bound) {
  if (!valid) {
    throw std::invalid_argument(
        fmt::format("auto-exposure: {} must be {} (got {})", option, bound, value));
  }
}

const AutoExposureOptions& validated(const AutoExposureOptions& options) {
  require(options.target_mean_dn > 0.0 && options.target_mean_dn < 255.0, "target_mean_dn",
          options.target_mean_dn, "in (0, 255)");
  require(options.tolerance >= 0.0, "tolerance", options.tolerance, ">= 0");
  require(options.damping > 0.0 && options.damping <= 1.0, "damping", options.damping, "in (0, 1]");
  require(options.min_exposure_time_s > 0.0, "min_exposure_time_s", options.min_exposure_time_s,
          "> 0");
  require(options.max_exposure_time_s >= options.min_exposure_time_s, "max_exposure_time_s",
          options.max_exposure_time_s,
          fmt::format(">= min_exposure_time_s ({})", options.min_exposure_time_s));
  require(options.max_gain_db >= 0.0, "max_gain_db", options.max_gain_db, ">= 0");
  return options;
}

double gainFactor(double gain_db) {
  return std::pow(10.0, gain_db / 20.0);
}

}  // namespace

AutoExposure::AutoExposure(const AutoExposureOptions& options, const ExposureSettings& initial)
    : options_(validated(options)) {
  expose(initial.exposure_time_s * gainFactor(initial.gain_db));
}

void AutoExposure::update(double mean_dn) {
  const double ratio = options_.target_mean_dn / std::max(mean_dn, 1.0);
  if (std::abs(1.0 / ratio - 1.0) <= options_.tolerance) {
    return;
  }
  expose(settings_.exposure_time_s * gainFactor(settings_.gain_db) *
         std::pow(ratio, options_.damping));
}

void AutoExposure::expose(double exposure_product_s) {
  const double product_s =
      std::clamp(exposure_product_s, options_.min_exposure_time_s,
                 options_.max_exposure_time_s * gainFactor(options_.max_gain_db));
  settings_.exposure_time_s =
      std::clamp(product_s, options_.min_exposure_time_s, options_.max_exposure_time_s);
  settings_.gain_db = std::max(0.0, 20.0 * std::log10(product_s / settings_.exposure_time_s));
}

}  // namespace lineloc

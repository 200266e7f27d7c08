#include "robot/vision/lines/segment_validation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lineloc {

SegmentValidation::SegmentValidation(cv::Size image_size, const EdgeNoise& noise,
                                     double max_false_alarms)
    : log10_tests_(2.0 * std::log10(static_cast<double>(image_size.area()))),
      log10_max_false_alarms_(std::log10(max_false_alarms)),
      noise_(noise) {
  if (!(max_false_alarms > 0.0)) {
    throw std::invalid_argument("segment validation: max_false_alarms must be > 0");
  }
}

double SegmentValidation::log10FalseAlarms(const LineSegment& segment) const {
  const double points = segment.moments.n;
  if (!(points > 0.0)) {
    return log10_tests_;
  }
  const double noise_mean = std::sqrt(2.0 / M_PI) * noise_.step_sigma;
  const double mean_sigma = std::sqrt(1.0 - 2.0 / M_PI) * noise_.step_sigma *
                            std::sqrt(std::min(1.0, noise_.correlation_length_px / points));
  const double excess = segment.contrast() - noise_mean;
  if (!(mean_sigma > 0.0)) {
    return excess > 0.0 ? -std::numeric_limits<double>::infinity() : log10_tests_;
  }
  const double tail = 0.5 * std::erfc(excess / (std::sqrt(2.0) * mean_sigma));
  return log10_tests_ + std::log10(tail);
}

bool SegmentValidation::meaningful(const LineSegment& segment) const {
  return log10FalseAlarms(segment) <= log10_max_false_alarms_;
}

}  // namespace lineloc

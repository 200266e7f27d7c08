#include "robot/vision/flow/motion_detector.h"

#include <fmt/format.h>

#include <array>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr double kMadToSigma = 1.0 / 0.6745;

// Median of an 8-bit single-channel image from its histogram.
int median8u(const cv::Mat& image) {
  std::array<size_t, 256> histogram{};
  for (int y = 0; y < image.rows; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      ++histogram[row[x]];
    }
  }
  const size_t half = (image.total() + 1) / 2;
  size_t seen = 0;
  for (int value = 0; value < 256; ++value) {
    seen += histogram[value];
    if (seen >= half) {
      return value;
    }
  }
  return 255;
}

}  // namespace

MotionMask detectMotion(const cv::Mat& previous, const cv::Mat& current,
                        const MotionOptions& options) {
  if (previous.empty() || current.empty()) {
    throw std::invalid_argument(fmt::format("motion detection: the {} frame is empty",
                                            previous.empty() ? "previous" : "current"));
  }
  if (previous.size() != current.size() || previous.type() != current.type() ||
      (previous.type() != CV_8UC1 && previous.type() != CV_8UC3)) {
    throw std::invalid_argument(fmt::format(
        "motion detection: frames must be 8-bit, 1 or 3 channels, of the same size and type "
        "(got {}x{} and {}x{})",
        previous.cols, previous.rows, current.cols, current.rows));
  }
  cv::Mat difference;
  cv::absdiff(previous, current, difference);
  if (difference.channels() == 3) {
    difference = difference.reshape(1, static_cast<int>(difference.total()));
    cv::reduce(difference, difference, 1, cv::REDUCE_MAX);
    difference = difference.reshape(1, previous.rows);
  }
  MotionMask mask;
  mask.noise_sigma = median8u(difference) * kMadToSigma;
  mask.threshold = std::max(options.threshold_sigmas * mask.noise_sigma, options.threshold_floor);
  mask.moving = difference > mask.threshold;
  return mask;
}

}  // namespace lineloc

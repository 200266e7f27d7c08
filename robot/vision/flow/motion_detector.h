// Motion detection by frame differencing (Persa & Jonker §4: flow is only
// estimated where motion is detected), with a threshold that adapts to the
// camera's noise.
//
// D(x) = max over channels |I_1(x) - I_0(x)|. Where nothing moves D is the
// difference of two noises, of standard deviation sigma_D; for a normal
// noise median|D| = 0.6745 sigma_D, so while fewer than half the pixels move
//
//   sigma_D = median(D) / 0.6745,   moving(x) = D(x) > max(k sigma_D, floor).
#pragma once

#include <opencv2/core.hpp>

namespace lineloc {

struct MotionOptions {
  double threshold_sigmas = 3.0;  // k
  double threshold_floor = 6.0;   // grey levels, for noise-free (synthetic) frames
};

struct MotionMask {
  cv::Mat moving;            // CV_8U, 255 where D > threshold
  double noise_sigma = 0.0;  // sigma_D, grey levels
  double threshold = 0.0;
};

// Frames: same size, CV_8UC1 or CV_8UC3, not empty; throws
// std::invalid_argument naming the problem otherwise.
MotionMask detectMotion(const cv::Mat& previous, const cv::Mat& current,
                        const MotionOptions& options = {});

}  // namespace lineloc

// A contrario validation of line segments against the image's noise
// (Helmholtz principle: Desolneux, Moisan & Morel, IJCV 40(1), 2000; as in
// LSD, von Gioi et al., PAMI 32(4), 2010, and EDLines, Akinlar & Topal,
// Pattern Recognition Letters 32(13), 2011).
//
// H0: the image is white Gaussian noise of sigma (noise_estimate.h). Under
// H0 each point's step is N(0, step_sigma^2) (EdgeNoise, edge_detector.h),
// its magnitude half-normal with mean sqrt(2 / pi) step_sigma and standard
// deviation sqrt(1 - 2 / pi) step_sigma, and a segment's contrast c, the
// mean magnitude over n points, is by the central limit theorem Gaussian with
//   mu_0 = sqrt(2 / pi) step_sigma,
//   s_n = sqrt(1 - 2 / pi) step_sigma sqrt(min(1, correlation_length_px / n)).
// Its number of false alarms is the number of segments an image holds times
// the probability that noise alone steps as much:
//   NFA = N_tests P(Z >= (c - mu_0) / s_n) = N_tests erfc((c - mu_0) / (sqrt(2) s_n)) / 2,
// N_tests = (W H)^2, the segments between two pixels of a W x H image
// (EDLines, sec. 2.4: N^4 for an N x N image). A segment is kept when
// NFA <= max_false_alarms (epsilon): then an image of pure noise yields at
// most epsilon segments in expectation, and the contrast a segment needs
// scales with sigma.
#pragma once

#include <opencv2/core.hpp>

#include "robot/vision/edges/edge_detector.h"
#include "robot/vision/lines/line_segment.h"

namespace lineloc {

class SegmentValidation {
 public:
  // Throws std::invalid_argument unless max_false_alarms > 0.
  SegmentValidation(cv::Size image_size, const EdgeNoise& noise, double max_false_alarms);

  // log10 NFA of `segment` (its contrast() over moments.n points).
  double log10FalseAlarms(const LineSegment& segment) const;
  bool meaningful(const LineSegment& segment) const;

 private:
  double log10_tests_;
  double log10_max_false_alarms_;
  EdgeNoise noise_;
};

}  // namespace lineloc

// Förstner's corner operator (Förstner, "A Framework for Low Level Feature
// Extraction", ECCV 1994; Förstner & Gülch 1987), used by Persa & Jonker §3.
//
// Structure tensor over a (2r+1)^2 window W, g the image gradient:
//   N = sum_W g g^T = [a b; b c]
// Weight (inverse size of the error ellipse) and roundness:
//   w = det N / tr N,    q = 4 det N / (tr N)^2  in [0, 1]
// A pixel is a candidate when q >= min_roundness and w >= max(min_weight,
// weight_factor x mean w over the image), and the maximum of w in its
// (2s+1)^2 neighbourhood (non-maximum suppression). Its sub-pixel position is
// the weighted least-squares intersection of the lines through each pixel p
// of W normal to g(p):
//   x = N^-1 sum_W g g^T p,
// with covariance sigma0^2 N^-1, sigma0^2 = sum_W (g^T (x - p))^2 / (|W| - 2),
// over a (2 refine_radius + 1)^2 window W.
// On a blurred corner the gradients near the tip point between the two edge
// normals and pull x along the bisector by a fraction of the blur; so x is
// solved again without the pixels within core_radius of the first estimate,
// leaving the straight edge flanks, whose lines pass through the corner.
//
// The tensor is summed exactly in integers (products g g^T rounded to 1/16 of
// the gradient unit squared, box sums by running column sums), w and q in
// floats, all SIMD through Highway, dispatched at run time to the best
// instruction set the processor has, down to plain scalar code. The
// refinement needs one pass over its window: the sums
// sum g g^T (1, p, p p^T) give x, and with them the residual
// sum (g^T (x - p))^2 = x^T N x - 2 x^T sum g g^T p + sum p^T g g^T p;
// the second solve subtracts the core's pixels. Buffers are reused.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc {

struct ForstnerOptions {
  int window_radius_px = 2;       // r: the tensor window is (2r+1)^2, r in [1, 5]
  int suppression_radius_px = 3;  // s
  int refine_radius_px = 5;       // window of the sub-pixel intersection
  double core_radius_px = 2.5;    // left out around the first estimate
  double min_roundness = 0.5;     // q threshold, Förstner's 0.5..0.75
  double weight_factor = 2.0;     // w threshold relative to the mean w
  double min_weight = 4.0;        // absolute w floor, (grey levels / px)^2
  int max_corners = 512;          // the strongest are kept
};

struct ForstnerCorner {
  Eigen::Vector2f position;    // distorted pixel coordinates
  Eigen::Matrix2f covariance;  // px^2
  float weight;                // w at the pixel
};

class ForstnerDetector {
 public:
  // Throws std::invalid_argument for out-of-range options.
  explicit ForstnerDetector(const ForstnerOptions& options);

  // `gradient_x`, `gradient_y`: CV_16S gradient images, `gain` x grey levels
  // per px, |g| <= 2^14 (EdgeDetector's). Corners come strongest first.
  void detect(const cv::Mat& gradient_x, const cv::Mat& gradient_y, float gain);

  // The same, row by row while the gradient is being computed (its rows still
  // in cache): begin(), addRow(y) for y = 0, 1, ... once rows 0..y of the
  // gradient are complete, finish() after the last.
  void begin(cv::Size size, float gain);
  void addRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y);
  void finish(const cv::Mat& gradient_x, const cv::Mat& gradient_y);

  const std::vector<ForstnerCorner>& corners() const { return corners_; }

 private:
  struct Candidate {
    int x, y;
    float weight;
  };
  struct Offset {
    int dx, dy;
  };

  int weightRingRows() const;
  float* weightRow(int y);
  void suppressNonMaxima(int y);
  bool refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y, const Candidate& candidate,
              ForstnerCorner& corner) const;

  ForstnerOptions options_;
  cv::Size size_;
  float gain_ = 1.0f;
  std::vector<int32_t> column_sums_;  // a, b, c column sums over 2r + 1 rows
  std::vector<float> weight_rows_;    // w of the last 2s + 1 rows, row y at y % (2s + 1)
  double weight_sum_ = 0.0;
  std::vector<Offset> neighbourhood_;  // the 2s (2s+1) neighbours in other rows, nearest first
  std::vector<const float*> suppression_rows_;
  std::vector<int32_t> row_candidates_;
  std::vector<Candidate> candidates_;
  std::vector<ForstnerCorner> corners_;
};

}  // namespace lineloc

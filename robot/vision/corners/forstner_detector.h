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
// The tensor is summed exactly in integers (products of the gradient in
// units of 1/32 grey level per px, box sums by running column sums), w and q
// in floats, all SIMD through Highway, dispatched at run time to the best
// instruction set the processor has, down to plain scalar code. The
// refinement sums g g^T (1, p) over its window (SIMD), and the second solve
// subtracts the core's sums. Buffers are reused.
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

  int weightRingRows() const;
  float candidateFloor() const;
  float* weightRow(int y);
  float* rowMaximumRow(int y);
  void suppressNonMaxima(int y);
  bool refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y, const Candidate& candidate,
              ForstnerCorner& corner);

  ForstnerOptions options_;
  cv::Size size_;
  float gain_ = 1.0f;
  double tensor_scale_ = 1.0;            // (grey levels / px)^2 per unit of the integer tensor
  std::vector<int32_t> column_sums_;     // a, b, c column sums over 2r + 1 rows
  std::vector<float> weight_rows_;       // w of the last 2s + 1 rows, row y at y % (2s + 1)
  std::vector<float> row_maximum_rows_;  // their maxima over 2s + 1 columns
  std::vector<float> row_peaks_;         // the largest w of each, 0 when below the floor
  std::vector<float> zero_row_;
  double weight_sum_ = 0.0;                     // of w in tensor units
  std::vector<const float*> suppression_rows_;  // row maxima of the 2s + 1 rows, own row first
  std::vector<int32_t> column_numbers_;         // 0, 1, ..., width - 1
  std::vector<int32_t> row_candidates_;         // kCompressSlack to spare
  std::vector<Candidate> candidates_;
  // The refinement window, row by row: pixel offsets and gradient (grey
  // levels per px), padded to a whole number of vectors.
  std::vector<float> window_u_, window_v_, window_gx_, window_gy_;
  std::vector<ForstnerCorner> corners_;
};

}  // namespace lineloc

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
// Tensor sums are running sums in loops the compiler vectorises; buffers are reused.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace lineloc {

struct ForstnerOptions {
  int window_radius_px = 2;       // r: the tensor window is (2r+1)^2
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

  // `gradient_x`, `gradient_y`: CV_16S Sobel responses (8 x grey levels / px),
  // as EdgeDetector makes them. Corners come strongest first.
  void detect(const cv::Mat& gradient_x, const cv::Mat& gradient_y);

  const std::vector<ForstnerCorner>& corners() const { return corners_; }

 private:
  void computeProducts(const cv::Mat& gradient_x, const cv::Mat& gradient_y);
  float computeWeights(const cv::Mat& gradient_x, const cv::Mat& gradient_y);
  void addRow(int y, float sign, size_t plane, int width);
  void collectCandidates(float min_weight);
  bool isLocalMaximum(int x, int y) const;
  bool refine(const cv::Mat& gradient_x, const cv::Mat& gradient_y, int x, int y,
              ForstnerCorner& corner) const;

  struct Candidate {
    int x, y;
    float weight;
  };

  ForstnerOptions options_;
  std::vector<Candidate> candidates_;
  std::vector<float> products_;  // gx^2, gx gy, gy^2 planes
  std::vector<float> column_sums_, tensor_row_;
  cv::Mat weight_;
  std::vector<ForstnerCorner> corners_;
};

}  // namespace lineloc

// Sub-pixel edge points with gradient direction and grey-level step, on 8-bit
// grey images (Persa & Jonker §3: the edges that become straight lines).
//
// Gaussian pre-smoothing (gaussian_smoother.h) and OpenCV's 3x3 Sobel
// gradient g = (gx, gy) (SIMD). A pixel is an edge point when |g| >= min_gradient and |g| is
// a strict maximum along the gradient direction quantised to 0, 45, 90 or 135
// degrees (non-maximum suppression). Its sub-pixel position is the peak of the
// Gaussian through the three magnitudes along that direction d (a parabola
// through l = ln |g|^2, exact for a blurred step, whose |g| is a Gaussian):
//   p = pixel + delta d,  delta = (l- - l+) / (2 (l- - 2 l0 + l+)),  |delta| <= 1/2,
// which lies on the edge for any d that crosses it, because |g| across a
// straight blurred step is symmetric about the step. The grey-level step is
// I(p + 3d) - I(p - 3d) in the smoothed image, d pointing dark -> bright: for
// a step of height h blurred to sigma s in all, h erf(3 / (sqrt(2) s)).
//
// Buffers are kept between calls: no allocation once the image size is stable.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "robot/vision/edges/gaussian_smoother.h"

namespace lineloc {

struct EdgePoint {
  Eigen::Vector2f position;  // sub-pixel, distorted image, pixel centres at integers
  Eigen::Vector2f gradient;  // grey levels per pixel, pointing dark -> bright
  Eigen::Vector2f normal;    // gradient / |gradient|
  float step;                // grey-level step across the edge (bright - dark)
  int pixel_x, pixel_y;      // the pixel it was found at
};

struct EdgeDetectorOptions {
  double smoothing_sigma_px = 1.0;  // Gaussian pre-smoothing; 0 disables it
  float min_gradient = 8.0f;        // grey levels per pixel
};

class EdgeDetector {
 public:
  // Throws std::invalid_argument for a negative sigma or a non-positive threshold.
  explicit EdgeDetector(const EdgeDetectorOptions& options);

  // `grey`: CV_8UC1, at least 5 x 5 (checked by the caller). Edge points are
  // found at least 3 px from the border.
  void detect(const cv::Mat& grey);

  const std::vector<EdgePoint>& points() const { return points_; }
  // CV_32S, the index of the edge point found at each pixel in points(), or -1.
  const cv::Mat& pointIndex() const { return point_index_; }
  // CV_16S Sobel responses, 8 x grey levels per pixel.
  const cv::Mat& gradientX() const { return gradient_x_; }
  const cv::Mat& gradientY() const { return gradient_y_; }

 private:
  void computeSquaredMagnitude();
  void suppressNonMaxima();

  EdgeDetectorOptions options_;
  std::optional<GaussianSmoother> smoother_;
  int64_t min_squared_sobel_;
  cv::Mat smoothed_, gradient_x_, gradient_y_, squared_magnitude_, point_index_;
  std::vector<EdgePoint> points_;
};

}  // namespace lineloc

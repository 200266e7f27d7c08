// Sub-pixel edge points with gradient direction and grey-level step, on 8-bit
// grey images (Persa & Jonker §3: the edges that become straight lines).
//
// Gaussian pre-smoothing (gaussian_smoother.h) and the 3x3 Sobel gradient
// g = (gx, gy), zero on the 1 px image border. A pixel is an edge point when
// |g| >= t and |g| is a maximum along the gradient direction
// quantised to 0, 45, 90 or 135 degrees (non-maximum suppression: strictly
// above the neighbour on the dark side, at least the one on the bright side).
// The threshold follows the image's noise sigma (noise_estimate.h): noise
// alone makes |g| Rayleigh, P(|g| > t) = exp(-t^2 / (2 sigma_g^2)), sigma_g
// that of each component (EdgeNoise), so that a W x H image expects one
// edge pixel from noise at
//   t = max(min_gradient, sigma_g sqrt(2 ln(W H))).
// min_gradient, the floor, is there for renders: their only noise is 8-bit
// rounding, which is not white on smooth shading and would else put edges
// on it.
// Its sub-pixel position is the peak of the
// Gaussian through the three magnitudes along that direction d (a parabola
// through l = ln |g|^2, exact for a blurred step, whose |g| is a Gaussian):
//   p = pixel + delta d,  delta = (l- - l+) / (2 (l- - 2 l0 + l+)),  |delta| <= 1/2,
// which lies on the edge for any d that crosses it, because |g| across a
// straight blurred step is symmetric about the step. The grey-level step is
// I(p + 3d) - I(p - 3d) in the smoothed image, d pointing dark -> bright: for
// a step of height h blurred to sigma s in all, h erf(3 / (sqrt(2) s)).
//
// Each point is also linked to its neighbours along the edge (next(),
// previous(), for EdgeLinker), found while their rows are at hand: among the
// 8-neighbours whose gradient turns by at most max_link_turn
// (g1.g2 >= cos(max_link_turn) |g1| |g2|), the nearest ahead of it along the
// tangent t = (-gy, gx) / |g| and the nearest behind it (neighbour_steps.h);
// p -> q is a link when q is p's neighbour ahead and p is q's neighbour
// behind, as in the chaining of the Canny/Devernay detector (von Gioi &
// Randall, IPOL 2017), so links stop at corners, at polarity flips and at
// junctions.
//
// One pass over the rows computes the gradient, |g|^2, the suppression and
// the neighbours together (three rows of |g|^2 and of point indices in
// flight), SIMD through Highway, dispatched at run time to the best
// instruction set the processor has, down to plain scalar code; only the
// surviving pixels are handled one by one.
// Buffers are kept between calls: no allocation once the image size is stable.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "robot/vision/edges/gaussian_smoother.h"
#include "robot/vision/edges/neighbour_steps.h"

namespace lineloc {

struct EdgePoint {
  Eigen::Vector2f position;  // sub-pixel, distorted image, pixel centres at integers
  Eigen::Vector2f gradient;  // grey levels per pixel, pointing dark -> bright
  Eigen::Vector2f normal;    // gradient / |gradient|
  float step;                // grey-level step across the edge (bright - dark)
  int pixel_x, pixel_y;      // the pixel it was found at
};

struct EdgeDetectorOptions {
  double smoothing_sigma_px = 1.0;  // Gaussian pre-smoothing, >= 0.5; 0 disables it
  float min_gradient = 8.0f;        // grey levels per pixel, the threshold's floor
  double max_link_turn_rad = 0.3;   // largest gradient turn between linked neighbours, < pi/2
};

// What white Gaussian noise of standard deviation sigma in the grey image
// becomes in EdgeDetector's measurements; w is the smoothing kernel (1D, sum
// 1; w = (1) without smoothing), rho(k) = (w * w)(k) / sum w^2 the smoothed
// noise's autocorrelation at k px along an axis:
//   gradient_sigma = sigma ||w * (1 2 1) / 4|| ||w * (-1 0 1) / 2||   (each of gx, gy)
//   step_sigma = sigma sum w^2 sqrt(2 (1 - rho(6)))   (smoothed samples 6 px apart)
//   correlation_length_px = sum_k rho(k) = 1 / sum w^2,
// so that the mean step of n points along an edge has variance
// step_sigma^2 min(1, correlation_length_px / n).
struct EdgeNoise {
  double image_sigma = 0.0;     // grey levels
  double gradient_sigma = 0.0;  // grey levels per pixel
  double step_sigma = 0.0;      // grey levels
  double correlation_length_px = 1.0;
};

// Working storage of EdgeDetector's SIMD passes: the pixels of one row that
// survive non-maximum suppression (column, |g|^2 there and behind and ahead
// along d, d) and their sub-pixel offset along d and 1 / |g|; each array
// has kCompressSlack elements to spare (simd/compress_slack.h).
struct EdgeRowMaxima {
  std::vector<int32_t> x, here, before, after, direction_x, direction_y;
  std::vector<float> offset, inverse_magnitude;
  int count = 0;
};

// Told of the gradient of each image row as soon as EdgeDetector has it, top
// to bottom, so that other operators on the gradient run while its rows are
// still in cache.
class GradientRowListener {
 public:
  virtual ~GradientRowListener() = default;
  // Rows 0..y of `gradient_x`, `gradient_y` are complete.
  virtual void gradientRow(int y, const cv::Mat& gradient_x, const cv::Mat& gradient_y) = 0;
};

class EdgeDetector {
 public:
  // gradientX(), gradientY() hold gain x grey levels per px: Sobel (8 x the
  // slope) of the smoothed image kept with 4 fractional bits.
  static constexpr float kGradientGain = 128.0f;

  // Throws std::invalid_argument for a sigma in (0, 0.5) or below 0, a
  // threshold outside (0, 255] or a turn outside (0, pi/2).
  explicit EdgeDetector(const EdgeDetectorOptions& options);

  // `grey`: CV_8UC1, at least 7 x 7 (checked by the caller), with white
  // noise of `noise_sigma` grey levels. Edge points are found at least 3 px
  // from the border. `listener`, if given, is told of every gradient row.
  void detect(const cv::Mat& grey, double noise_sigma, GradientRowListener* listener = nullptr);

  // The noise of the measurements for noise of `image_sigma` in the image.
  EdgeNoise noise(double image_sigma) const;

  // In raster order of their pixels.
  const std::vector<EdgePoint>& points() const { return points_; }
  // For each point, the linked neighbour along +t and along -t (see above), or -1.
  const std::vector<int32_t>& next() const { return next_; }
  const std::vector<int32_t>& previous() const { return previous_; }
  // CV_16S Sobel responses, kGradientGain x grey levels per pixel, zero on
  // the 1 px border.
  const cv::Mat& gradientX() const { return gradient_x_; }
  const cv::Mat& gradientY() const { return gradient_y_; }

 private:
  void prepareBuffers(cv::Size size);
  void smoothRow(const cv::Mat& grey, int y);
  int32_t* squaredMagnitudeRow(int y);
  int32_t* pointIndexRow(int y);
  int occupancyRowBytes() const;
  uint8_t* occupancyRow(int y);
  Eigen::Vector2f* normalRow(int y);
  void startRow(int y);
  void addPoints(int y);
  void findNeighbours(int y);

  EdgeDetectorOptions options_;
  std::optional<GaussianSmoother> smoother_;
  EdgeNoise unit_noise_;  // for image_sigma = 1
  int32_t min_squared_sobel_;
  float cos_max_turn_;
  NeighbourSteps neighbour_steps_;
  cv::Mat smoothed_, gradient_x_, gradient_y_;
  std::vector<int32_t> squared_magnitude_rows_;  // 3 rows, row y at y % 3
  std::vector<int32_t> point_index_rows_;        // 3 rows of point indices or -1, row y at y % 3
  std::vector<int32_t> no_points_;               // a row of -1
  std::vector<uint8_t> occupancy_rows_;          // the same 3 rows, 1 bit per pixel: a point?
  std::vector<Eigen::Vector2f> normal_rows_;     // the same 3 rows, the points' normals
  std::vector<int32_t> first_point_of_row_;
  std::vector<int32_t> nearest_ahead_, nearest_behind_;  // per point, or -1
  std::vector<int32_t> next_, previous_;
  std::vector<int32_t> column_numbers_;  // 0, 1, ..., width - 1
  EdgeRowMaxima maxima_;
  std::vector<EdgePoint> points_;
};

}  // namespace lineloc

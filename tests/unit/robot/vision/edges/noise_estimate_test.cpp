#include "robot/vision/edges/noise_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace lineloc {
namespace {

// Grey levels `background` plus white Gaussian noise of `sigma`, rounded to 8
// bits: the image's noise is then sqrt(sigma^2 + 1/12), rounding's variance
// being 1/12.
cv::Mat noisy(const cv::Mat& background, double sigma, uint64_t seed) {
  cv::Mat noise(background.size(), CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat sum;
  background.convertTo(sum, CV_32F);
  sum += noise;
  cv::Mat grey;
  sum.convertTo(grey, CV_8U);
  return grey;
}

double imageSigma(double sigma) {
  return std::sqrt(sigma * sigma + 1.0 / 12.0);
}

// Squares of 40 px alternating between 70 and 180 grey levels: edges on 5 %
// of the pixels.
cv::Mat checkerboard() {
  cv::Mat board(480, 640, CV_8U);
  for (int y = 0; y < board.rows; ++y) {
    for (int x = 0; x < board.cols; ++x) {
      board.at<uint8_t>(y, x) = ((x / 40 + y / 40) % 2) != 0 ? 180 : 70;
    }
  }
  return board;
}

class NoiseEstimateTest : public ::testing::TestWithParam<double> {};

TEST_P(NoiseEstimateTest, FlatImageWithinTenPercent) {
  const double sigma = GetParam();
  NoiseEstimator estimator;
  const double estimate = estimator.estimate(noisy(cv::Mat(480, 640, CV_8U, 128), sigma, 7));
  EXPECT_NEAR(estimate, imageSigma(sigma), 0.1 * imageSigma(sigma));
}

TEST_P(NoiseEstimateTest, EdgesDoNotInflateIt) {
  const double sigma = GetParam();
  NoiseEstimator estimator;
  const double estimate = estimator.estimate(noisy(checkerboard(), sigma, 11));
  EXPECT_NEAR(estimate, imageSigma(sigma), 0.1 * imageSigma(sigma));
}

INSTANTIATE_TEST_SUITE_P(Sigmas, NoiseEstimateTest, ::testing::Values(1.0, 2.0, 5.0, 10.0));

// The median |r| falls in bin 0, [0, 1/2): sigma < 1/2 / (6 x 0.6745).
TEST(NoiseEstimate, NoiselessImageHasAlmostNone) {
  NoiseEstimator estimator;
  EXPECT_LT(estimator.estimate(checkerboard()), 0.5 / (6.0 * 0.6745));
}

TEST(NoiseEstimate, RejectsRowStepBelowOne) {
  EXPECT_THROW(NoiseEstimator(0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc

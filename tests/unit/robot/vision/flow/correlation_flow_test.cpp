#include "robot/vision/flow/correlation_flow.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/unit/robot/vision/sample_images.h"

namespace lineloc {
namespace {

cv::Mat rubberWhale() {
  return readSampleImage("rubberwhale1.png", cv::IMREAD_COLOR);
}

// current(x) = reference(x - shift), bilinear.
cv::Mat shifted(const cv::Mat& reference, cv::Point2f shift) {
  cv::Mat moved;
  cv::warpAffine(reference, moved, cv::Matx23f(1, 0, shift.x, 0, 1, shift.y), reference.size(),
                 cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return moved;
}

// End-point errors of the known, moving blocks at least R from the border.
std::vector<double> endPointErrors(const FlowField& field, cv::Size size, cv::Point2f truth,
                                   int radius_px) {
  std::vector<double> errors;
  for (const FlowBlock& block : field.blocks) {
    const cv::Rect& r = block.block;
    const bool interior = r.x >= radius_px && r.y >= radius_px &&
                          r.x + r.width + radius_px <= size.width &&
                          r.y + r.height + radius_px <= size.height;
    if (interior && block.moving && block.known) {
      errors.push_back(cv::norm(block.flow_px - truth));
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

// Whole-frame shift of a real colour image: every block moves. Parabola
// fits off by at most 0.086 px per axis on a V-shaped SAD (block_matcher.h's
// test derives it), plus the bilinear warp's low-pass: the median end-point
// error must stay below 0.3 px.
TEST(CorrelationFlow, FullSearchRecoversASyntheticShift) {
  const cv::Mat first = rubberWhale();
  const cv::Point2f truth(2.4f, -1.3f);
  FlowOptions options;
  options.search_radius_px = 6;
  const FlowField field = computeCorrelationFlow(first, shifted(first, truth), options);
  const std::vector<double> errors = endPointErrors(field, first.size(), truth, 6);
  ASSERT_GT(errors.size(), field.blocks.size() / 3);
  RecordProperty("median_epe_px", std::to_string(errors[errors.size() / 2]));
  EXPECT_LT(errors[errors.size() / 2], 0.3);
  EXPECT_LT(errors[errors.size() * 3 / 4], 0.5);
}

// Motion along the expected direction: 1-D search along u, sub-pixel in t.
TEST(CorrelationFlow, LineSearchAlongTheExpectedDirection) {
  const cv::Mat first = rubberWhale();
  const cv::Point2f direction(0.8f, 0.6f);
  const cv::Point2f truth = 3.5f * direction;
  FlowOptions options;
  options.search_radius_px = 8;
  options.expected_direction = direction;
  const FlowField field = computeCorrelationFlow(first, shifted(first, truth), options);
  const std::vector<double> errors = endPointErrors(field, first.size(), truth, 8);
  ASSERT_GT(errors.size(), field.blocks.size() / 4);
  RecordProperty("median_epe_px", std::to_string(errors[errors.size() / 2]));
  EXPECT_LT(errors[errors.size() / 2], 0.3);
}

// Only a moved patch is searched; the rest is flow 0 without a search.
TEST(CorrelationFlow, OnlyBlocksWithDetectedMotionAreSearched) {
  const cv::Mat first = rubberWhale();
  cv::Mat second = first.clone();
  const cv::Rect patch(128, 128, 64, 64);
  first(patch + cv::Point(3, 0)).copyTo(second(patch));  // patch content moves by -3 px
  cv::Mat noise(first.size(), CV_8UC3);
  cv::randu(noise, 0, 3);
  second += noise;
  const FlowField field = computeCorrelationFlow(first, second, FlowOptions{});
  int moving = 0;
  for (const FlowBlock& block : field.blocks) {
    const bool inside = (block.block & patch).area() > 0;
    if (!inside) {
      EXPECT_FALSE(block.moving) << block.block;
      EXPECT_EQ(block.flow_px, cv::Point2f(0, 0));
    }
    moving += block.moving;
  }
  EXPECT_GT(moving, 0);
  EXPECT_LE(moving, 16);
  EXPECT_LT(field.motion.threshold, 20.0);
}

TEST(CorrelationFlow, EveryPathGivesTheScalarResult) {
  cv::Mat first;
  cv::resize(rubberWhale(), first, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  const cv::Mat second = shifted(first, {1.7f, 0.6f});
  FlowOptions options;
  options.search_radius_px = 5;
  const FlowField expected = computeCorrelationFlow(first, second, options, SimdPath::kScalar);
  for (SimdPath path : supportedSimdPaths()) {
    const FlowField field = computeCorrelationFlow(first, second, options, path);
    EXPECT_EQ(cv::countNonZero(field.known != expected.known), 0) << simdPathName(path);
    EXPECT_EQ(cv::norm(field.flow_px, expected.flow_px, cv::NORM_INF), 0.0) << simdPathName(path);
  }
}

TEST(CorrelationFlow, BadInputIsRejectedWithAClearError) {
  const cv::Mat image = rubberWhale();
  EXPECT_THROW(computeCorrelationFlow(cv::Mat(), image, {}), std::invalid_argument);
  EXPECT_THROW(computeCorrelationFlow(image, image(cv::Rect(0, 0, 64, 64)).clone(), {}),
               std::invalid_argument);
  FlowOptions huge;
  huge.block_size_px = 1000;
  EXPECT_THROW(computeCorrelationFlow(image, image, huge), std::invalid_argument);
  FlowOptions no_direction;
  no_direction.expected_direction = cv::Point2f(0, 0);
  cv::Mat moved = image.clone();
  moved(cv::Rect(0, 0, 64, 64)).setTo(cv::Scalar(0, 0, 0));
  EXPECT_THROW(computeCorrelationFlow(image, moved, no_direction), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc

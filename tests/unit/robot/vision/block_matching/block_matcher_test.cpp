#include "robot/vision/block_matching/block_matcher.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace lineloc {
namespace {

cv::Mat randomImage(int width, int height, int type, uint64_t seed) {
  cv::Mat image(height, width, type);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

// Uniform noise blurred with a Gaussian of sigma_px, contrast restored: a
// texture whose SAD surface is smooth and unimodal over a few sigma.
cv::Mat smoothTexture(int width, int height, double sigma_px, uint64_t seed) {
  cv::Mat noise = randomImage(width, height, CV_8UC1, seed), blurred;
  cv::GaussianBlur(noise, blurred, cv::Size(), sigma_px);
  cv::normalize(blurred, blurred, 0, 255, cv::NORM_MINMAX);
  return blurred;
}

// current(x, y) = reference(x - dx, y - dy): blocks move by (+dx, +dy).
cv::Mat shifted(const cv::Mat& reference, double dx, double dy) {
  const cv::Matx23d translation(1, 0, dx, 0, 1, dy);
  cv::Mat moved;
  cv::warpAffine(reference, moved, translation, reference.size(), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  return moved;
}

bool sameMatches(const std::vector<BlockMatch>& a, const std::vector<BlockMatch>& b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].dx != b[i].dx || a[i].dy != b[i].dy ||
        a[i].sad != b[i].sad || a[i].subpixel_dx != b[i].subpixel_dx ||
        a[i].subpixel_dy != b[i].subpixel_dy || a[i].status != b[i].status) {
      return false;
    }
  }
  return true;
}

struct Case {
  int width_px, height_px, radius_px, type;
  SearchStrategy strategy;
};

// Odd frame sizes so that the last blocks' windows are clipped by the image.
TEST(BlockMatcher, EveryPathGivesTheScalarResultOnRandomFrames) {
  const Case cases[] = {{16, 16, 16, CV_8UC1, SearchStrategy::kFull},
                        {16, 16, 7, CV_8UC1, SearchStrategy::kFullEarlyTermination},
                        {8, 8, 9, CV_8UC1, SearchStrategy::kFull},
                        {13, 7, 5, CV_8UC1, SearchStrategy::kDiamond},
                        {16, 16, 16, CV_8UC3, SearchStrategy::kFull},
                        {5, 11, 6, CV_8UC3, SearchStrategy::kThreeStep}};
  for (const Case& c : cases) {
    const cv::Mat reference = randomImage(101, 77, c.type, 3);
    const cv::Mat current = randomImage(101, 77, c.type, 4);
    const BlockMatchingOptions options{c.width_px, c.height_px, c.radius_px, c.strategy};
    const auto expected = BlockMatcher(options, SimdPath::kScalar).matchGrid(reference, current);
    ASSERT_FALSE(expected.empty());
    for (SimdPath path : supportedSimdPaths()) {
      EXPECT_TRUE(sameMatches(BlockMatcher(options, path).matchGrid(reference, current), expected))
          << simdPathName(path) << " block " << c.width_px << "x" << c.height_px;
    }
  }
}

TEST(BlockMatcher, EarlyTerminationFindsTheFullSearchResult) {
  const cv::Mat reference = smoothTexture(160, 120, 1.5, 5);
  const cv::Mat current = shifted(reference, 3, -2) + randomImage(160, 120, CV_8UC1, 6) / 16;
  for (const auto& [width, height] : {std::pair{16, 16}, {8, 8}, {12, 9}}) {
    const BlockMatchingOptions full{width, height, 8, SearchStrategy::kFull};
    BlockMatchingOptions early = full;
    early.strategy = SearchStrategy::kFullEarlyTermination;
    const std::vector<BlockMatch> expected = BlockMatcher(full).matchGrid(reference, current);
    EXPECT_TRUE(sameMatches(BlockMatcher(early).matchGrid(reference, current), expected));
    // One block at a time, early termination runs its spiral of partial SADs
    // also where a grid would run the grid search.
    std::vector<BlockMatch> spiral;
    for (const BlockMatch& match : expected) {
      spiral.push_back(BlockMatcher(early).matchBlock(reference, current, match.x, match.y));
    }
    EXPECT_TRUE(sameMatches(spiral, expected)) << width << "x" << height;
  }
}

TEST(BlockMatcher, IntegerShiftIsFoundExactlyByEveryStrategy) {
  const cv::Mat reference = smoothTexture(192, 144, 4.0, 8);
  const cv::Mat current = shifted(reference, 5, -3);
  for (SearchStrategy strategy : {SearchStrategy::kFull, SearchStrategy::kFullEarlyTermination,
                                  SearchStrategy::kThreeStep, SearchStrategy::kDiamond}) {
    const BlockMatcher matcher({16, 16, 8, strategy});
    const bool exhaustive =
        strategy == SearchStrategy::kFull || strategy == SearchStrategy::kFullEarlyTermination;
    int interior = 0, exact = 0;
    for (const BlockMatch& match : matcher.matchGrid(reference, current)) {
      if (match.x < 16 || match.y < 16 || match.x + 32 > 192 || match.y + 32 > 144) {
        continue;
      }
      ++interior;
      exact += (match.dx == 5 && match.dy == -3 && match.sad == 0);
    }
    ASSERT_GT(interior, 0);
    // Full search is exhaustive; three-step and diamond descend the SAD
    // surface, smooth over a few sigma (4 px) but not unimodal everywhere, so
    // they may stop in a local minimum on a few blocks.
    if (exhaustive) {
      EXPECT_EQ(exact, interior);
    } else {
      EXPECT_GE(exact, 0.9 * interior) << static_cast<int>(strategy);
    }
  }
}

// The SAD of a shift d near the true shift t of a smooth texture is a V,
// |d - t| * sum|gradient|. Through a V sampled at -1, 0, +1 the parabola's
// vertex is at delta / (2 (1 - |delta|)) for a true offset delta: at most
// 0.086 px off per axis (delta ~ 0.3), 0.122 px on both. The median end-point
// error must stay below 0.13 px; the bilinear warp also low-passes the current
// frame, which bends the V of weakly textured blocks, so 95 % of the interior
// blocks must be within 0.3 px (the flow target).
TEST(BlockMatcher, SubpixelShiftIsRecoveredByTheParabolaFit) {
  const cv::Mat reference = smoothTexture(192, 160, 1.5, 9);
  for (const auto& [true_dx, true_dy] : {std::pair{2.3, -1.6}, {-0.5, 0.25}, {4.75, 3.1}}) {
    const cv::Mat current = shifted(reference, true_dx, true_dy);
    std::vector<double> errors;
    for (const BlockMatch& match : BlockMatcher({16, 16, 8}).matchGrid(reference, current)) {
      const bool interior = match.x >= 16 && match.y >= 16 && match.x + 32 <= reference.cols &&
                            match.y + 32 <= reference.rows;
      if (interior && match.status == MatchStatus::kMatched) {
        errors.push_back(std::hypot(match.subpixel_dx - true_dx, match.subpixel_dy - true_dy));
      }
    }
    ASSERT_GT(errors.size(), 50u);
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 0.13) << true_dx << ", " << true_dy;
    EXPECT_LT(errors[errors.size() * 95 / 100], 0.3) << true_dx << ", " << true_dy;
  }
}

TEST(BlockMatcher, MotionBeyondTheWindowIsReportedAtTheBoundary) {
  const cv::Mat reference = smoothTexture(128, 128, 2.0, 10);
  const BlockMatch match =
      BlockMatcher({16, 16, 4}).matchBlock(reference, shifted(reference, 9, 0), 48, 48);
  EXPECT_EQ(match.dx, 4);
  EXPECT_EQ(match.status, MatchStatus::kAtSearchBoundary);
}

TEST(BlockMatcher, WindowIsClippedAtTheImageBorder) {
  const cv::Mat reference = smoothTexture(64, 64, 2.0, 11);
  const BlockMatch match =
      BlockMatcher({16, 16, 16}).matchBlock(reference, shifted(reference, -3, 2), 0, 0);
  EXPECT_EQ(match.dx, 0);  // -3 would leave the image: the window is clipped to dx >= 0
  EXPECT_EQ(match.status, MatchStatus::kAtSearchBoundary);
}

TEST(BlockMatcher, FlatImageIsTextureless) {
  const cv::Mat flat(64, 64, CV_8UC1, cv::Scalar(90));
  const BlockMatch match = BlockMatcher({16, 16, 4}).matchBlock(flat, flat, 24, 24);
  EXPECT_EQ(match.dx, 0);
  EXPECT_EQ(match.dy, 0);
  EXPECT_EQ(match.status, MatchStatus::kTextureless);
}

TEST(BlockMatcher, BadInputIsRejectedWithAClearError) {
  const cv::Mat image = randomImage(64, 48, CV_8UC1, 12);
  const BlockMatcher matcher({16, 16, 4});
  EXPECT_THROW(matcher.matchGrid(cv::Mat(), image), std::invalid_argument);
  EXPECT_THROW(matcher.matchGrid(image, randomImage(64, 40, CV_8UC1, 1)), std::invalid_argument);
  EXPECT_THROW(matcher.matchGrid(image, randomImage(64, 48, CV_8UC3, 1)), std::invalid_argument);
  EXPECT_THROW(matcher.matchGrid(cv::Mat(48, 64, CV_32F), cv::Mat(48, 64, CV_32F)),
               std::invalid_argument);
  EXPECT_THROW(BlockMatcher({80, 16, 4}).matchGrid(image, image), std::invalid_argument);
  EXPECT_THROW(matcher.matchBlock(image, image, 50, 0), std::invalid_argument);
  EXPECT_THROW(BlockMatcher({0, 16, 4}), std::invalid_argument);
  EXPECT_THROW(BlockMatcher({16, 16, -1}), std::invalid_argument);
  EXPECT_THROW(BlockMatcher({16, 16, kMaxSearchRadiusPx + 1}), std::invalid_argument);
  try {
    matcher.matchGrid(image, randomImage(64, 40, CV_8UC1, 1));
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("64x48"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace lineloc

// Every vector path the processor supports against the scalar reference:
// bit-exact SADs and grid search winners on random bytes, extreme values, odd
// sizes and strides, and blocks that end exactly at the end of their buffer
// (the sanitizer build turns any over-read into a failure).
#include "robot/vision/block_matching/sad_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace lineloc {
namespace {

// An image in a buffer of exactly rows * stride bytes.
struct Buffer {
  Buffer(int width, int height, ptrdiff_t stride, std::mt19937& random)
      : width(width), height(height), stride(stride), bytes(height * stride) {
    for (uint8_t& byte : bytes) {
      byte = static_cast<uint8_t>(random());
    }
  }
  const uint8_t* at(int x, int y) const { return bytes.data() + y * stride + x; }
  // A block of w x h bytes that ends at the buffer's last byte.
  const uint8_t* lastBlock(int w, int h) const { return at(width - w, height - h); }

  int width, height;
  ptrdiff_t stride;
  std::vector<uint8_t> bytes;
};

class SadKernelsTest : public testing::TestWithParam<SimdPath> {
 protected:
  const SadKernels& scalar_ = sadKernels(SimdPath::kScalar);
  const SadKernels& vector_ = sadKernels(GetParam());
  std::mt19937 random_{7};
};

TEST_P(SadKernelsTest, FixedSizesMatchScalarOnRandomBlocks) {
  const Buffer a(67, 41, 67, random_);
  const Buffer b(53, 29, 61, random_);
  for (int trial = 0; trial < 500; ++trial) {
    const int ax = random_() % (a.width - 15), ay = random_() % (a.height - 15);
    const int bx = random_() % (b.width - 15), by = random_() % (b.height - 15);
    ASSERT_EQ(vector_.sad16x16(a.at(ax, ay), a.stride, b.at(bx, by), b.stride),
              scalar_.sad16x16(a.at(ax, ay), a.stride, b.at(bx, by), b.stride));
    ASSERT_EQ(vector_.sad8x8(a.at(ax, ay), a.stride, b.at(bx, by), b.stride),
              scalar_.sad8x8(a.at(ax, ay), a.stride, b.at(bx, by), b.stride));
  }
  EXPECT_EQ(vector_.sad16x16(a.lastBlock(16, 16), a.stride, b.lastBlock(16, 16), b.stride),
            scalar_.sad16x16(a.lastBlock(16, 16), a.stride, b.lastBlock(16, 16), b.stride));
  EXPECT_EQ(vector_.sad8x8(a.lastBlock(8, 8), a.stride, b.lastBlock(8, 8), b.stride),
            scalar_.sad8x8(a.lastBlock(8, 8), a.stride, b.lastBlock(8, 8), b.stride));
}

TEST_P(SadKernelsTest, ExtremeValuesGiveTheLargestSad) {
  const std::vector<uint8_t> zeros(200 * 40, 0), full(200 * 40, 255);
  EXPECT_EQ(vector_.sad16x16(zeros.data(), 200, full.data(), 200), 16u * 16u * 255u);
  EXPECT_EQ(vector_.sad8x8(full.data(), 200, zeros.data(), 200), 8u * 8u * 255u);
  EXPECT_EQ(vector_.sad(zeros.data(), 200, full.data(), 200, 200, 40), 200u * 40u * 255u);
  std::vector<uint8_t> zero_frame(200 * 48, 0), full_frame(200 * 48, 255);
  const int margin = gridSearchMarginBytes(2);
  const GridSearch search{
      zero_frame.data() + margin, full_frame.data() + margin, 200, 64, 48, 16, 16, 2};
  std::vector<BlockBest> winners(12);
  vector_.gridFullSearch(search, winners.data());
  for (const BlockBest& winner : winners) {
    EXPECT_EQ(winner.sad, 16u * 16u * 255u);
  }
}

TEST_P(SadKernelsTest, EveryWidthAndHeightMatchesScalar) {
  const Buffer a(203, 23, 211, random_);
  const Buffer b(203, 23, 203, random_);
  for (int width = 1; width <= 203; ++width) {
    for (int height : {1, 2, 3, 7, 16, 23}) {
      const int ax = random_() % (a.width - width + 1), bx = random_() % (b.width - width + 1);
      ASSERT_EQ(vector_.sad(a.at(ax, 0), a.stride, b.at(bx, 0), b.stride, width, height),
                scalar_.sad(a.at(ax, 0), a.stride, b.at(bx, 0), b.stride, width, height))
          << width << "x" << height;
      ASSERT_EQ(vector_.sad(a.lastBlock(width, height), a.stride, b.lastBlock(width, height),
                            b.stride, width, height),
                scalar_.sad(a.lastBlock(width, height), a.stride, b.lastBlock(width, height),
                            b.stride, width, height))
          << width << "x" << height << " at the buffer's end";
    }
  }
}

// A grey frame inside a buffer that holds exactly the margins the grid search
// may read (random bytes: a lane that is not discarded changes the result).
struct MarginFrame {
  MarginFrame(int width, int height, int radius, std::mt19937& random, int levels = 256)
      : margin(gridSearchMarginBytes(radius)),
        buffer(width + 2 * margin, height, width + 2 * margin, random) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        uint8_t& pixel = buffer.bytes[y * buffer.stride + margin + x];
        pixel = static_cast<uint8_t>(pixel % levels);
      }
    }
  }
  const uint8_t* origin() const { return buffer.at(margin, 0); }

  int margin;
  Buffer buffer;
};

struct GridCase {
  int width, height, block_width, block_height, radius, levels;
};

bool sameWinners(const std::vector<BlockBest>& a, const std::vector<BlockBest>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const BlockBest& x, const BlockBest& y) {
                      return x.sad == y.sad && x.dx == y.dx && x.dy == y.dy;
                    });
}

// Frame sizes that leave partial registers of blocks and clip the window at
// every border; heights that leave 1, 3, 5 and 9 vertical candidates (the
// one-by-one, batch-of-4 and overlapping-batch cases); 2 grey levels, so
// that most candidates tie and the tie order decides.
TEST_P(SadKernelsTest, GridFullSearchMatchesScalar) {
  const GridCase cases[] = {
      {101, 77, 16, 16, 16, 256}, {203, 45, 8, 8, 9, 256},  {77, 40, 16, 8, 7, 256},
      {150, 35, 8, 16, 12, 256},  {64, 16, 16, 16, 4, 256}, {91, 18, 16, 16, 2, 256},
      {120, 21, 16, 16, 5, 256},  {66, 25, 16, 16, 9, 256}, {97, 64, 16, 16, 16, 2},
      {59, 43, 8, 8, 3, 2},       {40, 40, 8, 8, 0, 256},   {48, 33, 16, 16, 40, 256}};
  for (const GridCase& c : cases) {
    const MarginFrame reference(c.width, c.height, c.radius, random_, c.levels);
    const MarginFrame current(c.width, c.height, c.radius, random_, c.levels);
    const GridSearch search{
        reference.origin(), current.origin(), reference.buffer.stride, c.width,
        c.height,           c.block_width,    c.block_height,          c.radius};
    const size_t blocks =
        static_cast<size_t>(c.width / c.block_width) * (c.height / c.block_height);
    std::vector<BlockBest> expected(blocks), actual(blocks);
    scalar_.gridFullSearch(search, expected.data());
    vector_.gridFullSearch(search, actual.data());
    EXPECT_TRUE(sameWinners(actual, expected))
        << c.width << "x" << c.height << " block " << c.block_width << "x" << c.block_height
        << " radius " << c.radius << " levels " << c.levels;
  }
}

// Every displacement of the window ties on a flat frame: the zero vector wins.
TEST_P(SadKernelsTest, GridFullSearchBreaksTiesTowardsTheShortestVector) {
  MarginFrame frame(64, 48, 8, random_, 1);
  const GridSearch search{frame.origin(), frame.origin(), frame.buffer.stride, 64, 48, 16, 16, 8};
  std::vector<BlockBest> winners(12);
  vector_.gridFullSearch(search, winners.data());
  for (const BlockBest& winner : winners) {
    EXPECT_EQ(winner.sad, 0u);
    EXPECT_EQ(winner.dx, 0);
    EXPECT_EQ(winner.dy, 0);
  }
}

template <typename Cost>
std::vector<Cost> randomCosts(int count, Cost largest, std::mt19937& random) {
  std::vector<Cost> costs(count);
  for (Cost& cost : costs) {
    cost = static_cast<Cost>(random() % (static_cast<uint64_t>(largest) + 1));
  }
  return costs;
}

// Every disparity kernel on every count up to a few registers (the tails),
// with equal costs frequent enough that ties are exercised.
template <typename Cost>
void expectDisparityKernelsMatch(const DisparityKernels<Cost>& vector,
                                 const DisparityKernels<Cost>& scalar, std::mt19937& random) {
  const Buffer rows(300, 4, 300, random);
  for (int count = 1; count <= 150; ++count) {
    const auto row = [&](int r) { return rows.at(300 - count, r); };  // ends at the buffer's end
    std::vector<Cost> expected = randomCosts<Cost>(count, 20000, random), actual = expected;
    scalar.addRow(row(0), row(1), count, expected.data());
    vector.addRow(row(0), row(1), count, actual.data());
    ASSERT_EQ(actual, expected) << "addRow " << count;
    scalar.slideRow(row(2), row(3), row(0), row(1), count, expected.data());
    vector.slideRow(row(2), row(3), row(0), row(1), count, actual.data());
    ASSERT_EQ(actual, expected) << "slideRow " << count;
    std::vector<Cost> scratch(2 * count);
    for (int window : {1, 2, 3, 7, 16, 17, 31}) {
      if (window <= count) {
        std::vector<Cost> sums_expected(count - window + 1), sums_actual(count - window + 1);
        scalar.windowSums(expected.data(), count, window, sums_expected.data(), scratch.data());
        vector.windowSums(expected.data(), count, window, sums_actual.data(), scratch.data());
        ASSERT_EQ(sums_actual, sums_expected) << "windowSums " << count << " " << window;
      }
    }
    const std::vector<Cost> limit = randomCosts<Cost>(count, 12, random);
    struct Winners {
      std::vector<Cost> best, index, minus, plus, right_best, right_index;
      std::vector<uint8_t> ambiguous;
    };
    const auto winners = [&](const DisparityKernels<Cost>& kernels, uint64_t seed) {
      std::mt19937 costs_random(static_cast<uint32_t>(seed));
      Winners w{std::vector<Cost>(count, kNoCost<Cost>),
                std::vector<Cost>(count, 0),
                std::vector<Cost>(count),
                std::vector<Cost>(count),
                std::vector<Cost>(count, kNoCost<Cost>),
                std::vector<Cost>(count, 0),
                std::vector<uint8_t>(count, 0)};
      std::vector<Cost> previous(count, kNoCost<Cost>);
      for (Cost k = 0; k < 9; ++k) {
        const std::vector<Cost> costs = randomCosts<Cost>(count, 10, costs_random);
        kernels.considerDisparity(costs.data(), previous.data(), k, count, w.best.data(),
                                  w.index.data(), w.minus.data(), w.plus.data());
        kernels.considerRight(costs.data(), k, count, w.right_best.data(), w.right_index.data());
        previous = costs;
      }
      std::mt19937 again(static_cast<uint32_t>(seed));
      for (Cost k = 0; k < 9; ++k) {
        const std::vector<Cost> costs = randomCosts<Cost>(count, 10, again);
        kernels.markAmbiguous(costs.data(), limit.data(), w.index.data(), k, count,
                              w.ambiguous.data());
      }
      return w;
    };
    const uint64_t seed = random();
    const Winners w_expected = winners(scalar, seed), w_actual = winners(vector, seed);
    ASSERT_EQ(w_actual.best, w_expected.best) << count;
    ASSERT_EQ(w_actual.index, w_expected.index) << count;
    ASSERT_EQ(w_actual.minus, w_expected.minus) << count;
    ASSERT_EQ(w_actual.plus, w_expected.plus) << count;
    ASSERT_EQ(w_actual.ambiguous, w_expected.ambiguous) << count;
    ASSERT_EQ(w_actual.right_best, w_expected.right_best) << count;
    ASSERT_EQ(w_actual.right_index, w_expected.right_index) << count;
    const auto subpixel = [&](const DisparityKernels<Cost>& kernels) {
      std::pair<std::vector<float>, std::vector<uint8_t>> result{std::vector<float>(count),
                                                                 std::vector<uint8_t>(count)};
      kernels.subpixelWinners(w_expected.best.data(), w_expected.index.data(),
                              w_expected.minus.data(), w_expected.plus.data(),
                              w_expected.ambiguous.data(), 3, 8, count, result.first.data(),
                              result.second.data());
      return result;
    };
    ASSERT_EQ(subpixel(vector), subpixel(scalar)) << count;
    std::vector<Cost> limits_expected(count), limits_actual(count);
    const std::vector<Cost> best = randomCosts<Cost>(count, kNoCost<Cost>, random);
    scalar.uniquenessLimits(best.data(), 1100, count, limits_expected.data());
    vector.uniquenessLimits(best.data(), 1100, count, limits_actual.data());
    ASSERT_EQ(limits_actual, limits_expected) << count;
  }
}

TEST_P(SadKernelsTest, DisparityKernelsMatchScalar) {
  expectDisparityKernelsMatch(vector_.disparity16, scalar_.disparity16, random_);
  expectDisparityKernelsMatch(vector_.disparity32, scalar_.disparity32, random_);
}

std::string pathName(const testing::TestParamInfo<SimdPath>& info) {
  return std::string(simdPathName(info.param));
}

INSTANTIATE_TEST_SUITE_P(SupportedPaths, SadKernelsTest, testing::ValuesIn(supportedSimdPaths()),
                         pathName);

TEST(SadKernels, ScalarPathIsAlwaysSupportedAndBestIsTheWidest) {
  const std::vector<SimdPath> paths = supportedSimdPaths();
  ASSERT_FALSE(paths.empty());
  EXPECT_EQ(paths.front(), SimdPath::kScalar);
  EXPECT_EQ(bestSimdPath(), paths.back());
  EXPECT_EQ(sadKernels().path, bestSimdPath());
  for (SimdPath path : paths) {
    EXPECT_EQ(sadKernels(path).path, path);
  }
}

TEST(SadKernels, UnsupportedPathIsAnError) {
  for (SimdPath path : {SimdPath::kSse2, SimdPath::kAvx2, SimdPath::kAvx512Bw}) {
    const std::vector<SimdPath> paths = supportedSimdPaths();
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) {
      EXPECT_THROW(sadKernels(path), std::invalid_argument) << simdPathName(path);
    }
  }
}

}  // namespace
}  // namespace lineloc

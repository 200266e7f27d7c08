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

TEST_P(SadKernelsTest, AbsDiffRowMatchesScalar) {
  const Buffer a(300, 1, 300, random_);
  const Buffer b(300, 1, 300, random_);
  for (int width = 0; width <= 300; ++width) {
    std::vector<uint8_t> expected(width), actual(width);
    scalar_.absDiffRow(a.lastBlock(width, 1), b.at(0, 0), width, expected.data());
    vector_.absDiffRow(a.lastBlock(width, 1), b.at(0, 0), width, actual.data());
    ASSERT_EQ(actual, expected) << "width " << width;
  }
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

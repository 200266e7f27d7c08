// Every vector path the processor supports against the scalar reference:
// bit-exact SADs on random bytes, extreme values, odd sizes and strides, and
// blocks that end exactly at the end of their buffer (the sanitizer build
// turns any over-read into a failure).
#include "robot/vision/block_matching/sad_kernels.h"

#include <gtest/gtest.h>

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
  uint32_t sads[20];
  vector_.sadColumn16x16(zeros.data(), 200, full.data(), 200, 20, sads);
  for (uint32_t sad : sads) {
    EXPECT_EQ(sad, 16u * 16u * 255u);
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

TEST_P(SadKernelsTest, ColumnOfCandidatesMatchesScalarForEveryCount) {
  const Buffer block(16, 16, 16, random_);
  // 150 + 15 rows: counts up to 150 cross the kernel's 64-candidate chunks.
  const Buffer image(40, 165, 40, random_);
  std::vector<uint32_t> expected(150), actual(150);
  for (int count = 1; count <= 150; ++count) {
    const int x = random_() % (image.width - 15);
    const uint8_t* first = image.at(x, image.height - 15 - count);
    scalar_.sadColumn16x16(block.at(0, 0), block.stride, first, image.stride, count,
                           expected.data());
    vector_.sadColumn16x16(block.at(0, 0), block.stride, first, image.stride, count, actual.data());
    ASSERT_EQ(actual, expected) << "count " << count;
  }
}

TEST_P(SadKernelsTest, ColumnEqualsOneBlockAtATime) {
  const Buffer image(48, 60, 48, random_);
  uint32_t sads[45];
  vector_.sadColumn16x16(image.at(3, 5), image.stride, image.at(17, 0), image.stride, 45, sads);
  for (int k = 0; k < 45; ++k) {
    EXPECT_EQ(sads[k],
              scalar_.sad16x16(image.at(3, 5), image.stride, image.at(17, k), image.stride));
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

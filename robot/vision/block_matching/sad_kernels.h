// Sum of absolute differences (SAD) kernels, Persa & Jonker §4 eq. 7:
//
//   SAD(a, b) = sum_{r < height} sum_{c < width} |a(r, c) - b(r, c)|
//
// on 8-bit pixels, with a scalar reference and vector paths built around the
// x86 `psadbw` instruction (SSE2: 16 bytes per instruction, AVX2: 32,
// AVX-512BW: 64). The path is chosen at run time from the processor's
// features; every path returns exactly the scalar reference's result.
//
// Blocks are addressed by their top-left pixel and the row stride in bytes, so
// a colour block of w pixels is a grey block of 3w bytes.
//
// The vector paths are hand-written intrinsics behind a small traits layer
// (sad_vector_kernels.h), one translation unit per instruction set, rather
// than Highway: the throughput target is that of x86 `psadbw` itself, the
// grid search's speed depends on which rows stay in registers and in what
// order its partial sums are added (vector_grid_search.h), and x86 is the
// only vector target (elsewhere the scalar reference runs). The stereo
// kernels are plain loops the compiler vectorises in each of those units
// (disparity_kernel_loops.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "robot/vision/block_matching/candidate_rank.h"
#include "robot/vision/block_matching/disparity_kernels.h"

namespace lineloc {

enum class SimdPath { kScalar, kSse2, kAvx2, kAvx512Bw };

std::string_view simdPathName(SimdPath path);

// Vector width in bytes of the path's `psadbw` (1 for the scalar reference).
int simdPathWidthBytes(SimdPath path);

// The full search over the grid of blocks (x, y) = (i w, j h) of a grey frame:
// for every block and every displacement (dx, dy) with |dx|, |dy| <= radius
// that keeps the displaced block inside the frame, the SAD of the reference
// block with the current frame's block at (x + dx, y + dy). The winner of each
// block has the least SAD; ties go to the least dx^2 + dy^2, then the least
// dy, then the least dx.
//
// Both frames' rows must be readable from byte -gridSearchMarginBytes(radius)
// to width + gridSearchMarginBytes(radius): the vector paths load whole
// registers around the window and discard what falls outside the frame.
struct GridSearch {
  const uint8_t* reference;
  const uint8_t* current;
  ptrdiff_t stride;  // of both frames, bytes
  int width_px;
  int height_px;
  int block_width_px;
  int block_height_px;
  int radius_px;
};

// Winner of one block; gridFullSearch writes them row by row, block (i, j) at
// j * (width / w) + i.
struct BlockBest {
  uint32_t sad;
  int dx;
  int dy;
};

// Block sizes the grid search takes: 8 or 16 pixels wide and high, so that a
// SAD fits 16 bits (the vector paths rank candidates in 32 bits). The radius
// is at most kMaxSearchRadiusPx.
bool gridSearchSupports(int block_width_px, int block_height_px);
inline constexpr int gridSearchMarginBytes(int radius_px) {
  return radius_px + 64;
}

// The kernels of one path. All take the block `a` and the block `b` as a
// top-left pointer and a row stride in bytes.
struct SadKernels {
  SimdPath path;
  uint32_t (*sad16x16)(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride);
  uint32_t (*sad8x8)(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride);
  // Any width >= 1 (bytes) and height >= 1.
  uint32_t (*sad)(const uint8_t* a, ptrdiff_t a_stride, const uint8_t* b, ptrdiff_t b_stride,
                  int width, int height);
  // The full search of every block of a grid, one call per frame.
  void (*gridFullSearch)(const GridSearch& search, BlockBest* best);
  // The stereo matcher's cost-volume passes, 16- and 32-bit costs.
  DisparityKernels<uint16_t> disparity16;
  DisparityKernels<uint32_t> disparity32;
  // Throughput probe for benchmarks: runs kPsadbwProbeChains independent
  // chains of `loops` psadbw each on registers (no memory operands), so that
  // instructions / cycles is the instruction's peak throughput. Null for the
  // scalar reference. The result only keeps the work from being optimised out.
  uint64_t (*psadbwProbe)(int64_t loops);
};

inline constexpr int kPsadbwProbeChains = 12;

// Paths this build contains and this processor runs, scalar first.
std::vector<SimdPath> supportedSimdPaths();

// The widest supported path.
SimdPath bestSimdPath();

// The kernels of `path`; throws std::invalid_argument when the path is not
// supported here.
const SadKernels& sadKernels(SimdPath path);

// The kernels of bestSimdPath().
const SadKernels& sadKernels();

}  // namespace lineloc

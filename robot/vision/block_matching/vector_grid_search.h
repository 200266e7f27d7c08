// Internal: the grid full search (sad_kernels.h, GridSearch) written once
// over the vector traits of sad_vector_kernels.h, for blocks of w, h in
// {8, 16} grey pixels.
//
// Throughput layout. One register holds row r of kBlocks = V::kBytes / w
// neighbouring blocks (a plain load); one load of the current frame at the
// same row offset plus dx holds row r + dy of all their candidates (dx, dy),
// so one `psadbw` serves kBlocks blocks. The kHeight reference rows stay in
// registers for the whole search of the group; a batch of kBatch vertical
// candidates dy..dy + kBatch - 1 keeps kBatch accumulators in registers and
// reuses every loaded current row for each block row it meets (row j serves
// candidate t with block row j - t): kHeight + kBatch - 1 loads for
// kHeight * kBatch `psadbw`.
//
// Each accumulator holds per block w / 8 partial sums (one per 8-byte group,
// at most 16 * 8 * 255 < 2^16). Four candidates are packed into 32-bit ranks
//
//   rank = SAD << 16 | tie order (candidate_rank.h, tieOrder),
//
// so that one unsigned 32-bit minimum per four candidates keeps the running
// winner of every block, ties broken exactly as the scalar reference does.
// Candidates outside the frame (the window clipped at the borders, which can
// differ between the blocks of a register) get the rank 2^32 - 1 by an OR
// mask; whole batches stay inside the clipped rows, the last one overlapping
// the previous one rather than leaving the window.
#pragma once

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

#include "robot/vision/block_matching/sad_paths.h"

namespace lineloc::sad_paths {
namespace {

// SAD of n bytes, one at a time: the tails of the narrower paths.
inline uint32_t sadBytes(const uint8_t* a, const uint8_t* b, int n) {
  uint32_t sum = 0;
  for (int i = 0; i < n; ++i) {
    sum += static_cast<uint32_t>(a[i] > b[i] ? a[i] - b[i] : b[i] - a[i]);
  }
  return sum;
}

// Ranks of the window's candidates laid out for the packed registers: for
// every dx and dy the tie orders of the four candidates dy .. dy + 3 in the
// order in which rankQuad packs them (2^16 - 1 beyond the window).
class PackedTieOrders {
 public:
  PackedTieOrders(int radius_px, int block_width_px)
      : radius_(radius_px), side_(2 * radius_px + 1), order_(tieOrder(radius_px)) {
    // Dword slot s of a packed register holds candidate dy + kSlotOffset[s].
    static constexpr int kWide[4] = {0, 2, 1, 3};    // w = 16: [a, c, b, d]
    static constexpr int kNarrow[4] = {0, 1, 0, 1};  // w = 8: [a, b] per 64 bits
    const int* offsets = block_width_px == 16 ? kWide : kNarrow;
    keys_.resize(static_cast<size_t>(side_) * side_ * 4);
    displacements_.resize(order_.size());
    for (int dx = -radius_; dx <= radius_; ++dx) {
      for (int dy = -radius_; dy <= radius_; ++dy) {
        uint32_t* entry = keys_.data() + 4 * ((dx + radius_) * side_ + dy + radius_);
        for (int slot = 0; slot < 4; ++slot) {
          const int candidate_dy = dy + offsets[slot];
          entry[slot] = candidate_dy > radius_ ? 0xFFFFu : orderOf(dx, candidate_dy);
        }
        displacements_[orderOf(dx, dy)] = {dx, dy};
      }
    }
  }

  // The 4 x 32-bit entry of (dx, dy); entries of consecutive dy are adjacent.
  const uint32_t* keys(int dx, int dy) const {
    return keys_.data() + 4 * ((dx + radius_) * side_ + dy + radius_);
  }
  uint16_t orderOf(int dx, int dy) const { return order_[(dy + radius_) * side_ + dx + radius_]; }
  BlockBest decode(uint32_t rank) const {
    const auto [dx, dy] = displacements_[rank & 0xFFFFu];
    return {rank >> 16, dx, dy};
  }

 private:
  struct Displacement {
    int dx, dy;
  };
  int radius_;
  int side_;
  std::vector<uint16_t> order_;
  std::vector<uint32_t> keys_;
  std::vector<Displacement> displacements_;
};

// Materialises x here, in a register: without it GCC expands each `psadbw`
// of an unrolled batch next to the addition that consumes it (temporary
// expression replacement) in an order that spills most of them.
template <class Reg>
inline void pinToRegister(Reg& x) {
  asm("" : "+v"(x));
}

template <class V>
struct VectorGridSearch {
  using Reg = typename V::Reg;
  static constexpr int kBatch = V::kGridBatch;

  static void run(const GridSearch& search, BlockBest* best) {
    const PackedTieOrders orders(search.radius_px, search.block_width_px);
    const int w = search.block_width_px, h = search.block_height_px;
    if (w == 16 && h == 16) {
      Blocks<16, 16>::run(search, orders, best);
    } else if (w == 16) {
      Blocks<16, 8>::run(search, orders, best);
    } else if (h == 16) {
      Blocks<8, 16>::run(search, orders, best);
    } else {
      Blocks<8, 8>::run(search, orders, best);
    }
  }

  template <int kWidth, int kHeight>
  struct Blocks {
    static constexpr int kBlocks = V::kBytes / kWidth;
    static constexpr int kSlots = kWidth / 4;  // 32-bit ranks per block and register

    // The vertical window of one row of blocks.
    struct Rows {
      int y, dy_min, dy_max;
    };

    static void run(const GridSearch& search, const PackedTieOrders& orders, BlockBest* best) {
      const int blocks = search.width_px / kWidth;
      for (int y = 0; y + kHeight <= search.height_px; y += kHeight, best += blocks) {
        const Rows rows{y, std::max(-search.radius_px, -y),
                        std::min(search.radius_px, search.height_px - kHeight - y)};
        for (int first = 0; first < blocks; first += kBlocks) {
          const int count = std::min(kBlocks, blocks - first);
          if (rows.dy_max - rows.dy_min + 1 >= 4) {
            searchGroup(search, orders, rows, first * kWidth, count, best + first);
          } else {
            searchEachCandidate(search, orders, rows, first * kWidth, count, best + first);
          }
        }
      }
    }

    // Blocks x0 + i * kWidth, i < count, of the row of blocks at `rows.y`.
    static void searchGroup(const GridSearch& search, const PackedTieOrders& orders,
                            const Rows& rows, int x0, int count, BlockBest* best) {
      Reg reference[kHeight];
      const uint8_t* block = search.reference + rows.y * search.stride + x0;
      for (int r = 0; r < kHeight; ++r) {
        reference[r] = V::load(block + r * search.stride);
      }
      const int radius = search.radius_px;
      const int x_last = x0 + (count - 1) * kWidth;
      const bool interior =
          count == kBlocks && x0 >= radius && x_last + kWidth + radius <= search.width_px;
      Reg winners = V::ones();
      for (int dx = std::max(-radius, -x_last);
           dx <= std::min(radius, search.width_px - kWidth - x0); ++dx) {
        const Reg outside = interior ? V::zero() : outsideMask(search.width_px, x0, count, dx);
        const uint8_t* column = search.current + rows.y * search.stride + x0 + dx;
        searchColumn(reference, column, search.stride, rows, orders, dx, outside, winners);
      }
      alignas(64) uint32_t ranks[V::kBytes / 4];
      V::store(reinterpret_cast<uint8_t*>(ranks), winners);
      for (int i = 0; i < count; ++i) {
        best[i] = orders.decode(*std::min_element(ranks + i * kSlots, ranks + (i + 1) * kSlots));
      }
    }

    // All 32 bits set in the slots of the blocks that (x + dx) puts outside
    // the frame, and of the register's unused blocks.
    static Reg outsideMask(int width_px, int x0, int count, int dx) {
      alignas(64) uint8_t mask[V::kBytes];
      for (int i = 0; i < kBlocks; ++i) {
        const int x = x0 + i * kWidth + dx;
        const bool outside = i >= count || x < 0 || x + kWidth > width_px;
        std::memset(mask + i * kWidth, outside ? 0xFF : 0, kWidth);
      }
      return V::load(mask);
    }

    // Candidates dy_min .. dy_max at one dx, in batches inside that range.
    static void searchColumn(const Reg* reference, const uint8_t* column, ptrdiff_t stride,
                             const Rows& rows, const PackedTieOrders& orders, int dx, Reg outside,
                             Reg& winners) {
      const auto batches = [&](auto batch_size) {
        constexpr int kSize = decltype(batch_size)::value;
        for (int dy = rows.dy_min;; dy += kSize) {
          dy = std::min(dy, rows.dy_max + 1 - kSize);
          searchBatch<kSize>(reference, column + dy * stride, stride, orders.keys(dx, dy), outside,
                             winners);
          if (dy + kSize > rows.dy_max) {
            return;
          }
        }
      };
      if (rows.dy_max - rows.dy_min + 1 >= kBatch) {
        batches(std::integral_constant<int, kBatch>());
      } else {
        batches(std::integral_constant<int, 4>());
      }
    }

    // Candidates dy .. dy + kSize - 1 (kSize a multiple of 4); `candidates`
    // points at the first one's top-left pixel, `keys` at the tie orders of
    // its first four.
    template <int kSize>
    static void searchBatch(const Reg* reference, const uint8_t* candidates, ptrdiff_t stride,
                            const uint32_t* keys, Reg outside, Reg& winners) {
      Reg sums[kSize];
      std::fill_n(sums, kSize, V::zero());
#pragma GCC unroll 64
      for (int j = 0; j < kHeight + kSize - 1; ++j) {
        const Reg row = V::load(candidates + j * stride);
#pragma GCC unroll 32
        for (int t = 0; t < kSize; ++t) {
          const int r = j - t;
          if (r >= 0 && r < kHeight) {
            Reg sum = V::add64(sums[t], V::sad(row, reference[r]));
            pinToRegister(sum);
            sums[t] = sum;
          }
        }
      }
#pragma GCC unroll 8
      for (int t = 0; t < kSize; t += 4) {
        rankQuad(sums + t, keys + 4 * t, outside, winners);
      }
    }

    // Ranks of the four candidates of sums[0..3] into the running minimum.
    static void rankQuad(const Reg* sums, const uint32_t* keys, Reg outside, Reg& winners) {
      if constexpr (kWidth == 16) {
        // Per 128-bit lane (one block): [a0 a1] [b0 b1] -> [a b], then
        // [a b] | [c d] << 32 -> 32-bit [a c b d].
        const Reg ab =
            V::add64(V::unpackLow64(sums[0], sums[1]), V::unpackHigh64(sums[0], sums[1]));
        const Reg cd =
            V::add64(V::unpackLow64(sums[2], sums[3]), V::unpackHigh64(sums[2], sums[3]));
        const Reg packed = V::bitOr(ab, V::shiftLeft64By32(cd));
        winners = V::minU32(winners, rank(packed, broadcast(keys), outside));
      } else {
        // Per 64 bits (one block): a | b << 32 -> [a b].
        for (int pair = 0; pair < 2; ++pair) {
          const Reg packed = V::bitOr(sums[2 * pair], V::shiftLeft64By32(sums[2 * pair + 1]));
          winners = V::minU32(winners, rank(packed, broadcast(keys + 8 * pair), outside));
        }
      }
    }

    static Reg broadcast(const uint32_t* keys) {
      return V::broadcast16(reinterpret_cast<const uint8_t*>(keys));
    }

    static Reg rank(Reg packed_sads, Reg keys, Reg outside) {
      return V::bitOr(V::bitOr(V::shiftLeft32By16(packed_sads), keys), outside);
    }

    // Frames too short for a batch of 4 (fewer than kHeight + 3 rows): one
    // candidate at a time.
    static void searchEachCandidate(const GridSearch& search, const PackedTieOrders& orders,
                                    const Rows& rows, int x0, int count, BlockBest* best) {
      for (int i = 0; i < count; ++i) {
        const int x = x0 + i * kWidth;
        const uint8_t* block = search.reference + rows.y * search.stride + x;
        uint32_t winner = UINT32_MAX;
        for (int dy = rows.dy_min; dy <= rows.dy_max; ++dy) {
          for (int dx = std::max(-search.radius_px, -x);
               dx <= std::min(search.radius_px, search.width_px - kWidth - x); ++dx) {
            const uint8_t* candidate = search.current + (rows.y + dy) * search.stride + x + dx;
            uint32_t sum = 0;
            for (int r = 0; r < kHeight; ++r) {
              sum += sadBytes(block + r * search.stride, candidate + r * search.stride, kWidth);
            }
            winner = std::min(winner, sum << 16 | orders.orderOf(dx, dy));
          }
        }
        best[i] = orders.decode(winner);
      }
    }
  };
};

}  // namespace
}  // namespace lineloc::sad_paths

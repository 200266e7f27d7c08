#include <gtest/gtest.h>
#include <sys/resource.h>

#include <vector>

#include "common/parallel/resident_heap.h"

namespace lineloc {
namespace {

// Page faults the calling thread has taken so far (minor: no disk read).
long minorPageFaults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// Allocates, fills and frees what one frame's verification map needs: eight
// 640 x 480 byte maps (600 pages of 4 KiB). Returns a byte of each, so that
// the buffers are used.
int buildAndFreeFrameBuffers() {
  constexpr size_t kMapBytes = 640 * 480;
  std::vector<std::vector<unsigned char>> maps;
  for (int map = 0; map < 8; ++map) {
    maps.emplace_back(kMapBytes, static_cast<unsigned char>(map));
  }
  int sum = 0;
  for (const std::vector<unsigned char>& map : maps) {
    sum += map[kMapBytes / 2];
  }
  return sum;
}

TEST(ResidentHeap, AFramesBuffersBuiltAgainDoNotFaultTheirPagesInAgain) {
  if (!keepFreedMemoryResident()) {
    GTEST_SKIP() << "this allocator (a sanitizer's) does not take glibc's settings";
  }
  ASSERT_EQ(buildAndFreeFrameBuffers(), 28);
  const long faults_before = minorPageFaults();
  ASSERT_EQ(buildAndFreeFrameBuffers(), 28);
  // Returned to the kernel, the 600 pages would fault in again, one by one.
  EXPECT_LT(minorPageFaults() - faults_before, 60);
}

}  // namespace
}  // namespace lineloc

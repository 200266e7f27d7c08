// Keeps the memory a real-time process frees for its next allocations, so a
// frame's buffers do not page-fault in again on every frame. glibc serves a
// block above its mmap threshold (128 KiB at start, raised to the largest
// block freed) with fresh pages, and returns the free top of a heap beyond
// its trim threshold (twice that) to the kernel; every later touch of those
// pages is a page fault: a frame's buffers of a few megabytes take ten times
// longer to build when their pages fault in again each frame. Blocks up to
// max_mmap_threshold come from the heap, and freed
// memory stays with the process up to trim_threshold. Best effort, as
// lowerThreadPriority (thread_priority.h): a refusal changes nothing.
#pragma once

#include <malloc.h>

#include <cstddef>

namespace lineloc {

struct ResidentHeapOptions {
  // Blocks larger than this are still mapped on their own (glibc's ceiling
  // for the threshold on 64-bit systems: 32 MiB).
  int max_mmap_threshold_bytes = 32 << 20;
  // Free memory at the top of a heap kept before any is returned.
  int trim_threshold_bytes = 512 << 20;
};

// Returns whether the allocator took both settings (an allocator other than
// glibc's, such as a sanitizer's, may refuse them; nothing changes then).
inline bool keepFreedMemoryResident(const ResidentHeapOptions& options = {}) {
  return mallopt(M_MMAP_THRESHOLD, options.max_mmap_threshold_bytes) == 1 &&
         mallopt(M_TRIM_THRESHOLD, options.trim_threshold_bytes) == 1;
}

}  // namespace lineloc

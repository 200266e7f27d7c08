// Keeps the memory a real-time process frees for its next allocations, so a
// frame's buffers do not page-fault in again on every frame. glibc serves a
// block above its mmap threshold (128 KiB at start, raised to the largest
// block freed) with fresh pages, and returns the free top of a heap beyond
// its trim threshold (twice that) to the kernel; every later touch of those
// pages is a page fault. The backbone's verification map alone is eight
// 640 x 480 byte maps, 2.4 MB: built per frame in the service, it took 7-8 ms,
// nearly all of it faulting its pages in, against 0.6 ms when the memory
// stays (BM_VerificationMap); on simulated Delft seeds 1 and 2 the exposure
// -> fix p99 was 18.5 and 16.2 ms with the memory returned, 8.6 and 8.3 ms with
// it kept. Blocks up to max_mmap_threshold come from the heap, and freed
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

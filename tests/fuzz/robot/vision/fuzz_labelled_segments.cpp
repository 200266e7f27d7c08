// Fuzz target: hand-labelled line segment files (tests/unit/robot/vision/support).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "labelled_segments.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const lineloc::testing::LabelledSegments labels =
        lineloc::testing::readLabelledSegments(in, "fuzz");
    if (!labels.region.min().allFinite() || !labels.region.max().allFinite() ||
        !(labels.region.min().array() < labels.region.max().array()).all()) {
      __builtin_trap();  // accepted an empty or non-finite region
    }
    for (const lineloc::testing::Segment2d& s : labels.segments) {
      if (!s.start.allFinite() || !s.end.allFinite() || s.start == s.end) {
        __builtin_trap();  // accepted a non-finite or zero-length segment
      }
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}

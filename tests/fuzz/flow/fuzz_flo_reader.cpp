// Fuzz target: decodeFlo either returns a CV_32FC2 image of the size its
// header states or throws std::runtime_error; anything else is a bug.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "robot/vision/flow/flo_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cv::Mat flow = lineloc::decodeFlo({data, size});
    if (flow.type() != CV_32FC2 || 12 + flow.total() * 8 != size) {
      std::abort();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}

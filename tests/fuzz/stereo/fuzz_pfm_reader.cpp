// Fuzz target: decodePfm either returns an image of the size its header
// states or throws std::runtime_error; anything else (crash, other
// exception, sanitizer report) is a bug.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "robot/vision/stereo/pfm_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cv::Mat image = lineloc::decodePfm({data, size});
    if (image.empty() || image.total() * image.elemSize() > size) {
      std::abort();
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}

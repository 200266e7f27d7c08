// Fuzz target: an image's header either gives a size within int32 that the
// decoder then decodes to (for images small enough to decode here), or throws
// std::runtime_error; a size beyond that is refused from the header alone, as
// readImageFile refuses sizes beyond its limit. Anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/image/image_header.h"

namespace {

// Small enough that decoding every seed's mutations keeps the replay fast.
constexpr int64_t kDecodedPixels = 1 << 16;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  lineloc::ImageHeader header;
  try {
    header = lineloc::readImageHeader(in, "fuzz");
  } catch (const std::runtime_error&) {
    return 0;
  }
  constexpr int64_t kMaxSide = std::numeric_limits<int32_t>::max();
  if (header.width_px < 1 || header.height_px < 1 || header.width_px > kMaxSide ||
      header.height_px > kMaxSide) {
    std::abort();
  }
  if (header.width_px * header.height_px > kDecodedPixels) {
    return 0;
  }
  const cv::Mat bytes(1, static_cast<int>(size), CV_8U, const_cast<uint8_t*>(data));
  const cv::Mat image = cv::imdecode(
      bytes, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR | cv::IMREAD_IGNORE_ORIENTATION);
  if (!image.empty() && (image.cols != header.width_px || image.rows != header.height_px)) {
    std::abort();
  }
  return 0;
}

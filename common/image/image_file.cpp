#include "common/image/image_file.h"

#include <fmt/format.h>

#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "common/image/image_header.h"

namespace lineloc {

namespace {

void requireWithinLimit(const ImageHeader& header, const std::string& source, int64_t max_pixels) {
  if (header.width_px * header.height_px > max_pixels) {
    throw std::runtime_error(
        fmt::format("image '{}': its {} header claims {} x {} pixels, more than the limit of {}",
                    source, header.format, header.width_px, header.height_px, max_pixels));
  }
}

}  // namespace

cv::Mat readImageFile(const std::string& path, int imread_flags, int64_t max_pixels) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot open image '{}'", path));
  }
  requireWithinLimit(readImageHeader(file, path), path, max_pixels);
  file.close();
  cv::Mat image = cv::imread(path, imread_flags);
  if (image.empty()) {
    throw std::runtime_error(fmt::format("cannot read image '{}'", path));
  }
  return image;
}

cv::Mat decodeImageBytes(const uint8_t* data, size_t size, int imread_flags,
                         const std::string& source, int64_t max_pixels) {
  std::istringstream bytes(std::string(reinterpret_cast<const char*>(data), size));
  requireWithinLimit(readImageHeader(bytes, source), source, max_pixels);
  if (size > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw std::runtime_error(fmt::format("image '{}': {} bytes, too many to decode", source, size));
  }
  cv::Mat image = cv::imdecode(
      cv::Mat(1, static_cast<int>(size), CV_8UC1, const_cast<uint8_t*>(data)), imread_flags);
  if (image.empty()) {
    throw std::runtime_error(fmt::format("cannot decode image '{}'", source));
  }
  return image;
}

}  // namespace lineloc

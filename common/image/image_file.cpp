#include "common/image/image_file.h"

#include <fmt/format.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/image/image_header.h"

namespace lineloc {

cv::Mat readImageFile(const std::string& path, int imread_flags, int64_t max_pixels) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot open image '{}'", path));
  }
  const ImageHeader header = readImageHeader(file, path);
  if (header.width_px * header.height_px > max_pixels) {
    throw std::runtime_error(
        fmt::format("image '{}': its {} header claims {} x {} pixels, more than the limit of {}",
                    path, header.format, header.width_px, header.height_px, max_pixels));
  }
  file.close();
  cv::Mat image = cv::imread(path, imread_flags);
  if (image.empty()) {
    throw std::runtime_error(fmt::format("cannot read image '{}'", path));
  }
  return image;
}

}  // namespace lineloc

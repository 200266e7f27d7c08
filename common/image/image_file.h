// Reading an image file with its size bounded before it is decoded: the size
// its header claims (common/image/image_header.h) must stay within a pixel
// limit, so a small file claiming a huge image is refused instead of making
// the decoder allocate for it. Every program reads its images through here.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace lineloc {

// 64 megapixels: far above the robot's 2-5 MP cameras and a photograph's
// 20-50 MP, far below what exhausts a robot's memory once decoded.
constexpr int64_t kDefaultMaxImagePixels = 64'000'000;

// cv::imread(path, imread_flags) once the header of `path` claims at most
// `max_pixels`. Throws std::runtime_error naming the file: it cannot be
// opened, its header is not one readImageHeader reads, it claims more
// pixels (naming the claimed size and the limit), or it does not decode.
cv::Mat readImageFile(const std::string& path, int imread_flags,
                      int64_t max_pixels = kDefaultMaxImagePixels);

// The same for an encoded image in memory (a message's JPEG or PNG), named
// `source` in errors: cv::imdecode once its header claims at most
// `max_pixels`.
cv::Mat decodeImageBytes(const uint8_t* data, size_t size, int imread_flags,
                         const std::string& source, int64_t max_pixels = kDefaultMaxImagePixels);

}  // namespace lineloc

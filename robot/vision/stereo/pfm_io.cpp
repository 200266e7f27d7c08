#include "robot/vision/stereo/pfm_io.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int64_t kMaxPixels = int64_t{1} << 26;

// Reads the header token at `at` (after any whitespace) and the one
// whitespace character that ends it.
std::string headerToken(std::span<const uint8_t> bytes, size_t& at, const char* what) {
  while (at < bytes.size() && std::isspace(bytes[at])) {
    ++at;
  }
  const size_t start = at;
  while (at < bytes.size() && !std::isspace(bytes[at]) && at - start < 32) {
    ++at;
  }
  if (at == start || at >= bytes.size() || !std::isspace(bytes[at])) {
    throw std::runtime_error(fmt::format("PFM header: missing or malformed {}", what));
  }
  ++at;
  return {reinterpret_cast<const char*>(bytes.data()) + start, at - 1 - start};
}

int64_t positiveInteger(const std::string& token, const char* what) {
  int64_t value = 0;
  for (char c : token) {
    if (c < '0' || c > '9' || value > kMaxPixels) {
      throw std::runtime_error(
          fmt::format("PFM header: {} '{}' is not a positive integer", what, token));
    }
    value = value * 10 + (c - '0');
  }
  if (value < 1 || value > kMaxPixels) {
    throw std::runtime_error(fmt::format("PFM header: {} {} out of range", what, value));
  }
  return value;
}

double finiteScale(const std::string& token) {
  size_t used = 0;
  double scale = 0.0;
  try {
    scale = std::stod(token, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != token.size() || !std::isfinite(scale) || scale == 0.0) {
    throw std::runtime_error(fmt::format("PFM header: scale '{}' is not a non-zero number", token));
  }
  return scale;
}

}  // namespace

std::vector<uint8_t> encodePfm(const cv::Mat& image) {
  if (image.empty() || (image.type() != CV_32FC1 && image.type() != CV_32FC3)) {
    throw std::runtime_error("PFM: image must be non-empty CV_32FC1 or CV_32FC3");
  }
  const std::string header =
      fmt::format("{}\n{} {}\n-1\n", image.channels() == 1 ? "Pf" : "PF", image.cols, image.rows);
  std::vector<uint8_t> bytes(header.begin(), header.end());
  const size_t row_bytes = image.cols * image.elemSize();
  for (int y = image.rows - 1; y >= 0; --y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    bytes.insert(bytes.end(), row, row + row_bytes);
  }
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little endian");
  return bytes;
}

void writePfm(const std::string& path, const cv::Mat& image) {
  const std::vector<uint8_t> bytes = encodePfm(image);
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!file) {
    throw std::runtime_error(fmt::format("cannot write PFM file '{}'", path));
  }
}

cv::Mat decodePfm(std::span<const uint8_t> bytes) {
  size_t at = 0;
  const std::string magic = headerToken(bytes, at, "magic (Pf or PF)");
  if (magic != "Pf" && magic != "PF") {
    throw std::runtime_error(fmt::format("PFM header: magic '{}' is neither Pf nor PF", magic));
  }
  const int channels = magic == "Pf" ? 1 : 3;
  const int64_t width = positiveInteger(headerToken(bytes, at, "width"), "width");
  const int64_t height = positiveInteger(headerToken(bytes, at, "height"), "height");
  if (width * height > kMaxPixels) {
    throw std::runtime_error(fmt::format("PFM header: {}x{} is too large", width, height));
  }
  const bool little_endian = finiteScale(headerToken(bytes, at, "scale")) < 0.0;
  const size_t row_bytes = static_cast<size_t>(width) * channels * sizeof(float);
  const size_t expected = row_bytes * static_cast<size_t>(height);
  if (bytes.size() - at != expected) {
    throw std::runtime_error(
        fmt::format("PFM: {}x{} with {} channel(s) needs {} bytes of data, "
                    "the file has {}",
                    width, height, channels, expected, bytes.size() - at));
  }
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_32FC(channels));
  for (int y = 0; y < image.rows; ++y) {
    std::memcpy(image.ptr<uint8_t>(image.rows - 1 - y), bytes.data() + at + y * row_bytes,
                row_bytes);
  }
  if (little_endian != (std::endian::native == std::endian::little)) {
    uint32_t* words = image.ptr<uint32_t>();
    for (size_t i = 0; i < image.total() * channels; ++i) {
      words[i] = __builtin_bswap32(words[i]);
    }
  }
  return image;
}

cv::Mat readPfm(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot open PFM file '{}'", path));
  }
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file),
                                   std::istreambuf_iterator<char>()};
  try {
    return decodePfm(bytes);
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: {}", path, error.what()));
  }
}

cv::Mat disparityForPfm(const cv::Mat& disparity_px, const cv::Mat& valid) {
  cv::Mat out = disparity_px.clone();
  out.setTo(std::numeric_limits<float>::infinity(), valid == 0);
  return out;
}

}  // namespace lineloc

#include "robot/vision/flow/flo_io.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr char kMagic[4] = {'P', 'I', 'E', 'H'};
constexpr int32_t kMaxSide = 1 << 15;
constexpr size_t kHeaderBytes = 12;

static_assert(std::endian::native == std::endian::little, ".flo I/O assumes little endian");

}  // namespace

std::vector<uint8_t> encodeFlo(const cv::Mat& flow_px, const cv::Mat& known) {
  if (flow_px.empty() || flow_px.type() != CV_32FC2) {
    throw std::runtime_error(".flo: flow must be a non-empty CV_32FC2 image");
  }
  if (!known.empty() && (known.size() != flow_px.size() || known.type() != CV_8U)) {
    throw std::runtime_error(".flo: the known mask must be CV_8U of the flow's size");
  }
  std::vector<uint8_t> bytes(kHeaderBytes + flow_px.total() * sizeof(cv::Vec2f));
  const int32_t size[2] = {flow_px.cols, flow_px.rows};
  std::memcpy(bytes.data(), kMagic, 4);
  std::memcpy(bytes.data() + 4, size, sizeof(size));
  const cv::Vec2f unknown(kUnknownFlow, kUnknownFlow);
  uint8_t* out = bytes.data() + kHeaderBytes;
  for (int y = 0; y < flow_px.rows; ++y) {
    for (int x = 0; x < flow_px.cols; ++x, out += sizeof(cv::Vec2f)) {
      const bool is_known = known.empty() || known.at<uint8_t>(y, x) != 0;
      const cv::Vec2f value = is_known ? flow_px.at<cv::Vec2f>(y, x) : unknown;
      std::memcpy(out, value.val, sizeof(cv::Vec2f));
    }
  }
  return bytes;
}

void writeFlo(const std::string& path, const cv::Mat& flow_px, const cv::Mat& known) {
  const std::vector<uint8_t> bytes = encodeFlo(flow_px, known);
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!file) {
    throw std::runtime_error(fmt::format("cannot write .flo file '{}'", path));
  }
}

cv::Mat decodeFlo(std::span<const uint8_t> bytes) {
  if (bytes.size() < kHeaderBytes) {
    throw std::runtime_error(
        fmt::format(".flo: {} bytes, shorter than the 12-byte header", bytes.size()));
  }
  if (std::memcmp(bytes.data(), kMagic, 4) != 0) {
    throw std::runtime_error(".flo: does not start with the tag PIEH (202021.25)");
  }
  int32_t width = 0, height = 0;
  std::memcpy(&width, bytes.data() + 4, 4);
  std::memcpy(&height, bytes.data() + 8, 4);
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) {
    throw std::runtime_error(
        fmt::format(".flo: size {}x{} outside [1, {}]", width, height, kMaxSide));
  }
  const size_t expected = static_cast<size_t>(width) * static_cast<size_t>(height) * 8;
  if (bytes.size() - kHeaderBytes != expected) {
    throw std::runtime_error(fmt::format(".flo: {}x{} needs {} bytes of flow, the file has {}",
                                         width, height, expected, bytes.size() - kHeaderBytes));
  }
  cv::Mat flow(height, width, CV_32FC2);
  std::memcpy(flow.data, bytes.data() + kHeaderBytes, expected);
  return flow;
}

cv::Mat readFlo(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error(fmt::format("cannot open .flo file '{}'", path));
  }
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file),
                                   std::istreambuf_iterator<char>()};
  try {
    return decodeFlo(bytes);
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: {}", path, error.what()));
  }
}

}  // namespace lineloc

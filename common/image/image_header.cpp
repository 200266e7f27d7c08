#include "common/image/image_header.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <limits>
#include <stdexcept>

namespace lineloc {
namespace {

constexpr int64_t kMaxSide = std::numeric_limits<int32_t>::max();
constexpr const char* kUnknownFormat = "not a PNG, JPEG, BMP or Netpbm (PBM, PGM, PPM) image";

class HeaderBytes {
 public:
  HeaderBytes(std::istream& in, const std::string& source) : in_(in), source_(source) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(fmt::format("image '{}': {}", source_, what));
  }

  uint8_t byte(const char* what) {
    const int c = in_.get();
    if (c == std::char_traits<char>::eof()) {
      fail(fmt::format("truncated {}", what));
    }
    return static_cast<uint8_t>(c);
  }

  // Unsigned, `count` bytes, big-endian unless `little_endian`.
  uint32_t number(int count, bool little_endian, const char* what) {
    uint32_t value = 0;
    for (int i = 0; i < count; ++i) {
      const uint32_t next = byte(what);
      value = little_endian ? value | next << (8 * i) : value << 8 | next;
    }
    return value;
  }

  void skip(std::streamsize count, const char* what) {
    if (!in_.ignore(count) || in_.gcount() != count) {
      fail(fmt::format("truncated {}", what));
    }
  }

 private:
  std::istream& in_;
  const std::string& source_;
};

ImageHeader checkedSize(const HeaderBytes& bytes, const char* format, int64_t width,
                        int64_t height) {
  if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide) {
    bytes.fail(fmt::format("{} header gives an invalid size {} x {}", format, width, height));
  }
  return {format, width, height};
}

// The IHDR chunk must come first (ISO/IEC 15948 §5.6).
ImageHeader readPng(HeaderBytes& bytes) {
  for (const uint8_t expected : {'G', '\r', '\n', '\x1a', '\n'}) {
    if (bytes.byte("PNG signature") != expected) {
      bytes.fail(kUnknownFormat);
    }
  }
  const uint32_t length = bytes.number(4, false, "PNG IHDR chunk");
  const uint32_t type = bytes.number(4, false, "PNG IHDR chunk");
  if (length != 13 || type != 0x49484452u) {
    bytes.fail("PNG does not start with its IHDR chunk");
  }
  const int64_t width = bytes.number(4, false, "PNG IHDR chunk");
  const int64_t height = bytes.number(4, false, "PNG IHDR chunk");
  return checkedSize(bytes, "PNG", width, height);
}

// Walks the markers after SOI the way libjpeg does (bytes between markers
// skipped, 0xFF fill bytes allowed) up to the first frame header.
ImageHeader readJpeg(HeaderBytes& bytes) {
  for (;;) {
    uint8_t marker = 0;
    while (marker == 0) {
      while (bytes.byte("JPEG before its frame header") != 0xFF) {
      }
      do {
        marker = bytes.byte("JPEG before its frame header");
      } while (marker == 0xFF);
    }
    const bool frame_header =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame_header) {
      bytes.skip(3, "JPEG frame header");  // length, sample precision
      const int64_t height = bytes.number(2, false, "JPEG frame header");
      const int64_t width = bytes.number(2, false, "JPEG frame header");
      return checkedSize(bytes, "JPEG", width, height);
    }
    if (marker == 0xDA || marker == 0xD9 || marker == 0xD8) {
      bytes.fail("JPEG has no frame header before its scan or end");
    }
    if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      continue;  // RSTn and TEM stand alone
    }
    const uint32_t length = bytes.number(2, false, "JPEG marker segment");
    if (length < 2) {
      bytes.fail(fmt::format("JPEG marker segment 0xFF{:02X} has length {}", marker, length));
    }
    bytes.skip(length - 2, "JPEG marker segment");
  }
}

// BITMAPCOREHEADER (12 bytes) holds 16-bit sizes; every later info header
// 32-bit ones, the height negative for rows stored top-down.
ImageHeader readBmp(HeaderBytes& bytes) {
  bytes.skip(12, "BMP file header");
  const uint32_t info_size = bytes.number(4, true, "BMP info header");
  if (info_size == 12) {
    const int64_t width = bytes.number(2, true, "BMP info header");
    const int64_t height = bytes.number(2, true, "BMP info header");
    return checkedSize(bytes, "BMP", width, height);
  }
  if (info_size < 16) {
    bytes.fail(fmt::format("BMP info header of {} bytes", info_size));
  }
  const int64_t width = static_cast<int32_t>(bytes.number(4, true, "BMP info header"));
  const int64_t height = static_cast<int32_t>(bytes.number(4, true, "BMP info header"));
  return checkedSize(bytes, "BMP", width, height < 0 ? -height : height);
}

// A decimal after whitespace and '#' comments (Netpbm's header tokens). The
// byte after its digits ends it and is consumed with it, '#' included, as
// OpenCV's decoder reads it: "10#6\n255" is 10 then 6, where the Netpbm
// specification would read 10, a comment, then 255.
int64_t netpbmNumber(HeaderBytes& bytes) {
  uint8_t c = bytes.byte("Netpbm header");
  while (std::isspace(c) || c == '#') {
    if (c == '#') {
      while (c != '\n' && c != '\r') {
        c = bytes.byte("Netpbm header");
      }
    }
    c = bytes.byte("Netpbm header");
  }
  if (!std::isdigit(c)) {
    bytes.fail("Netpbm header holds no size");
  }
  int64_t value = 0;
  for (;;) {
    value = value * 10 + (c - '0');
    if (value > kMaxSide) {
      bytes.fail("Netpbm header gives a size out of range");
    }
    c = bytes.byte("Netpbm header");
    if (!std::isdigit(c)) {
      return value;
    }
  }
}

ImageHeader readNetpbm(HeaderBytes& bytes) {
  const int64_t width = netpbmNumber(bytes);
  const int64_t height = netpbmNumber(bytes);
  return checkedSize(bytes, "Netpbm", width, height);
}

}  // namespace

ImageHeader readImageHeader(std::istream& in, const std::string& source) {
  HeaderBytes bytes(in, source);
  std::array<uint8_t, 3> start{};
  for (uint8_t& b : start) {
    const int c = in.get();
    if (c == std::char_traits<char>::eof()) {
      bytes.fail("too short to be an image");
    }
    b = static_cast<uint8_t>(c);
  }
  if (start[0] == 0x89 && start[1] == 'P' && start[2] == 'N') {
    return readPng(bytes);
  }
  if (start[0] == 0xFF && start[1] == 0xD8 && start[2] == 0xFF) {
    in.unget();
    return readJpeg(bytes);
  }
  if (start[0] == 'B' && start[1] == 'M') {
    in.unget();
    return readBmp(bytes);
  }
  if (start[0] == 'P' && start[1] >= '1' && start[1] <= '6' && std::isspace(start[2])) {
    return readNetpbm(bytes);
  }
  bytes.fail(kUnknownFormat);
}

}  // namespace lineloc

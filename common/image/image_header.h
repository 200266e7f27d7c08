// The size an image file claims, read from its header without decoding it:
// PNG's IHDR chunk (ISO/IEC 15948 §11.2.2), JPEG's first frame header SOFn
// (ITU-T T.81 §B.2.2), BMP's info or core header, and the Netpbm header
// (P1-P6: PBM, PGM, PPM). The formats are told apart by their signatures, as
// OpenCV's decoders tell them, so the size read is the one a decoder would
// allocate for; a program can refuse an image too large to decode before any
// decoder allocates its pixels.
#pragma once

#include <cstdint>
#include <istream>
#include <string>

namespace lineloc {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG", "BMP" or "Netpbm"
  int64_t width_px = 0;
  int64_t height_px = 0;
};

// Reads the header at the start of `in`, skipping (not buffering) what lies
// before a JPEG's frame header. Throws std::runtime_error naming `source` for
// another format, a truncated header, or a zero or out-of-range size.
ImageHeader readImageHeader(std::istream& in, const std::string& source);

}  // namespace lineloc

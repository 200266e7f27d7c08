// Parsing of "AxB" size pairs as users type them on command lines: a
// chessboard of 9x6 inner corners, an image of 640x480 pixels.
#pragma once

#include <optional>
#include <string_view>

namespace lineloc {

struct SizePair {
  int first = 0;
  int second = 0;
};

// Parses "<digits>x<digits>" with 1..max_digits digits on each side and
// nothing else (no signs, no spaces); std::nullopt for anything else.
std::optional<SizePair> parseSizePair(std::string_view text, int max_digits);

}  // namespace lineloc

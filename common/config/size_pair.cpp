#include "common/config/size_pair.h"

namespace lineloc {

namespace {

// Reads a run of 1..max_digits decimal digits from the front of text.
std::optional<int> takeNumber(std::string_view* text, int max_digits) {
  int value = 0;
  int digits = 0;
  while (!text->empty() && text->front() >= '0' && text->front() <= '9') {
    if (++digits > max_digits)
      return std::nullopt;
    value = 10 * value + (text->front() - '0');
    text->remove_prefix(1);
  }
  if (digits == 0)
    return std::nullopt;
  return value;
}

}  // namespace

std::optional<SizePair> parseSizePair(std::string_view text, int max_digits) {
  const std::optional<int> first = takeNumber(&text, max_digits);
  if (!first || text.empty() || text.front() != 'x')
    return std::nullopt;
  text.remove_prefix(1);
  const std::optional<int> second = takeNumber(&text, max_digits);
  if (!second || !text.empty())
    return std::nullopt;
  return SizePair{*first, *second};
}

}  // namespace lineloc

// Fuzz targets that fill a message struct's fields from the input's bytes,
// field by field in order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace lineloc::fuzz {

// Copies the next sizeof(T) bytes of the input into `value` (fewer when the
// input ends first) and moves past them.
template <typename T>
void takeField(T& value, const uint8_t*& data, size_t& size) {
  const size_t n = sizeof(T) < size ? sizeof(T) : size;
  if (n == 0) {
    return;
  }
  std::memcpy(&value, data, n);
  data += n;
  size -= n;
}

}  // namespace lineloc::fuzz

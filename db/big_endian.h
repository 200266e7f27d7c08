// Big-endian (network order) fixed-width values, the byte order of
// PostgreSQL's binary formats: binary COPY rows, binary results, and the
// *send() functions the line packs are built from in SQL.
#pragma once

#include <bit>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <string>

namespace lineloc::db {

static_assert(std::endian::native == std::endian::little, "lineloc targets little-endian hosts");

template <typename T>
concept BigEndianValue = (std::integral<T> || std::same_as<T, double>)&&(sizeof(T) == 2 ||
                                                                         sizeof(T) == 4 ||
                                                                         sizeof(T) == 8);

namespace detail {
template <typename T>
auto swappedBits(T value) {
  if constexpr (sizeof(T) == 2) {
    return __builtin_bswap16(std::bit_cast<uint16_t>(value));
  } else if constexpr (sizeof(T) == 4) {
    return __builtin_bswap32(std::bit_cast<uint32_t>(value));
  } else {
    return __builtin_bswap64(std::bit_cast<uint64_t>(value));
  }
}
}  // namespace detail

// Appends `value` in big-endian byte order.
template <BigEndianValue T>
void appendBigEndian(std::string& out, T value) {
  const auto bits = detail::swappedBits(value);
  out.append(reinterpret_cast<const char*>(&bits), sizeof(bits));
}

// Reads a big-endian `T` from `bytes` (at least sizeof(T) of them).
template <BigEndianValue T>
T readBigEndian(const char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return std::bit_cast<T>(detail::swappedBits(value));
}

}  // namespace lineloc::db

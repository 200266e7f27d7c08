// Integer hashes for procedural texture: every pattern the simulator paints is
// a pure function of the object's id and a lattice cell, so it looks the same
// from every view and in every run.
#pragma once

#include <cmath>
#include <cstdint>

namespace lineloc {

// A well-mixed 32-bit hash (Wellons' lowbias32) of up to three integers.
inline uint32_t proceduralHash(uint32_t a, uint32_t b = 0, uint32_t c = 0) {
  uint32_t x = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du;
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// Uniform in [0, 1) from a hash.
inline float unitFromHash(uint32_t h) {
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

// The lattice cell of `size` that holds a coordinate, as a hash input.
inline uint32_t latticeCell(float coordinate, float size) {
  return static_cast<uint32_t>(static_cast<int32_t>(std::floor(coordinate / size)));
}

}  // namespace lineloc

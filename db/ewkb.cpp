#include "db/ewkb.h"

#include <bit>
#include <cstdint>
#include <cstring>

namespace lineloc::db {
namespace {

constexpr uint32_t kLineString = 2;
constexpr uint32_t kPolygon = 3;
constexpr uint32_t kHasZ = 0x80000000u;
constexpr uint32_t kHasSrid = 0x20000000u;
constexpr uint32_t kHasM = 0x40000000u;
constexpr uint8_t kLittleEndian = 1;

// Little-endian output: lineloc targets little-endian hosts (static_assert below).
class Writer {
 public:
  explicit Writer(std::string& out) : out_(out) {}

  void u32(uint32_t value) { out_.append(reinterpret_cast<const char*>(&value), sizeof(value)); }
  void point(const Eigen::Vector3d& p) {
    out_.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(double));
  }
  void header(uint32_t type, int srid) {
    out_.push_back(static_cast<char>(kLittleEndian));
    u32(type | kHasZ | kHasSrid);
    u32(static_cast<uint32_t>(srid));
  }

 private:
  std::string& out_;
};

static_assert(std::endian::native == std::endian::little, "EWKB writer assumes little endian");

class Reader {
 public:
  Reader(const char* bytes, size_t length) : bytes_(bytes), length_(length) {}

  bool u8(uint8_t& value) { return raw(&value, 1); }
  bool u32(uint32_t& value) {
    if (!raw(&value, 4))
      return false;
    if (swap_)
      value = __builtin_bswap32(value);
    return true;
  }
  bool f64(double& value) {
    uint64_t bits;
    if (!raw(&bits, 8))
      return false;
    if (swap_)
      bits = __builtin_bswap64(bits);
    value = std::bit_cast<double>(bits);
    return true;
  }
  void setByteOrder(uint8_t order) {
    swap_ = (order == kLittleEndian) != (std::endian::native == std::endian::little);
  }
  bool points(uint32_t count, std::vector<Eigen::Vector3d>& out) {
    if (count > (length_ - at_) / 24)
      return false;
    out.resize(count);
    for (Eigen::Vector3d& p : out) {
      if (!f64(p.x()) || !f64(p.y()) || !f64(p.z()))
        return false;
    }
    return true;
  }

 private:
  bool raw(void* out, size_t size) {
    if (length_ - at_ < size)
      return false;
    std::memcpy(out, bytes_ + at_, size);
    at_ += size;
    return true;
  }

  const char* bytes_;
  size_t length_;
  size_t at_ = 0;
  bool swap_ = false;
};

}  // namespace

void appendEwkbLineStringZ(std::string& out, int srid, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  Writer writer(out);
  writer.header(kLineString, srid);
  writer.u32(2);
  writer.point(a);
  writer.point(b);
}

void appendEwkbPolygonZ(std::string& out, int srid,
                        const std::vector<std::vector<Eigen::Vector3d>>& rings) {
  Writer writer(out);
  writer.header(kPolygon, srid);
  writer.u32(static_cast<uint32_t>(rings.size()));
  for (const auto& ring : rings) {
    writer.u32(static_cast<uint32_t>(ring.size() + 1));
    for (const Eigen::Vector3d& point : ring) {
      writer.point(point);
    }
    writer.point(ring.front());
  }
}

std::optional<std::vector<std::vector<Eigen::Vector3d>>> decodeEwkbZ(const char* bytes,
                                                                     size_t length) {
  Reader reader(bytes, length);
  uint8_t order = 0;
  uint32_t type = 0;
  if (!reader.u8(order) || order > 1)
    return std::nullopt;
  reader.setByteOrder(order);
  if (!reader.u32(type) || !(type & kHasZ) || (type & kHasM))
    return std::nullopt;
  if (type & kHasSrid) {
    uint32_t srid;
    if (!reader.u32(srid))
      return std::nullopt;
  }
  const uint32_t base = type & 0xFFFF;
  std::vector<std::vector<Eigen::Vector3d>> rings;
  uint32_t ring_count = 1;
  if (base == kPolygon) {
    if (!reader.u32(ring_count) || ring_count > length)
      return std::nullopt;
  } else if (base != kLineString) {
    return std::nullopt;
  }
  rings.resize(ring_count);
  for (auto& ring : rings) {
    uint32_t count = 0;
    if (!reader.u32(count) || !reader.points(count, ring))
      return std::nullopt;
  }
  return rings;
}

}  // namespace lineloc::db

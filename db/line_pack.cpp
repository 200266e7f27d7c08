#include "db/line_pack.h"

#include <fmt/format.h>

#include "db/big_endian.h"

namespace lineloc::db {
namespace {

constexpr int16_t kLastKind = static_cast<int16_t>(LineKind::kGround);

void appendVector(std::string& out, const Eigen::Vector3d& v) {
  appendBigEndian(out, v.x());
  appendBigEndian(out, v.y());
  appendBigEndian(out, v.z());
}

class RecordReader {
 public:
  explicit RecordReader(const char* record) : at_(record) {}

  template <typename T>
  T next() {
    const T value = readBigEndian<T>(at_);
    at_ += sizeof(T);
    return value;
  }
  Eigen::Vector3d nextVector() {
    const double x = next<double>();
    const double y = next<double>();
    return {x, y, next<double>()};
  }

 private:
  const char* at_;
};

}  // namespace

void appendLinePackRecord(std::string& pack, int64_t line_id,
                          const citymodel::ExtractedLine& line) {
  appendBigEndian(pack, line_id);
  appendBigEndian(pack, static_cast<int16_t>(line.kind));
  appendBigEndian<int32_t>(pack, line.face_a);
  appendBigEndian<int32_t>(pack, line.face_b);
  appendVector(pack, line.start);
  appendVector(pack, line.end);
  appendVector(pack, line.normal_a);
  appendVector(pack, line.normal_b);
}

void decodeLinePack(std::string_view pack, int64_t building_id, const Eigen::Vector3d& origin,
                    std::vector<ModelLine>& lines) {
  if (pack.size() % kLinePackRecordBytes != 0) {
    throw DatabaseError(
        fmt::format("building {}: line pack of {} bytes is not a whole number of {}-byte records",
                    building_id, pack.size(), kLinePackRecordBytes));
  }
  for (size_t at = 0; at < pack.size(); at += kLinePackRecordBytes) {
    RecordReader record(pack.data() + at);
    ModelLine line;
    line.id = record.next<int64_t>();
    line.building_id = building_id;
    const auto kind = record.next<int16_t>();
    line.face_a = record.next<int32_t>();
    line.face_b = record.next<int32_t>();
    line.start_world = record.nextVector() - origin;
    line.end_world = record.nextVector() - origin;
    line.normal_a = record.nextVector();
    line.normal_b = record.nextVector();
    if (kind < 0 || kind > kLastKind) {
      throw DatabaseError(
          fmt::format("building {}, line {}: unknown kind {}", building_id, line.id, kind));
    }
    line.kind = static_cast<LineKind>(kind);
    if (!line.start_world.allFinite() || !line.end_world.allFinite() ||
        !line.normal_a.allFinite() || !line.normal_b.allFinite()) {
      throw DatabaseError(fmt::format("building {}, line {}: coordinate or normal not finite",
                                      building_id, line.id));
    }
    lines.push_back(line);
  }
}

}  // namespace lineloc::db

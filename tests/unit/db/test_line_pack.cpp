// The packed line records of table building_line_pack: what the loader
// appends decodes back exactly, and malformed packs are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "db/big_endian.h"
#include "db/line_pack.h"

namespace lineloc::db {
namespace {

citymodel::ExtractedLine ridge() {
  return {.start = {85010.25, 447020.5, 12.75},
          .end = {85030.125, 447020.5, 12.75},
          .kind = LineKind::kRidge,
          .face_a = 3,
          .face_b = 4,
          .normal_a = {0.0, 0.6, 0.8},
          .normal_b = {0.0, -0.6, 0.8}};
}

// A line on one face only: no second face, zero second normal.
citymodel::ExtractedLine freeBorder() {
  return {.start = {85000.0, 447000.0, 0.0},
          .end = {85000.0, 447000.0, 9.5},
          .kind = LineKind::kVertical,
          .face_a = 0,
          .normal_a = Eigen::Vector3d::UnitX()};
}

TEST(LinePack, RecordsDecodeExactlyIntoWorldCoordinates) {
  std::string pack;
  appendLinePackRecord(pack, 41, ridge());
  appendLinePackRecord(pack, 42, freeBorder());
  ASSERT_EQ(pack.size(), 2 * kLinePackRecordBytes);

  const Eigen::Vector3d origin(85000.0, 447000.0, 0.0);
  std::vector<ModelLine> lines;
  decodeLinePack(pack, 7, origin, lines);
  ASSERT_EQ(lines.size(), 2u);
  // Every value is exactly representable, so the round trip is exact.
  EXPECT_EQ(lines[0].id, 41);
  EXPECT_EQ(lines[0].building_id, 7);
  EXPECT_EQ(lines[0].kind, LineKind::kRidge);
  EXPECT_EQ(lines[0].start_world, Eigen::Vector3d(10.25, 20.5, 12.75));
  EXPECT_EQ(lines[0].end_world, Eigen::Vector3d(30.125, 20.5, 12.75));
  EXPECT_EQ(lines[0].face_a, 3);
  EXPECT_EQ(lines[0].face_b, 4);
  EXPECT_EQ(lines[0].normal_a, ridge().normal_a);
  EXPECT_EQ(lines[0].normal_b, ridge().normal_b);
  EXPECT_EQ(lines[1].id, 42);
  EXPECT_EQ(lines[1].face_b, -1);
  EXPECT_EQ(lines[1].normal_b, Eigen::Vector3d::Zero());
  EXPECT_EQ(lines[1].end_world, Eigen::Vector3d(0.0, 0.0, 9.5));
}

TEST(LinePack, FieldsAreBigEndianAsPostgresSendFunctionsWriteThem) {
  std::string pack;
  appendLinePackRecord(pack, 0x0102030405060708, ridge());
  EXPECT_EQ(pack.substr(0, 8), std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8));
  EXPECT_EQ(readBigEndian<int16_t>(pack.data() + 8), 3);
  // float8send(85010.25): sign 0, exponent 1023 + 16, so the bytes start 0x40 0xF4.
  EXPECT_EQ(static_cast<uint8_t>(pack[18]), 0x40);
  EXPECT_EQ(static_cast<uint8_t>(pack[19]), 0xF4);
  EXPECT_EQ(readBigEndian<double>(pack.data() + 18), 85010.25);
}

TEST(LinePack, AnEmptyPackHasNoLines) {
  std::vector<ModelLine> lines;
  decodeLinePack({}, 1, Eigen::Vector3d::Zero(), lines);
  EXPECT_TRUE(lines.empty());
}

void expectRefused(const std::string& pack, const std::string& message_part) {
  std::vector<ModelLine> lines;
  try {
    decodeLinePack(pack, 99, Eigen::Vector3d::Zero(), lines);
    FAIL() << "a malformed pack must be refused";
  } catch (const DatabaseError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("building 99"), std::string::npos) << what;
    EXPECT_NE(what.find(message_part), std::string::npos) << what;
  }
}

TEST(LinePack, MalformedPacksAreRefusedNamingTheBuilding) {
  std::string pack;
  appendLinePackRecord(pack, 5, ridge());
  expectRefused(pack.substr(0, kLinePackRecordBytes - 1), "not a whole number");
  expectRefused(pack + "x", "not a whole number");

  std::string unknown_kind = pack;
  unknown_kind[8] = '\x00';  // kind, big-endian int16
  unknown_kind[9] = '\x05';
  expectRefused(unknown_kind, "unknown kind 5");
  unknown_kind[8] = '\xFF';
  unknown_kind[9] = '\xFF';
  expectRefused(unknown_kind, "unknown kind -1");

  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    citymodel::ExtractedLine line = ridge();
    line.normal_b.y() = bad;
    std::string not_finite;
    appendLinePackRecord(not_finite, 6, line);
    expectRefused(not_finite, "line 6: coordinate or normal not finite");
  }
}

}  // namespace
}  // namespace lineloc::db

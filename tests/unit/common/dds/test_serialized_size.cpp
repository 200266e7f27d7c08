// The wire size of lineloc's messages against their CDR layout worked out by
// hand from idl/lineloc.idl (XCDR1: primitives aligned to their own size, up to 8).
#include <gtest/gtest.h>

#include "common/messages/messages.h"
#include "common/messages/topics.h"

namespace lineloc {
namespace {

LineSetData lineSet(int segments, int corners) {
  LineSetData line_set;
  line_set.robot_id = "r1";
  line_set.segments.resize(segments);
  line_set.corners.resize(corners);
  return line_set;
}

uint32_t wireBytes(const LineSetData& line_set) {
  const LineSetMessage message(line_set);
  return dds::serializedSizeBytes(message.message());
}

// Encapsulation 4; robot_id 4 + 3 ("r1\0") -> 7; sequence_number at 8 -> 12;
// stamp_ns at 16 -> 24; camera 4 doubles + 2 shorts -> 60; two empty sequence
// lengths -> 68; pose at 72: 7 doubles + 36 -> 416; camera_height_m -> 424.
TEST(SerializedSize, EmptyLineSetIsItsHeaderFields) {
  EXPECT_EQ(wireBytes(lineSet(0, 0)), 4u + 424u);
}

// A segment is 11 floats and a short (46 bytes), padded to the next float: 48.
// A corner is 6 floats: 24.
TEST(SerializedSize, EachSegmentAndCornerAddsItsCdrSize) {
  const uint32_t empty = wireBytes(lineSet(0, 0));
  EXPECT_EQ(wireBytes(lineSet(1, 0)), empty + 48u);
  EXPECT_EQ(wireBytes(lineSet(300, 0)), empty + 300u * 48u);
  EXPECT_EQ(wireBytes(lineSet(300, 50)), empty + 300u * 48u + 50u * 24u);
}

}  // namespace
}  // namespace lineloc

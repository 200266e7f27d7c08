#include <gtest/gtest.h>

#include "common/config/size_pair.h"

namespace lineloc {
namespace {

TEST(SizePair, ParsesWidthAndHeight) {
  const std::optional<SizePair> size = parseSizePair("640x480", 5);
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->first, 640);
  EXPECT_EQ(size->second, 480);
}

TEST(SizePair, RejectsMalformedText) {
  for (const char* text :
       {"", "x", "9x", "x6", "9*6", "9x6x2", " 9x6", "9x6 ", "-9x6", "9X6", "9x+6", "123456x1"}) {
    EXPECT_FALSE(parseSizePair(text, 5).has_value()) << "'" << text << "'";
  }
}

TEST(SizePair, LimitsTheNumberOfDigits) {
  EXPECT_TRUE(parseSizePair("9999x9999", 4).has_value());
  EXPECT_FALSE(parseSizePair("10000x9", 4).has_value());
}

}  // namespace
}  // namespace lineloc

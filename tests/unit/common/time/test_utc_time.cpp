// ISO 8601 UTC text <-> Unix nanoseconds, and the errors that name what is wrong.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "common/time/utc_time.h"

namespace lineloc {
namespace {

TEST(UtcTime, ParsesKnownInstants) {
  EXPECT_EQ(parseUtcTime_ns("1970-01-01T00:00:00Z"), 0);
  EXPECT_EQ(parseUtcTime_ns("2000-01-01T12:00:00Z"), 946'728'000'000'000'000);
  // The simulator's default start.
  EXPECT_EQ(parseUtcTime_ns("2023-11-14T22:13:20Z"), 1'700'000'000'000'000'000);
  EXPECT_EQ(parseUtcTime_ns("2024-02-29T23:59:59.5Z"), 1'709'251'199'500'000'000);
  EXPECT_EQ(parseUtcTime_ns("2026-05-21T08:30:00.000000001Z"), 1'779'352'200'000'000'001);
}

TEST(UtcTime, FormatsAndParsesBack) {
  for (const int64_t stamp_ns :
       {int64_t{0}, int64_t{1'700'000'000'000'000'000}, int64_t{1'779'352'200'000'000'001},
        int64_t{1'709'251'199'500'000'000}}) {
    EXPECT_EQ(parseUtcTime_ns(formatUtcTime(stamp_ns)), stamp_ns) << formatUtcTime(stamp_ns);
  }
  EXPECT_EQ(formatUtcTime(1'700'000'000'000'000'000), "2023-11-14T22:13:20Z");
  EXPECT_EQ(formatUtcTime(1'709'251'199'500'000'000), "2024-02-29T23:59:59.500000000Z");
}

// The message of the error `text` raises.
std::string errorOf(const std::string& text) {
  try {
    parseUtcTime_ns(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "accepted";
}

TEST(UtcTime, MalformedTextNamesTheCharacterAndTheField) {
  EXPECT_NE(errorOf("").find("character 1: expected a digit of the year"), std::string::npos);
  EXPECT_NE(errorOf("2026-13-01T00:00:00Z").find("character 6: month 13 is outside 1..12"),
            std::string::npos);
  EXPECT_NE(errorOf("2026-02-30T00:00:00Z").find("character 9: 2026-02 has no day 30"),
            std::string::npos);
  EXPECT_NE(errorOf("2026-05-21 08:30:00Z").find("character 11: expected 'T'"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00").find("character 20: expected 'Z'"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00+02:00").find("expected 'Z'"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:60Z").find("second 60 is outside 0..59"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T24:00:00Z").find("hour 24"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00.Z").find("expected a digit after '.'"), std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00.1234567890Z").find("more than nine digits"),
            std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00Zx").find("character 21: expected the end"),
            std::string::npos);
  EXPECT_NE(errorOf("1969-12-31T23:59:59Z").find("year 1969 is outside 1970..2261"),
            std::string::npos);
  EXPECT_NE(errorOf("2026-05-21T08:30:00Z").find("accepted"), std::string::npos);
}

}  // namespace
}  // namespace lineloc

#include "common/nmea/nmea_sentence.h"

#include <gtest/gtest.h>

namespace lineloc {
namespace {

constexpr int64_t kNsPerSecond = 1'000'000'000;

// The textbook sentences (NMEA 0183 reference examples) with their published checksums.
constexpr const char* kClassicGga =
    "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
constexpr const char* kClassicRmc =
    "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A";

// Rebuilds a sentence with a correct checksum so only the named field is wrong.
std::string withValidChecksum(const std::string& body) {
  char hex[3];
  std::snprintf(hex, sizeof(hex), "%02X", nmeaChecksum(body));
  return "$" + body + "*" + hex;
}

TEST(NmeaChecksum, MatchesPublishedExample) {
  const std::string_view sentence(kClassicGga);
  EXPECT_EQ(nmeaChecksum(sentence.substr(1, sentence.size() - 4)), 0x47);
}

TEST(ParseNmea, ClassicGga) {
  const NmeaParseResult result = parseNmeaSentence(std::string(kClassicGga) + "\r\n");
  ASSERT_EQ(result.status, NmeaStatus::kOk) << result.error;
  const auto& gga = std::get<GgaSentence>(result.sentence);
  EXPECT_EQ(gga.talker, "GP");
  EXPECT_EQ(gga.time_of_day_ns, (12 * 3600 + 35 * 60 + 19) * kNsPerSecond);
  EXPECT_DOUBLE_EQ(gga.latitude_deg, 48.0 + 7.038 / 60.0);
  EXPECT_DOUBLE_EQ(gga.longitude_deg, 11.0 + 31.0 / 60.0);
  EXPECT_EQ(gga.fix_quality, 1);
  EXPECT_EQ(gga.satellites, 8);
  EXPECT_DOUBLE_EQ(gga.hdop, 0.9);
  EXPECT_DOUBLE_EQ(gga.ellipsoidHeight_m(), 545.4 + 46.9);
}

TEST(ParseNmea, ClassicRmcWithDate) {
  const NmeaParseResult result = parseNmeaSentence(kClassicRmc);
  ASSERT_EQ(result.status, NmeaStatus::kOk) << result.error;
  const auto& rmc = std::get<RmcSentence>(result.sentence);
  EXPECT_TRUE(rmc.valid);
  EXPECT_EQ(rmc.year, 1994);
  EXPECT_EQ(rmc.month, 3);
  EXPECT_EQ(rmc.day, 23);
  EXPECT_EQ(rmc.speed_knots, 22.4);
  EXPECT_EQ(rmc.course_deg, 84.4);
  // 1994-03-23 12:35:19 UTC = 764426119 s after the epoch (date -u -d @764426119).
  EXPECT_EQ(rmc.utcStamp_ns(), 764'426'119 * kNsPerSecond);
}

TEST(ParseNmea, SouthAndWestAreNegative) {
  GgaSentence gga;
  gga.latitude_deg = -33.8567844;
  gga.longitude_deg = -151.2152967;
  gga.fix_quality = 2;
  const NmeaParseResult result = parseNmeaSentence(formatGga(gga));
  ASSERT_EQ(result.status, NmeaStatus::kOk) << result.error;
  // 7 decimals of arc minutes: at most 0.5e-7 / 60 degrees of rounding.
  EXPECT_NEAR(std::get<GgaSentence>(result.sentence).latitude_deg, gga.latitude_deg, 1e-9);
  EXPECT_NEAR(std::get<GgaSentence>(result.sentence).longitude_deg, gga.longitude_deg, 1e-9);
}

TEST(FormatNmea, GgaRoundTrip) {
  GgaSentence gga;
  gga.talker = "GN";
  gga.time_of_day_ns = 36'915'250'000'000;
  gga.latitude_deg = 52.0116;
  gga.longitude_deg = 4.3571;
  gga.fix_quality = 2;
  gga.satellites = 12;
  gga.hdop = 0.8;
  gga.altitude_msl_m = 1.234;
  gga.geoid_separation_m = 43.21;
  const std::string text = formatGga(gga);
  const NmeaParseResult result = parseNmeaSentence(text);
  ASSERT_EQ(result.status, NmeaStatus::kOk) << text << ": " << result.error;
  const auto& parsed = std::get<GgaSentence>(result.sentence);
  EXPECT_EQ(parsed.talker, "GN");
  EXPECT_EQ(parsed.time_of_day_ns, gga.time_of_day_ns);
  EXPECT_NEAR(parsed.latitude_deg, gga.latitude_deg, 1e-9);
  EXPECT_NEAR(parsed.longitude_deg, gga.longitude_deg, 1e-9);
  EXPECT_EQ(parsed.fix_quality, 2);
  EXPECT_EQ(parsed.satellites, 12);
  EXPECT_DOUBLE_EQ(parsed.altitude_msl_m, 1.234);
  EXPECT_DOUBLE_EQ(parsed.geoid_separation_m, 43.21);
}

TEST(FormatNmea, RmcRoundTrip) {
  RmcSentence rmc;
  rmc.time_of_day_ns = 86'399'999'000'000;
  rmc.valid = true;
  rmc.latitude_deg = 52.0116;
  rmc.longitude_deg = 4.3571;
  rmc.speed_knots = 2.5;
  rmc.course_deg = 271.25;
  rmc.year = 2026;
  rmc.month = 11;
  rmc.day = 22;
  const NmeaParseResult result = parseNmeaSentence(formatRmc(rmc));
  ASSERT_EQ(result.status, NmeaStatus::kOk) << result.error;
  const auto& parsed = std::get<RmcSentence>(result.sentence);
  EXPECT_EQ(parsed.utcStamp_ns(), rmc.utcStamp_ns());
  EXPECT_NEAR(parsed.latitude_deg, rmc.latitude_deg, 1e-9);
  EXPECT_EQ(parsed.speed_knots, 2.5);
  EXPECT_EQ(parsed.course_deg, 271.25);
}

// A receiver standing still leaves the course out, some the speed too: an
// empty field is "not given", not zero, both ways.
TEST(FormatNmea, RmcWithoutSpeedOrCourseRoundTrip) {
  const NmeaParseResult result =
      parseNmeaSentence(withValidChecksum("GPRMC,123519,A,4807.038,N,01131.000,E,0.0,,230394,,"));
  ASSERT_EQ(result.status, NmeaStatus::kOk) << result.error;
  const auto& rmc = std::get<RmcSentence>(result.sentence);
  EXPECT_EQ(rmc.speed_knots, 0.0);
  EXPECT_FALSE(rmc.course_deg);
  RmcSentence without_speed = rmc;
  without_speed.speed_knots.reset();
  const std::string text = formatRmc(without_speed);
  EXPECT_NE(text.find(",E,,,230394,"), std::string::npos) << text;
  const NmeaParseResult reparsed = parseNmeaSentence(text);
  ASSERT_EQ(reparsed.status, NmeaStatus::kOk) << reparsed.error;
  const auto& parsed = std::get<RmcSentence>(reparsed.sentence);
  EXPECT_FALSE(parsed.speed_knots);
  EXPECT_FALSE(parsed.course_deg);
}

TEST(FormatNmea, MinutesThatRoundUpCarryIntoDegrees) {
  GgaSentence gga;
  gga.fix_quality = 1;
  gga.latitude_deg = 52.0 - 1e-12;
  const std::string text = formatGga(gga);
  EXPECT_NE(text.find(",5200.0000000,N,"), std::string::npos) << text;
}

TEST(ParseNmea, NoFixIsReportedWithTheSentence) {
  GgaSentence gga;
  gga.time_of_day_ns = 1000 * kNsPerSecond;
  gga.fix_quality = 0;
  const NmeaParseResult result = parseNmeaSentence(formatGga(gga));
  EXPECT_EQ(result.status, NmeaStatus::kNoFix);
  EXPECT_EQ(std::get<GgaSentence>(result.sentence).time_of_day_ns, gga.time_of_day_ns);

  RmcSentence rmc;
  rmc.valid = false;
  EXPECT_EQ(parseNmeaSentence(formatRmc(rmc)).status, NmeaStatus::kNoFix);
}

struct MalformedCase {
  const char* name;
  std::string sentence;
  NmeaStatus expected;
};

TEST(ParseNmea, RejectsMalformedInputNamingTheProblem) {
  const std::vector<MalformedCase> cases = {
      {"empty", "", NmeaStatus::kBadFraming},
      {"no dollar", "GPGGA,123519*47", NmeaStatus::kBadFraming},
      {"no checksum", "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       NmeaStatus::kBadFraming},
      {"bad checksum", "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*48",
       NmeaStatus::kBadChecksum},
      {"non-hex checksum", "$GPGGA,123519*ZZ", NmeaStatus::kBadFraming},
      {"too long", "$GPGGA," + std::string(200, '1') + "*00", NmeaStatus::kBadFraming},
      {"binary byte",
       withValidChecksum("GPGGA,12\x01"
                         "3519"),
       NmeaStatus::kBadFraming},
      {"unsupported", withValidChecksum("GPGSV,3,1,11"), NmeaStatus::kUnsupportedType},
      {"short address", withValidChecksum("GGA,1"), NmeaStatus::kMalformedField},
      {"few fields", withValidChecksum("GPGGA,123519,4807.038,N"), NmeaStatus::kMalformedField},
      {"bad hour",
       withValidChecksum("GPGGA,253519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"bad hemisphere",
       withValidChecksum("GPGGA,123519,4807.038,X,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"minutes >= 60",
       withValidChecksum("GPGGA,123519,4867.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"latitude > 90",
       withValidChecksum("GPGGA,123519,9107.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"nan altitude",
       withValidChecksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,nan,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"huge altitude",
       withValidChecksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,1e300,M,46.9,M,,"),
       NmeaStatus::kMalformedField},
      {"bad date", withValidChecksum("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,320394,,"),
       NmeaStatus::kMalformedField},
      {"negative speed",
       withValidChecksum("GPRMC,123519,A,4807.038,N,01131.000,E,-1.0,084.4,230394,,"),
       NmeaStatus::kMalformedField},
      {"speed not a number",
       withValidChecksum("GPRMC,123519,A,4807.038,N,01131.000,E,fast,084.4,230394,,"),
       NmeaStatus::kMalformedField},
      {"course > 360",
       withValidChecksum("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,361.0,230394,,"),
       NmeaStatus::kMalformedField},
      {"bad status",
       withValidChecksum("GPRMC,123519,Q,4807.038,N,01131.000,E,022.4,084.4,230394,,"),
       NmeaStatus::kMalformedField},
  };
  for (const MalformedCase& c : cases) {
    const NmeaParseResult result = parseNmeaSentence(c.sentence);
    EXPECT_EQ(result.status, c.expected) << c.name << ": " << result.error;
    EXPECT_FALSE(result.error.empty()) << c.name;
  }
}

}  // namespace
}  // namespace lineloc

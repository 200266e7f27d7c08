#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/nmea/nmea_sentence.h"
#include "robot/inertial/nmea_gps_decoder.h"
#include "robot/inertial/sensor_csv.h"
#include "robot/inertial/sensor_line_reader.h"

namespace lineloc {
namespace {

constexpr int64_t kNsPerDay = 86'400'000'000'000;

TEST(SensorCsv, ParsesEurocImuLines) {
  // The first data line of EuRoC MH_01_easy imu0/data.csv.
  const auto line = parseEurocImuLine(
      "1403636579758555392,-0.099134701513277898,0.14730578886832138,0.02722713633111154,"
      "8.1476917083333333,-0.37592158333333331,-2.4026292499999999\r");
  ASSERT_EQ(line.kind, CsvLineKind::kRecord) << line.error;
  EXPECT_EQ(line.record.stamp_ns, 1403636579758555392);
  EXPECT_DOUBLE_EQ(line.record.gyro_radps.y(), 0.14730578886832138);
  EXPECT_DOUBLE_EQ(line.record.accel_mps2.x(), 8.1476917083333333);
  EXPECT_EQ(parseEurocImuLine("#timestamp [ns],w_RS_S_x [rad s^-1]").kind, CsvLineKind::kSkipped);
  EXPECT_EQ(parseEurocImuLine("   ").kind, CsvLineKind::kSkipped);
}

TEST(SensorCsv, RejectsMalformedLinesSayingWhy) {
  for (const char* text :
       {"1,2,3", "1,2,3,4,5,6,7,8", "x,0,0,0,0,0,9.8", "-5,0,0,0,0,0,9.8", "1,0,0,zero,0,0,9.8",
        "1,0,0,0,0,0,", "1.5,0,0,0,0,0,9.8", "1,0,0,0,0,0,9.8,,,,,,,,,,"}) {
    const auto line = parseEurocImuLine(text);
    EXPECT_EQ(line.kind, CsvLineKind::kMalformed) << text;
    EXPECT_FALSE(line.error.empty());
  }
  // "nan" is a number: it reaches the navigator, which drops and counts it.
  EXPECT_EQ(parseEurocImuLine("1,nan,0,0,0,0,9.8").kind, CsvLineKind::kRecord);
}

TEST(SensorCsv, ParsesCompassLines) {
  const auto line = parseCompassLine("1700000000000000000, 4.2856546");
  ASSERT_EQ(line.kind, CsvLineKind::kRecord) << line.error;
  EXPECT_DOUBLE_EQ(line.record.magnetic_heading_rad, 4.2856546);
  EXPECT_EQ(parseCompassLine("1,inf").kind, CsvLineKind::kMalformed);
  EXPECT_EQ(parseCompassLine("1,90,3").kind, CsvLineKind::kMalformed);
  EXPECT_EQ(parseCompassLine("# t, heading").kind, CsvLineKind::kSkipped);
}

TEST(SensorCsv, FileReaderCountsAndLocatesBadLines) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("lineloc_compass_" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream file(path);
    file << "#timestamp [ns],heading [rad]\n1,0.1\n2,ten\n3,0.3\n";
  }
  const auto file = readCompassCsv(path.string());
  ASSERT_EQ(file.records.size(), 2u);
  EXPECT_EQ(file.malformed_lines, 1);
  ASSERT_EQ(file.errors.size(), 1u);
  EXPECT_NE(file.errors[0].find(path.string() + ":3:"), std::string::npos) << file.errors[0];
  std::filesystem::remove(path);
  EXPECT_THROW(readEurocImuCsv(path.string()), std::runtime_error);
}

SiteProjection delftSite() {
  return SiteProjection("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
}

// A valid RMC at 10:00 UTC on 22 November 2026, at `position`.
RmcSentence rmcAt(const GeodeticPosition& position) {
  RmcSentence rmc;
  rmc.valid = true;
  rmc.time_of_day_ns = 36'000'000'000'000;
  rmc.year = 2026;
  rmc.month = 11;
  rmc.day = 22;
  rmc.latitude_deg = position.latitude_deg;
  rmc.longitude_deg = position.longitude_deg;
  return rmc;
}

TEST(NmeaGpsDecoder, DatesGgaWithRmcAndProjectsToTheSite) {
  NmeaGpsDecoder decoder(delftSite());
  const Eigen::Vector3d p_site(120.0, -45.0, 2.0);
  const GeodeticPosition position = decoder.projection().toGeodetic(p_site);
  const RmcSentence rmc = rmcAt(position);
  GgaSentence gga;
  gga.time_of_day_ns = rmc.time_of_day_ns;
  gga.fix_quality = 2;
  gga.latitude_deg = position.latitude_deg;
  gga.longitude_deg = position.longitude_deg;
  gga.altitude_msl_m = position.height_msl_m;
  EXPECT_TRUE(std::holds_alternative<std::monostate>(decoder.decode(formatGga(gga))));
  EXPECT_EQ(decoder.counters().undated, 1);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(decoder.decode(formatRmc(rmc))));
  const GpsReading reading = decoder.decode(formatGga(gga));
  const auto* fix = std::get_if<GpsFix>(&reading);
  ASSERT_NE(fix, nullptr);
  EXPECT_EQ(fix->stamp_ns, rmc.utcStamp_ns());
  // NMEA keeps 0.2 mm of latitude/longitude and 1 mm of altitude.
  EXPECT_LT((fix->p_world_antenna - p_site).norm(), 2e-3);
  EXPECT_EQ(decoder.counters().fixes, 1);
}

// A fix's sigma is its HDOP times the ranging error of its quality; a
// quality that says nothing of the error leaves the navigator's own.
TEST(NmeaGpsDecoder, SetsEachFixsSigmaFromItsQualityAndHdop) {
  GnssErrorModel errors;
  errors.rtk_fixed_sigma_m = 0.02;
  NmeaGpsDecoder decoder(delftSite(), errors);
  const GeodeticPosition position = decoder.projection().toGeodetic({10.0, 20.0, 1.0});
  const RmcSentence rmc = rmcAt(position);
  decoder.decode(formatRmc(rmc));
  const auto fixOf = [&](int quality, double hdop) {
    GgaSentence gga;
    gga.time_of_day_ns = rmc.time_of_day_ns;
    gga.fix_quality = quality;
    gga.hdop = hdop;
    gga.latitude_deg = position.latitude_deg;
    gga.longitude_deg = position.longitude_deg;
    const GpsReading reading = decoder.decode(formatGga(gga));
    EXPECT_TRUE(std::holds_alternative<GpsFix>(reading)) << quality;
    return std::holds_alternative<GpsFix>(reading) ? std::get<GpsFix>(reading) : GpsFix{};
  };
  const GpsFix rtk = fixOf(4, 0.8);
  EXPECT_NEAR(rtk.horizontal_sigma_m, 0.016, 1e-9);
  EXPECT_NEAR(rtk.vertical_sigma_m, 0.032, 1e-9);
  EXPECT_NEAR(fixOf(2, 0.9).horizontal_sigma_m, 0.9 * errors.dgps_sigma_m, 1e-9);
  EXPECT_NEAR(fixOf(1, 2.0).horizontal_sigma_m, 2.0 * errors.gps_sigma_m, 1e-9);
  EXPECT_NEAR(fixOf(5, 1.0).vertical_sigma_m, 2.0 * errors.rtk_float_sigma_m, 1e-9);
  EXPECT_EQ(fixOf(6, 1.0).horizontal_sigma_m, 0.0);  // dead reckoning: no word on its error
  EXPECT_EQ(fixOf(2, 0.0).horizontal_sigma_m, 0.0);  // no HDOP
  GnssErrorModel negative;
  negative.dgps_sigma_m = -1.0;
  try {
    NmeaGpsDecoder refused(delftSite(), negative);
    FAIL() << "a negative ranging error accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("gnss_dgps_sigma_m"), std::string::npos);
  }
}

TEST(NmeaGpsDecoder, CountsBadSentencesAndDatesByReference) {
  NmeaGpsDecoder decoder(delftSite());
  std::string good = formatGga([] {
    GgaSentence gga;
    gga.time_of_day_ns = 100'000'000'000;  // 00:01:40 UTC
    gga.fix_quality = 1;
    gga.latitude_deg = 52.01;
    gga.longitude_deg = 4.35;
    return gga;
  }());
  std::string corrupted = good;
  corrupted[10] = corrupted[10] == '1' ? '2' : '1';
  const auto nothing = [&](std::string_view line) {
    return std::holds_alternative<std::monostate>(decoder.decode(line, 1));
  };
  EXPECT_TRUE(nothing(corrupted));
  EXPECT_TRUE(nothing(fmt::format("$GPGGA,bad*{:02X}", nmeaChecksum("GPGGA,bad"))));
  EXPECT_TRUE(nothing(formatGga(GgaSentence{})));  // quality 0
  EXPECT_TRUE(nothing("$GPGSV,1,1,00*79"));
  // Reference late on the previous day: the fix is just after midnight.
  const int64_t reference = 20'000 * kNsPerDay - 60'000'000'000;
  const GpsReading reading = decoder.decode(good, reference);
  const auto* fix = std::get_if<GpsFix>(&reading);
  ASSERT_NE(fix, nullptr);
  EXPECT_EQ(fix->stamp_ns, 20'000 * kNsPerDay + 100'000'000'000);
  const NmeaCounters& counters = decoder.counters();
  EXPECT_EQ(counters.bad_checksum, 1);
  EXPECT_EQ(counters.malformed, 1);
  EXPECT_EQ(counters.no_fix, 1);
  EXPECT_EQ(counters.unsupported, 1);
}

// RMC's speed and course give the velocity in the site frame: the course, a
// true bearing, turned by the grid bearing of true north there (1.3 degrees
// at Delft in UTM zone 31). A speed of zero needs no course; a speed without
// a course, or an RMC without a speed, gives no velocity.
TEST(NmeaGpsDecoder, TurnsRmcSpeedAndCourseIntoTheSiteFrame) {
  NmeaGpsDecoder decoder(delftSite());
  const GeodeticPosition position = decoder.projection().toGeodetic({10.0, 20.0, 0.0});
  const double grid_bearing_of_true_north_rad =
      decoder.projection().gridBearingOfTrueNorth_rad(position);
  ASSERT_GT(std::abs(grid_bearing_of_true_north_rad), 1.0 * M_PI / 180.0);
  RmcSentence rmc = rmcAt(position);
  rmc.speed_knots = 10.0;
  rmc.course_deg = 30.0;
  const GpsReading reading = decoder.decode(formatRmc(rmc));
  const auto* velocity = std::get_if<GpsVelocity>(&reading);
  ASSERT_NE(velocity, nullptr);
  EXPECT_EQ(velocity->stamp_ns, rmc.utcStamp_ns());
  const double speed_mps = 10.0 * 1852.0 / 3600.0;
  const double grid_bearing_rad = 30.0 * M_PI / 180.0 + grid_bearing_of_true_north_rad;
  EXPECT_NEAR(velocity->v_world_mps.x(), speed_mps * std::sin(grid_bearing_rad), 1e-6);
  EXPECT_NEAR(velocity->v_world_mps.y(), speed_mps * std::cos(grid_bearing_rad), 1e-6);

  rmc.speed_knots = 0.0;
  rmc.course_deg.reset();
  const GpsReading standing = decoder.decode(formatRmc(rmc));
  ASSERT_TRUE(std::holds_alternative<GpsVelocity>(standing));
  EXPECT_EQ(std::get<GpsVelocity>(standing).v_world_mps, Eigen::Vector2d::Zero());
  rmc.speed_knots = 3.0;
  EXPECT_TRUE(std::holds_alternative<std::monostate>(decoder.decode(formatRmc(rmc))));
  rmc.speed_knots.reset();
  EXPECT_TRUE(std::holds_alternative<std::monostate>(decoder.decode(formatRmc(rmc))));
  EXPECT_EQ(decoder.counters().velocities, 2);
  EXPECT_EQ(decoder.counters().malformed, 0);
}

TEST(SensorLineReader, ReadsNmeaLinesFromAPseudoTerminal) {
  int master = -1;
  int slave = -1;
  char name[256] = {};
  ASSERT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
  {
    SensorLineReader reader(name, 9600);
    const std::string sentence =
        "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
    const std::string data = sentence + "\r\n" + std::string(300, 'x') + "\n" + "$GPRMC,par";
    ASSERT_EQ(::write(master, data.data(), data.size()), static_cast<ssize_t>(data.size()));
    std::vector<std::string> lines = reader.readLines(1000);
    ASSERT_GE(lines.size(), 1u);
    EXPECT_EQ(lines[0], sentence);
    const std::string rest = "tial\n";
    ASSERT_EQ(::write(master, rest.data(), rest.size()), static_cast<ssize_t>(rest.size()));
    std::vector<std::string> more = reader.readLines(1000);
    lines.insert(lines.end(), more.begin(), more.end());
    ASSERT_EQ(lines.size(), 2u);  // the 300-byte line is dropped
    EXPECT_EQ(lines[1], "$GPRMC,partial");
    EXPECT_EQ(reader.overlongLines(), 1);
    EXPECT_TRUE(reader.readLines(10).empty());  // nothing more: times out
  }
  ::close(slave);
  ::close(master);
  EXPECT_THROW(SensorLineReader(name, 12345), std::invalid_argument);
  EXPECT_THROW(SensorLineReader("/nonexistent/ttyUSB9", 9600), std::runtime_error);
}

// A FIFO's feeder may close it and open it again: the stream goes on. A
// file ends at its end.
TEST(SensorLineReader, AFifoOutlivesItsFeederAndAFileEnds) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / fmt::format("line_reader_{}", ::getpid());
  std::filesystem::create_directories(folder);
  const std::string fifo = (folder / "imu").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  SensorLineReader reader(fifo, 115200);
  for (const std::string line : {"1,0,0,0,0,0,9.8", "2,0,0,0,0,0,9.8"}) {
    const int feeder = ::open(fifo.c_str(), O_WRONLY);
    ASSERT_GE(feeder, 0);
    const std::string data = line + "\n";
    ASSERT_EQ(::write(feeder, data.data(), data.size()), static_cast<ssize_t>(data.size()));
    ::close(feeder);
    const std::vector<std::string> lines = reader.readLines(1000);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0], line);
    EXPECT_FALSE(reader.ended());
  }
  EXPECT_TRUE(reader.readLines(10).empty());
  EXPECT_FALSE(reader.ended());

  const std::string file = (folder / "imu.csv").string();
  std::ofstream(file) << "1,0,0,0,0,0,9.8\n2,0,0,0,0,0,9.8\n";
  SensorLineReader from_file(file, 9600);
  EXPECT_EQ(from_file.readLines(100).size(), 2u);
  EXPECT_TRUE(from_file.readLines(100).empty());
  EXPECT_TRUE(from_file.ended());
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace lineloc

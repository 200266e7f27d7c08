// GpsdClient against a real gpsd fed by gpsfake: each 3D fix of the receiver
// comes back in the site frame where the log put it, at its UTC time, with
// the sigma its RTK quality and gpsd's HDOP give; a gpsd that is not there is
// named.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "common/nmea/nmea_sentence.h"
#include "robot/input/gpsd_client.h"
#include "tests/support/fake_gpsd.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kSecondNs = 1'000'000'000;

SiteProjection delftSite() {
  return SiteProjection("UTM:31N", Eigen::Vector3d(593000.0, 5763000.0, 0.0));
}

std::string withChecksum(const std::string& body) {
  return fmt::format("${}*{:02X}", body, nmeaChecksum(body));
}

// Epoch k at 10:00:0k UTC on 22 November 2026, at site (10 k, 5, 2): RMC,
// GGA (RTK fixed, HDOP 0.8), and a satellites' view (GSA, GSV) for gpsd's
// DOPs. Epoch 5 has its RMC alone: no height, no fix quality, no fix.
std::map<int64_t, Eigen::Vector3d> writeLog(const std::string& path, const SiteProjection& site) {
  std::ofstream log(path);
  std::map<int64_t, Eigen::Vector3d> truth;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d p_site(10.0 * k, 5.0, 2.0);
    const GeodeticPosition position = site.toGeodetic(p_site);
    RmcSentence rmc;
    rmc.valid = true;
    rmc.time_of_day_ns = 36'000 * kSecondNs + k * kSecondNs;
    rmc.year = 2026;
    rmc.month = 11;
    rmc.day = 22;
    rmc.latitude_deg = position.latitude_deg;
    rmc.longitude_deg = position.longitude_deg;
    GgaSentence gga;
    gga.time_of_day_ns = rmc.time_of_day_ns;
    gga.latitude_deg = position.latitude_deg;
    gga.longitude_deg = position.longitude_deg;
    gga.altitude_msl_m = position.height_msl_m;
    gga.fix_quality = 4;
    gga.satellites = 8;
    gga.hdop = 0.8;
    log << formatRmc(rmc) << "\n";
    if (k == 5) {
      break;
    }
    log << formatGga(gga) << "\n";
    log << withChecksum("GPGSA,A,3,04,05,09,12,24,25,29,31,,,,,1.6,0.8,1.4") << "\n";
    log << withChecksum("GPGSV,2,1,08,04,40,083,46,05,17,308,41,09,60,150,45,12,22,040,40") << "\n";
    log << withChecksum("GPGSV,2,2,08,24,50,200,44,25,33,260,42,29,70,100,47,31,15,010,39") << "\n";
    truth[rmc.utcStamp_ns()] = p_site;
  }
  return truth;
}

TEST(GpsdClient, TakesEachFixWhereAndWhenTheReceiverPutIt) {
  const fs::path folder = fs::temp_directory_path() / fmt::format("gpsd_client_{}", getpid());
  fs::create_directories(folder);
  const std::map<int64_t, Eigen::Vector3d> truth =
      writeLog((folder / "drive.nmea").string(), delftSite());
  const test::FakeGpsd gpsd((folder / "drive.nmea").string(), 0.02,
                            (folder / "gpsfake.log").string());
  GnssErrorModel errors;
  errors.rtk_fixed_sigma_m = 0.05;
  GpsdClient client("localhost", gpsd.port(), delftSite(), errors);
  // The log plays over and over: each epoch comes back, with its HDOP once
  // gpsd has reported one.
  std::set<int64_t> fixed, with_sigma;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (with_sigma.size() < truth.size() && std::chrono::steady_clock::now() < deadline) {
    for (const GpsReading& reading : client.read(200).readings) {
      if (const auto* fix = std::get_if<GpsFix>(&reading)) {
        ASSERT_TRUE(truth.contains(fix->stamp_ns)) << fix->stamp_ns;
        // NMEA keeps 0.2 mm of latitude and longitude, 1 mm of height.
        EXPECT_LT((fix->p_world_antenna - truth.at(fix->stamp_ns)).norm(), 2e-3);
        fixed.insert(fix->stamp_ns);
        if (fix->horizontal_sigma_m > 0.0) {
          with_sigma.insert(fix->stamp_ns);
          EXPECT_NEAR(fix->horizontal_sigma_m, 0.8 * 0.05, 1e-9);
          EXPECT_NEAR(fix->vertical_sigma_m, 2.0 * 0.8 * 0.05, 1e-9);
        }
      }
    }
  }
  EXPECT_EQ(fixed.size(), truth.size());
  EXPECT_EQ(with_sigma.size(), truth.size());
  fs::remove_all(folder);
}

TEST(GpsdClient, AGpsdThatIsNotThereIsNamed) {
  try {
    GpsdClient client("localhost", "1", delftSite(), GnssErrorModel{});
    FAIL() << "connected to nothing";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("gpsd at localhost:1"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace lineloc

// LiveSensors: a camera (a video file), an IMU streaming CSV rows into a FIFO
// and a GNSS receiver's NMEA into another, fed as they are measured: every
// reading comes out once, stamped on the robot's time base in its device's
// order, malformed rows and an undated fix dropped and counted; only the
// newest frame waits.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/videoio.hpp>
#include <thread>

#include "common/nmea/nmea_sentence.h"
#include "robot/input/live_sensors.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kMs = 1'000'000;
constexpr int kFrames = 10;
constexpr double kFps = 20.0;
constexpr int kImuSamples = 120;  // 0.6 s at 200 Hz

const Eigen::Vector3d kSiteOrigin(593000.0, 5763000.0, 0.0);

void writeLine(int fd, const std::string& line) {
  const std::string data = line + "\n";
  ASSERT_EQ(::write(fd, data.data(), data.size()), static_cast<ssize_t>(data.size()));
}

TEST(LiveSensors, ReadsEachSensorAsItIsMeasuredOnTheRobotsTime) {
  const fs::path folder = fs::temp_directory_path() / fmt::format("live_sensors_{}", getpid());
  fs::create_directories(folder);
  const std::string video = (folder / "camera.mkv").string();
  {
    cv::VideoWriter writer(video, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('F', 'F', 'V', '1'), kFps,
                           cv::Size(32, 24));
    for (int i = 0; i < kFrames; ++i) {
      writer.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(20 * i)));
    }
  }
  const std::string imu_fifo = (folder / "imu").string();
  const std::string gnss_fifo = (folder / "gnss").string();
  ASSERT_EQ(::mkfifo(imu_fifo.c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(gnss_fifo.c_str(), 0600), 0);

  // A compass's log as a file: read to its end at once.
  const std::string compass_file = (folder / "compass.csv").string();
  std::ofstream(compass_file) << "# timestamp_ns, heading_rad\n1000000000,0.5\nbad,row\n"
                                 "1100000000,0.52\n";

  LiveSensorConfig config;
  config.camera.source = video;
  config.imu_source = imu_fifo;
  config.gnss_source = gnss_fifo;
  config.compass_source = compass_file;
  const RobotTimeBase time_base;
  LiveSensors sensors(config, time_base, "UTM:31N", kSiteOrigin, GnssErrorModel{});

  const int64_t device_start_ns = 1'000'000'000;
  std::thread feeder([&] {
    const int imu = ::open(imu_fifo.c_str(), O_WRONLY);
    const int gnss = ::open(gnss_fifo.c_str(), O_WRONLY);
    const SiteProjection site("UTM:31N", kSiteOrigin);
    const GeodeticPosition position = site.toGeodetic({3.0, 4.0, 1.0});
    GgaSentence gga;
    gga.time_of_day_ns = 36'000'000 * kMs;
    gga.latitude_deg = position.latitude_deg;
    gga.longitude_deg = position.longitude_deg;
    gga.altitude_msl_m = position.height_msl_m;
    gga.fix_quality = 2;
    gga.hdop = 1.0;
    writeLine(gnss, formatGga(gga));  // before any RMC: no date
    RmcSentence rmc;
    rmc.valid = true;
    rmc.time_of_day_ns = gga.time_of_day_ns;
    rmc.year = 2026;
    rmc.month = 11;
    rmc.day = 22;
    rmc.latitude_deg = position.latitude_deg;
    rmc.longitude_deg = position.longitude_deg;
    writeLine(gnss, formatRmc(rmc));
    writeLine(gnss, formatGga(gga));
    writeLine(imu, "1000000000,0.0,0.0,x,0.0,0.0,9.81");  // malformed
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kImuSamples; ++i) {
      std::this_thread::sleep_until(start + std::chrono::milliseconds(5 * i));
      writeLine(imu, fmt::format("{},0.01,0.0,0.0,0.0,0.0,9.81", device_start_ns + i * 5 * kMs));
    }
    ::close(imu);
    ::close(gnss);
  });

  std::vector<ImuSample> imu;
  std::vector<LiveFrame> frames;
  std::vector<GpsFix> fixes;
  std::vector<CompassReading> headings;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while ((!sensors.cameraEnded() || static_cast<int>(imu.size()) < kImuSamples) &&
         std::chrono::steady_clock::now() < deadline) {
    for (LiveReading& reading : sensors.take(50 * kMs)) {
      if (auto* sample = std::get_if<ImuSample>(&reading)) {
        imu.push_back(*sample);
      } else if (auto* frame = std::get_if<LiveFrame>(&reading)) {
        frames.push_back(std::move(*frame));
      } else if (auto* fix = std::get_if<GpsFix>(&reading)) {
        fixes.push_back(*fix);
      } else if (auto* heading = std::get_if<CompassReading>(&reading)) {
        headings.push_back(*heading);
      }
    }
    // The robot is slow to take frames now and then: only the newest waits.
    std::this_thread::sleep_for(std::chrono::milliseconds(frames.size() == 3 ? 120 : 5));
  }
  feeder.join();
  const LiveSensorCounts counts = sensors.counts();

  ASSERT_EQ(static_cast<int>(imu.size()), kImuSamples);
  for (size_t i = 1; i < imu.size(); ++i) {
    // In order; how far apart depends on the delays (device_clock.h).
    EXPECT_GT(imu[i].stamp_ns, imu[i - 1].stamp_ns);
  }
  EXPECT_EQ(counts.imu_lines_dropped, 1);
  ASSERT_EQ(headings.size(), 2u);
  EXPECT_EQ(headings[1].stamp_ns - headings[0].stamp_ns, 100 * kMs);
  EXPECT_DOUBLE_EQ(headings[1].magnetic_heading_rad, 0.52);
  EXPECT_EQ(counts.compass_lines_dropped, 1);
  ASSERT_EQ(fixes.size(), 1u);
  EXPECT_LT((fixes[0].p_world_antenna - Eigen::Vector3d(3.0, 4.0, 1.0)).norm(), 2e-3);
  EXPECT_NEAR(fixes[0].horizontal_sigma_m, GnssErrorModel{}.dgps_sigma_m, 1e-9);
  EXPECT_EQ(counts.gnss_dropped, 1);  // the undated GGA
  // On the robot's time: every reading at or before its arrival, not long before.
  EXPECT_LE(imu.back().stamp_ns, time_base.now());
  EXPECT_GT(imu.back().stamp_ns, time_base.now() - 1000 * kMs);
  EXPECT_EQ(counts.frames, kFrames);
  EXPECT_EQ(static_cast<int64_t>(frames.size()) + counts.frames_dropped, kFrames);
  EXPECT_GE(counts.frames_dropped, 1);
  for (size_t i = 1; i < frames.size(); ++i) {
    EXPECT_GT(frames[i].sequence, frames[i - 1].sequence);
    EXPECT_GT(frames[i].captured.stamp_ns, frames[i - 1].captured.stamp_ns);
  }
  fs::remove_all(folder);
}

TEST(LiveSensors, ASourceThatCannotBeOpenedIsNamed) {
  const RobotTimeBase time_base;
  LiveSensorConfig config;
  config.camera.source = "/nonexistent/camera.mkv";
  EXPECT_THROW(LiveSensors(config, time_base, "", kSiteOrigin, GnssErrorModel{}),
               std::runtime_error);
  const fs::path folder = fs::temp_directory_path() / fmt::format("live_sources_{}", getpid());
  fs::create_directories(folder);
  config.camera.source = (folder / "camera.mkv").string();
  {
    cv::VideoWriter writer(config.camera.source, cv::CAP_FFMPEG,
                           cv::VideoWriter::fourcc('F', 'F', 'V', '1'), kFps, cv::Size(32, 24));
    writer.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(0)));
  }
  config.imu_source = "/nonexistent/ttyIMU";
  try {
    LiveSensors sensors(config, time_base, "", kSiteOrigin, GnssErrorModel{});
    FAIL() << "a missing IMU opened";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("imu_source '/nonexistent/ttyIMU'"), std::string::npos)
        << error.what();
  }
  config.imu_source.clear();
  config.gnss_source = "gpsd";
  try {
    LiveSensors sensors(config, time_base, "", kSiteOrigin, GnssErrorModel{});
    FAIL() << "GNSS without a site frame";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("site_crs"), std::string::npos) << error.what();
  }
  config.gnss_source = "gpsd:nohost";
  try {
    LiveSensors sensors(config, time_base, "UTM:31N", kSiteOrigin, GnssErrorModel{});
    FAIL() << "a gpsd address without a port";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("gpsd:HOST:PORT"), std::string::npos) << error.what();
  }
  fs::remove_all(folder);
}

}  // namespace
}  // namespace lineloc

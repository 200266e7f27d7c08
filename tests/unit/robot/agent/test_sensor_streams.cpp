#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "robot/agent/sensor_streams.h"

namespace lineloc {
namespace {

namespace fs = std::filesystem;

void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A two-frame dataset as lineloc-sim writes it: quoted NMEA sentences in
// gps0/data.csv, headings in radians, the camera's mounting in cam0/sensor.yaml.
class SensorStreamsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("lineloc_streams_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    writeFile(root_ / "cam0" / "data.csv",
              "#timestamp [ns],filename\n1700000000000000000,a.png\n1700000000050000000,b.png\n");
    writeFile(root_ / "cam0" / "data" / "a.png", "");
    writeFile(root_ / "cam0" / "data" / "b.png", "");
    writeFile(root_ / "cam0" / "sensor.yaml",
              "T_BS:\n  cols: 4\n  rows: 4\n  data: [0, 0, 1, 0, -1, 0, 0, 0, 0, -1, 0, 1.2, 0, "
              "0, 0, 1]\n");
    writeFile(root_ / "imu0" / "data.csv",
              "#timestamp [ns],wx,wy,wz,ax,ay,az\n1700000000000000000,0,0,0,0,0,9.81\n");
    writeFile(root_ / "compass0" / "data.csv",
              "#timestamp [ns],heading [rad]\n1700000000000000000,4.285654603\n");
    writeFile(
        root_ / "gps0" / "data.csv",
        "#timestamp [ns],sentence\n"
        "1700000000000000000,\"$GPGGA,221320.000,5200.7022564,N,00421.9874028,E,2,10,0.9,-2.784,"
        "M,0.000,M,,*4B\"\n"
        "1700000000000000001,\"$GPRMC,221320.000,A,5200.7022564,N,00421.9874028,E,0.000,0.00,"
        "141123,,,D*57\"\n"
        "1700000001000000000,\"$GPGGA,221321.000,5200.7029852,N,00421.9856604,E,2,10,0.9,-4.166,"
        "M,0.000,M,,*4C\"\n"
        "garbage\n");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
};

TEST_F(SensorStreamsTest, ReadsEveryStreamOfASimulatedDataset) {
  NmeaGpsDecoder gps(SiteProjection("EPSG:7415", Eigen::Vector3d(84900.0, 447600.0, 0.0)));
  const SensorStreams streams = loadSensorStreams(root_.string(), &gps);
  EXPECT_EQ(streams.frames.size(), 2u);
  EXPECT_EQ(streams.imu.size(), 1u);
  ASSERT_EQ(streams.compass.size(), 1u);
  EXPECT_DOUBLE_EQ(streams.compass[0].magnetic_heading_rad, 4.285654603);
  // The first GGA is a fix; the RMC dates it and gives a velocity (standing:
  // zero); the second GGA has a bad checksum (4C, not 4D) and the last row is
  // not a row at all: both dropped.
  ASSERT_EQ(streams.gps.size(), 1u);
  EXPECT_EQ(streams.gps[0].stamp_ns, 1700000000000000000);
  EXPECT_LT(streams.gps[0].p_world_antenna.head<2>().norm(), 1000.0);
  ASSERT_EQ(streams.gps_velocity.size(), 1u);
  EXPECT_EQ(streams.gps_velocity[0].stamp_ns, 1700000000000000001);
  EXPECT_EQ(streams.gps_velocity[0].v_world_mps, Eigen::Vector2d::Zero());
  EXPECT_EQ(streams.dropped_lines, 2);
  ASSERT_EQ(streams.drop_reasons.size(), 2u);
  EXPECT_NE(streams.drop_reasons[0].find("gps0/data.csv:4"), std::string::npos)
      << streams.drop_reasons[0];
  ASSERT_TRUE(streams.T_body_camera.has_value());
  EXPECT_DOUBLE_EQ(streams.T_body_camera->translation().z(), 1.2);
  EXPECT_FALSE(streams.T_body_imu.has_value());
  EXPECT_EQ(streams.timeline.size(), 6u);
}

// A robot whose software restarts mid-drive replays from later on: 10 ms in,
// only the second frame is left; everything else came at the start.
TEST_F(SensorStreamsTest, StartsLaterLeavingOutTheRecordsBefore) {
  NmeaGpsDecoder gps(SiteProjection("EPSG:7415", Eigen::Vector3d(84900.0, 447600.0, 0.0)));
  const SensorStreams streams =
      loadSensorStreams(root_.string(), &gps, {.start_offset_ns = 10'000'000});
  ASSERT_EQ(streams.frames.size(), 1u);
  EXPECT_EQ(streams.frames[0].stamp_ns, 1700000000050000000);
  EXPECT_TRUE(streams.imu.empty());
  EXPECT_TRUE(streams.compass.empty());
  EXPECT_TRUE(streams.gps.empty());
  EXPECT_TRUE(streams.gps_velocity.empty());
  ASSERT_EQ(streams.timeline.size(), 1u);
  EXPECT_EQ(streams.timeline[0].kind, SensorKind::kFrame);
  EXPECT_EQ(streams.timeline[0].index, 0u);
}

// A camera whose clock runs 30 ms ahead of the other sensors': its frames
// take their place on the timeline, and their stamps, 30 ms earlier.
TEST_F(SensorStreamsTest, FramesAreStampedOnTheOtherSensorsClock) {
  const SensorStreams streams =
      loadSensorStreams(root_.string(), nullptr, {.camera_time_offset_ns = 30'000'000});
  ASSERT_EQ(streams.frames.size(), 2u);
  EXPECT_EQ(streams.frames[0].stamp_ns, 1699999999970000000);
  EXPECT_EQ(streams.frames[1].stamp_ns, 1700000000020000000);
  ASSERT_FALSE(streams.timeline.empty());
  EXPECT_EQ(streams.timeline.front().kind, SensorKind::kFrame);
  EXPECT_EQ(streams.timeline.front().stamp_ns, 1699999999970000000);
}

// The IMU's noise comes from its sensor.yaml, as lineloc-sim and EuRoC write it.
TEST_F(SensorStreamsTest, ReadsTheImusNoiseFromItsSensorYaml) {
  EXPECT_FALSE(loadSensorStreams(root_.string(), nullptr).imu_noise.has_value());
  writeFile(root_ / "imu0" / "sensor.yaml",
            "sensor_type: imu\nrate_hz: 200\ngyroscope_noise_density: 1.6968e-04\n"
            "gyroscope_random_walk: 1.9393e-05\naccelerometer_noise_density: 2.0000e-03\n"
            "accelerometer_random_walk: 3.0000e-03\n"
            "T_BS:\n  cols: 4\n  rows: 4\n  data: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\n");
  const std::optional<ImuNoiseDensities> noise =
      loadSensorStreams(root_.string(), nullptr).imu_noise;
  ASSERT_TRUE(noise.has_value());
  EXPECT_EQ(noise->gyro_noise_radps_per_sqrt_hz, 1.6968e-04);
  EXPECT_EQ(noise->accel_noise_mps2_per_sqrt_hz, 2.0e-03);
  EXPECT_EQ(noise->gyro_bias_random_walk_radps2_per_sqrt_hz, 1.9393e-05);
  EXPECT_EQ(noise->accel_bias_random_walk_mps3_per_sqrt_hz, 3.0e-03);
}

TEST_F(SensorStreamsTest, StartingLaterNeedsTimeStampedFrames) {
  const fs::path images = root_ / "plain";
  writeFile(images / "a.png", "");
  try {
    loadSensorStreams(images.string(), nullptr, {.start_offset_ns = 1'000'000'000});
    FAIL() << "started an untimed image folder later";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("time-stamped"), std::string::npos) << error.what();
  }
  EXPECT_EQ(loadSensorStreams(images.string(), nullptr).frames.size(), 1u);
}

// A dataset without the IMU or DGPS the robot needs is refused with a
// message naming the file; with a start pose it needs no DGPS; a camera
// folder on its own needs neither.
TEST_F(SensorStreamsTest, RequiresTheIMUAndDGPSOfADataset) {
  NmeaGpsDecoder gps(SiteProjection("EPSG:7415", Eigen::Vector3d(84900.0, 447600.0, 0.0)));
  const auto errorOf = [&](NmeaGpsDecoder* decoder, bool start_pose_given = false) -> std::string {
    try {
      requireNavigationSensors(root_.string(), loadSensorStreams(root_.string(), decoder),
                               decoder != nullptr, start_pose_given);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_EQ(errorOf(&gps), "");
  EXPECT_NE(errorOf(nullptr).find((root_ / "gps0" / "data.csv").string() +
                                  "' needs the site's CRS and origin"),
            std::string::npos)
      << errorOf(nullptr);
  writeFile(root_ / "gps0" / "data.csv", "#timestamp [ns],sentence\ngarbage\n");
  EXPECT_NE(errorOf(&gps).find("holds no valid DGPS position"), std::string::npos);
  fs::remove(root_ / "gps0" / "data.csv");
  EXPECT_NE(errorOf(&gps).find("has no DGPS stream: '" + (root_ / "gps0" / "data.csv").string() +
                               "' is missing"),
            std::string::npos)
      << errorOf(&gps);
  EXPECT_EQ(errorOf(nullptr, true), "");
  writeFile(root_ / "imu0" / "data.csv", "#timestamp [ns],wx,wy,wz,ax,ay,az\n1,2\n");
  EXPECT_NE(errorOf(&gps).find("holds no valid IMU sample"), std::string::npos) << errorOf(&gps);
  fs::remove(root_ / "imu0" / "data.csv");
  EXPECT_NE(errorOf(&gps).find("has no IMU stream: '" + (root_ / "imu0" / "data.csv").string() +
                               "' is missing"),
            std::string::npos)
      << errorOf(&gps);
  EXPECT_NE(errorOf(nullptr, true).find("has no IMU stream"), std::string::npos);
  const std::string camera_folder = (root_ / "cam0").string();
  EXPECT_NO_THROW(requireNavigationSensors(camera_folder, loadSensorStreams(camera_folder, nullptr),
                                           false, false));
}

TEST_F(SensorStreamsTest, MalformedMountingIsAnErrorNamingTheFile) {
  writeFile(root_ / "imu0" / "sensor.yaml", "T_BS: {rows: 4}\n");
  try {
    loadSensorStreams(root_.string(), nullptr);
    FAIL() << "accepted a malformed imu0/sensor.yaml";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("imu0/sensor.yaml"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace lineloc

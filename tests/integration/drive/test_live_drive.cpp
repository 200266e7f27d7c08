// The robot on live sensors (robot/input/live_sensors.h), the README's drive
// on the bundled Delft tile played through the live path as a robot's
// devices deliver it: the camera a video file of the drive's frames
// (lossless), the GNSS receiver's NMEA through a real gpsd (gpsfake), the
// IMU and the compass streaming their CSV rows into FIFOs in real time. The
// robot maps each device's stamps onto its own time base by their arrival;
// mapped back onto the drive's, its poses must meet the bounds the dataset's
// replay meets (city_drive.h).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "common/time/clock.h"
#include "robot/input/euroc_sensor.h"
#include "tests/integration/drive/city_drive.h"
#include "tests/support/delft_drive.h"
#include "tests/support/fake_gpsd.h"

namespace lineloc {
namespace {

using namespace lineloc::test;

struct StampedRow {
  int64_t stamp_ns = 0;
  std::string row;
  int fd = -1;
};

// The rows of an EuRoC CSV file (comments left out), each with its stamp.
std::vector<StampedRow> csvRows(const fs::path& path, int fd) {
  std::vector<StampedRow> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#') {
      rows.push_back({std::stoll(line.substr(0, line.find(','))), line, fd});
    }
  }
  return rows;
}

class LiveDrive : public CityDrive {
 protected:
  LiveDrive()
      : CityDrive({"delft", delftCityModel(), delftSiteOriginArgs(), kDelftCameraHeightM,
                   kDelftDriveStartUtc}) {}

  void SetUp() override {
    CityDrive::SetUp();
    simulateDrive(1, "dataset");
    const fs::path dataset = work_ / "dataset";
    frame_stamps_ns_ = {};
    for (const StampedRow& row : csvRows(dataset / "cam0" / "data.csv", -1)) {
      frame_stamps_ns_.push_back(row.stamp_ns);
    }
    ASSERT_GT(frame_stamps_ns_.size(), 2u);
    const double fps = 1e9 / static_cast<double>(frame_stamps_ns_[1] - frame_stamps_ns_[0]);
    cv::VideoWriter video((work_ / "camera.mkv").string(), cv::CAP_FFMPEG,
                          cv::VideoWriter::fourcc('F', 'F', 'V', '1'), fps, cv::Size(640, 480));
    ASSERT_TRUE(video.isOpened());
    for (const int64_t stamp_ns : frame_stamps_ns_) {
      const cv::Mat image =
          cv::imread((dataset / "cam0" / "data" / (std::to_string(stamp_ns) + ".png")).string(),
                     cv::IMREAD_COLOR);
      ASSERT_FALSE(image.empty()) << stamp_ns;
      video.write(image);
    }
    std::ofstream nmea(work_ / "gnss.nmea");
    for (const StampedRow& row : csvRows(dataset / "gps0" / "data.csv", -1)) {
      std::string sentence = row.row.substr(row.row.find(',') + 1);
      std::erase(sentence, '"');
      nmea << sentence << "\r\n";
    }
  }

  // The drive's frame stamp nearest `stamp_ns` on its clock; nullopt beyond
  // a fifth of a frame.
  std::optional<int64_t> frameAt(int64_t stamp_ns) const {
    const auto next = std::lower_bound(frame_stamps_ns_.begin(), frame_stamps_ns_.end(), stamp_ns);
    std::optional<int64_t> nearest;
    for (auto candidate : {next, next == frame_stamps_ns_.begin() ? next : std::prev(next)}) {
      if (candidate != frame_stamps_ns_.end() &&
          (!nearest || std::abs(*candidate - stamp_ns) < std::abs(*nearest - stamp_ns))) {
        nearest = *candidate;
      }
    }
    const int64_t period_ns = frame_stamps_ns_[1] - frame_stamps_ns_[0];
    if (!nearest || std::abs(*nearest - stamp_ns) > period_ns / 5) {
      return std::nullopt;
    }
    return nearest;
  }

  // Rewrites robot `robot_id`'s logs from its time onto the drive's, less
  // `offset_ns`; the frames' stamps (fixes, predictions) onto the frames'.
  // Returns how many stamps matched no frame.
  int mapLogsOntoTheDrive(const std::string& from_id, const std::string& to_id,
                          int64_t offset_ns) const {
    int unmatched = 0;
    for (const auto& [suffix, frames] :
         std::vector<std::pair<std::string, bool>>{{"-fused.tum", true},
                                                   {"-fixes.tum", true},
                                                   {"-fixes.txt", true},
                                                   {"-states.txt", false}}) {
      std::ifstream in(work_ / (from_id + suffix));
      std::ofstream out(work_ / (to_id + suffix));
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') {
          out << line << '\n';
          continue;
        }
        const size_t space = line.find(' ');
        int64_t stamp_ns =
            static_cast<int64_t>(std::llround(std::stod(line.substr(0, space)) * 1e9)) - offset_ns;
        if (frames) {
          const std::optional<int64_t> frame = frameAt(stamp_ns);
          if (!frame) {
            ++unmatched;
            continue;
          }
          stamp_ns = *frame;
        }
        out << fmt::format("{}.{:09d}", stamp_ns / 1'000'000'000, stamp_ns % 1'000'000'000)
            << line.substr(space) << '\n';
      }
    }
    return unmatched;
  }

  std::vector<int64_t> frame_stamps_ns_;
};

TEST_F(LiveDrive, TheRobotOnLiveSensorsKnowsItsPoseAsItDoesReplayingTheDataset) {
  const fs::path dataset = work_ / "dataset";
  const std::string imu_fifo = (work_ / "imu").string();
  const std::string compass_fifo = (work_ / "compass").string();
  ASSERT_EQ(::mkfifo(imu_fifo.c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo(compass_fifo.c_str(), 0600), 0);
  const FakeGpsd gpsd((work_ / "gnss.nmea").string(), 0.5, (work_ / "gpsfake.log").string());
  const auto backbone = startBackbone("backbone.log");

  // The sensors as a robot's config gives them: the mounting and the IMU's
  // noise, here the dataset's.
  std::vector<std::string> options = {"--camera-source",  (work_ / "camera.mkv").string(),
                                      "--imu-source",     imu_fifo,
                                      "--compass-source", compass_fifo,
                                      "--gnss-source",    "gpsd:localhost:" + gpsd.port()};
  for (const auto& [option, file] :
       {std::pair{"--T-body-camera", "cam0"}, {"--T-body-imu", "imu0"}}) {
    const Eigen::Matrix4d T =
        readEurocSensorPose((dataset / file / "sensor.yaml").string()).matrix();
    options.push_back(option);
    for (int row = 0; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) {
        options.push_back(fmt::format("{}", T(row, col)));
      }
    }
  }
  const std::optional<ImuNoiseDensities> noise =
      readEurocImuNoise((dataset / "imu0" / "sensor.yaml").string());
  ASSERT_TRUE(noise);
  for (const auto& [option, value] :
       {std::pair{"--gyro-noise-density", noise->gyro_noise_radps_per_sqrt_hz},
        {"--accel-noise-density", noise->accel_noise_mps2_per_sqrt_hz},
        {"--gyro-random-walk", noise->gyro_bias_random_walk_radps2_per_sqrt_hz},
        {"--accel-random-walk", noise->accel_bias_random_walk_mps3_per_sqrt_hz}}) {
    options.insert(options.end(), {option, fmt::format("{}", value)});
  }
  const auto robot = std::make_unique<ChildProcess>(
      std::string(LINELOC_BIN_DIR) + "/lineloc-robot", robotArgs("live-raw", "dataset", options),
      (work_ / "live-raw.log").string(), environment_);

  // The IMU and the compass stream as measured, in step with the video,
  // whose first frame the robot reads as it opens their FIFOs.
  const int imu = ::open(imu_fifo.c_str(), O_WRONLY);
  const int compass = ::open(compass_fifo.c_str(), O_WRONLY);
  ASSERT_GE(imu, 0);
  ASSERT_GE(compass, 0);
  const int64_t start_wall_ns = wallClockNs();
  const auto start = std::chrono::steady_clock::now();
  std::vector<StampedRow> rows = csvRows(dataset / "imu0" / "data.csv", imu);
  const std::vector<StampedRow> headings = csvRows(dataset / "compass0" / "data.csv", compass);
  rows.insert(rows.end(), headings.begin(), headings.end());
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.stamp_ns < b.stamp_ns; });
  for (const StampedRow& row : rows) {
    std::this_thread::sleep_until(start +
                                  std::chrono::nanoseconds(row.stamp_ns - frame_stamps_ns_[0]));
    const std::string data = row.row + "\n";
    ASSERT_EQ(::write(row.fd, data.data(), data.size()), static_cast<ssize_t>(data.size()));
  }
  ::close(imu);
  ::close(compass);
  waitForRobot(*robot, "live-raw");
  backbone->signal(SIGTERM);
  backbone->wait(10'000);

  const std::string robot_log = readFile(work_ / "live-raw.log");
  // The robot's clock less the drive's, from the first frame it sent: the
  // robot names its place in the video.
  const int first_sent = countIn(robot_log, R"(sending from frame ([0-9]+))");
  const auto fused = poses("live-raw-fused.tum");
  ASSERT_TRUE(first_sent >= 0 && !fused.empty()) << robot_log << "gpsfake:\n"
                                                 << readFile(work_ / "gpsfake.log");
  const int64_t offset_ns = fused.begin()->first - frame_stamps_ns_.at(first_sent);
  fmt::print("camera stamped {:.1f} ms after the IMU and compass streams' time\n",
             toMilliseconds(offset_ns - (start_wall_ns - frame_stamps_ns_[0])));
  EXPECT_EQ(mapLogsOntoTheDrive("live-raw", "live", offset_ns), 0) << robot_log;
  std::ofstream(work_ / "live.log") << robot_log;
  expectLocalized("live", "dataset");
}

}  // namespace
}  // namespace lineloc

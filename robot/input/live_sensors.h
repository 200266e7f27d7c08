// The robot's live sensors, each read on its own thread and stamped on the
// robot's time base (device_clock.h): a camera (video_camera.h); GNSS from
// gpsd (gpsd_client.h) or NMEA 0183 from a serial port, a FIFO or a file
// (nmea_gps_decoder.h); an IMU and a compass streaming CSV rows as their
// EuRoC files hold them (sensor_csv.h: "timestamp_ns, w_x, w_y, w_z, a_x,
// a_y, a_z"; "timestamp_ns, magnetic heading rad") on a serial port, a FIFO
// or a file. Each device's stamps (the IMU's counter, the receiver's UTC, the
// camera's buffer time) are mapped by a DeviceClock of its own.
//
// The camera starts first, and the line sources are opened once it runs: a
// program feeding a FIFO in step with a video file (a replay through the
// live path) starts when its FIFO is opened.
//
// Readings wait in arrival order until taken; of the camera's frames only
// the newest waits: a frame the robot could not take before the next came is
// dropped and counted, as a camera driver overwrites its buffer. An NMEA GGA
// before the first RMC has no date and is dropped (counted).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "common/geodesy/site_projection.h"
#include "robot/inertial/gnss_error_model.h"
#include "robot/inertial/imu_sample.h"
#include "robot/inertial/navigator_measurements.h"
#include "robot/inertial/nmea_gps_decoder.h"
#include "robot/inertial/sensor_csv.h"
#include "robot/inertial/sensor_line_reader.h"
#include "robot/input/device_clock.h"
#include "robot/input/gpsd_client.h"
#include "robot/input/video_camera.h"

namespace lineloc {

struct LiveSensorConfig {
  VideoCameraOptions camera;
  // "gpsd" (localhost:2947) or "gpsd:HOST:PORT", or a serial device, FIFO or
  // file of NMEA 0183; empty: none.
  std::string gnss_source;
  int gnss_baud = 9600;
  // A serial device, FIFO or file of EuRoC CSV rows; empty: none.
  std::string imu_source;
  int imu_baud = 115200;
  // A serial device, FIFO or file of compass CSV rows; empty: none.
  std::string compass_source;
  int compass_baud = 9600;
};

struct LiveFrame {
  uint32_t sequence = 0;
  CapturedFrame captured;
};

using LiveReading = std::variant<ImuSample, GpsFix, GpsVelocity, CompassReading, LiveFrame>;

// A source of live readings besides those configured above (ROS 2 topics,
// robot/ros2/ros2_sensor_source.h), run by LiveSensors on a thread of its own:
// it hands over what arrives, each reading stamped on its device's clock
// (mapped by a DeviceClock of the source's own), until `stop`.
class LiveSource {
 public:
  virtual ~LiveSource() = default;
  virtual void run(const std::function<void(std::vector<LiveReading>)>& arrived,
                   const std::atomic<bool>& stop) = 0;
  // True when it delivers camera frames, with sequence numbers of its own.
  virtual bool deliversFrames() const = 0;
  // Messages it could not take and dropped.
  virtual int64_t dropped() const = 0;
};

struct LiveSensorCounts {
  int64_t frames = 0;
  int64_t frames_dropped = 0;
  int64_t imu_samples = 0;
  int64_t imu_lines_dropped = 0;
  int64_t compass_readings = 0;
  int64_t compass_lines_dropped = 0;
  int64_t gnss_fixes = 0;
  int64_t gnss_velocities = 0;
  // NMEA sentences that were malformed, failed their checksum or were undated,
  // and gpsd reports without a 3D fix.
  int64_t gnss_dropped = 0;
  // Dropped by the sources besides (LiveSource::dropped).
  int64_t source_dropped = 0;
};

class LiveSensors {
 public:
  // Opens every configured source, and starts reading them and `sources`.
  // The camera is config.camera's unless a source delivers frames. The site
  // frame (its CRS, empty: none, and origin), needed with a GNSS source, is
  // where its fixes are projected. Throws std::runtime_error naming the option
  // and the source that cannot be opened.
  LiveSensors(const LiveSensorConfig& config, const RobotTimeBase& time_base,
              const std::string& site_crs, const Eigen::Vector3d& site_origin,
              const GnssErrorModel& gnss_errors,
              std::vector<std::unique_ptr<LiveSource>> sources = {});
  ~LiveSensors();
  LiveSensors(const LiveSensors&) = delete;
  LiveSensors& operator=(const LiveSensors&) = delete;

  // The readings that arrived, waiting up to `timeout_ns` for one.
  std::vector<LiveReading> take(int64_t timeout_ns);

  // True once the camera delivers no more (a file played out, a device gone;
  // never for a source's).
  bool cameraEnded() const { return camera_ended_; }
  LiveSensorCounts counts() const;

 private:
  void stopThreads();
  void push(LiveReading reading);
  // Pushes readings that arrived together, stamped by the device's clock.
  void pushMapped(std::vector<LiveReading> readings, DeviceClock& clock, int64_t arrival_ns);
  void readCamera(std::unique_ptr<VideoCamera> camera);
  // Rows parsed by `parse` (sensor_csv.h), malformed ones counted in `dropped`.
  template <typename Record>
  void readCsv(std::unique_ptr<SensorLineReader> stream, CsvLine<Record> (*parse)(std::string_view),
               int64_t LiveSensorCounts::*dropped);
  void readNmea(std::unique_ptr<SensorLineReader> stream, std::unique_ptr<NmeaGpsDecoder> decoder);
  void readGpsd(std::unique_ptr<GpsdClient> gpsd);
  void readSource(LiveSource& source);

  const RobotTimeBase& time_base_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> camera_ended_{false};
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<LiveReading> readings_;
  std::optional<size_t> waiting_frame_;
  LiveSensorCounts counts_;
  std::vector<std::unique_ptr<LiveSource>> sources_;
  std::vector<std::thread> threads_;
};

}  // namespace lineloc

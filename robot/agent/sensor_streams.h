// The robot's timed inputs from a recorded or simulated EuRoC/ASL dataset —
// camera frames (cam0/), IMU (imu0/data.csv), DGPS as NMEA 0183
// (gps0/data.csv: "timestamp_ns,sentence"; positions and velocities) and
// compass (compass0/data.csv) — merged into one time-ordered timeline, so the
// robot can replay them as they were measured, the mounting of camera and
// IMU on the body (T_BS of cam0/sensor.yaml and imu0/sensor.yaml) and the
// IMU's noise (imu0/sensor.yaml, euroc_sensor.h). Streams other than the
// camera are optional.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "robot/inertial/inertial_navigator.h"
#include "robot/inertial/nmea_gps_decoder.h"
#include "robot/input/image_sequence.h"

namespace lineloc {

enum class SensorKind { kImu, kGps, kGpsVelocity, kCompass, kFrame };

struct SensorEvent {
  int64_t stamp_ns = 0;
  SensorKind kind = SensorKind::kFrame;
  size_t index = 0;  // into the stream of its kind
};

struct SensorStreams {
  std::vector<FrameRef> frames;
  std::vector<ImuSample> imu;
  std::vector<GpsFix> gps;
  std::vector<GpsVelocity> gps_velocity;
  std::vector<CompassReading> compass;
  std::vector<SensorEvent> timeline;
  // The sensors' poses in the body frame, when the dataset gives them.
  std::optional<Eigen::Isometry3d> T_body_camera;
  std::optional<Eigen::Isometry3d> T_body_imu;
  // The IMU's noise, when its sensor.yaml gives it.
  std::optional<ImuNoiseDensities> imu_noise;
  // Lines of the CSV and NMEA inputs dropped as malformed, with the first few
  // reasons.
  int dropped_lines = 0;
  std::vector<std::string> drop_reasons;
};

struct StreamTiming {
  // Leaves out the records of this long from the earliest one of any stream
  // (a robot whose software restarts mid-drive).
  int64_t start_offset_ns = 0;
  // The camera clock minus the other sensors': each frame's stamp less this
  // is its place on their timeline, and the stamp the robot uses.
  int64_t camera_time_offset_ns = 0;
};

// Reads the streams of the dataset at `root` (or a plain image folder: frames
// only). `gps` decodes the NMEA sentences into the site frame; without it
// DGPS is not read. Throws std::runtime_error naming the file when the camera
// stream or a sensor.yaml is unreadable; frames without a time stamp are
// refused when other streams are present (they cannot be placed on the
// timeline), and when the replay starts later.
SensorStreams loadSensorStreams(const std::string& root, NmeaGpsDecoder* gps,
                                const StreamTiming& timing = {});

// Throws std::runtime_error, naming the file and what is missing, unless
// `streams`, read from `root`, hold what the robot needs to localise: in a
// dataset (a folder with cam0/), IMU samples (imu0/data.csv), which carry the
// pose between fixes, and DGPS positions (gps0/data.csv, read with a site
// CRS: `gps_decoded`), which give the navigator its first position, without
// which it never sends a frame, unless `start_pose_given`. A camera folder or
// a plain folder of images needs neither: its frames carry a configured
// prediction.
void requireNavigationSensors(const std::string& root, const SensorStreams& streams,
                              bool gps_decoded, bool start_pose_given);

}  // namespace lineloc

// Writes a simulated drive as an EuRoC/ASL dataset folder (Burri et al., "The
// EuRoC micro aerial vehicle datasets", IJRR 2016), the layout users' tools
// already read:
//   cam0/data/<stamp_ns>.png, cam0/data.csv, cam0/sensor.yaml (+ the OpenCV
//     calibration file cam0/calibration.yaml lineloc reads),
//   imu0/data.csv, imu0/sensor.yaml,
//   gps0/data.csv (one NMEA 0183 sentence per row) and gps0/nmea.txt (raw),
//   compass0/data.csv,
//   state_groundtruth_estimate0/data.csv (body pose, velocity, IMU biases),
//   groundtruth_cam0.tum (T_world_camera at every image, TUM format).
// Every number is printed with a fixed format, so equal inputs give equal bytes.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <fstream>
#include <opencv2/core.hpp>
#include <string>

#include "common/camera/camera_calibration.h"
#include "common/trajectory/tum_trajectory.h"

namespace lineloc {

struct EurocImuSpec {
  double rate_hz = 200.0;
  // Continuous-time noise densities and bias random walks (Kalibr/EuRoC units).
  double gyroscope_noise_density = 0.0;      // rad / s / sqrt(Hz)
  double gyroscope_random_walk = 0.0;        // rad / s^2 / sqrt(Hz)
  double accelerometer_noise_density = 0.0;  // m / s^2 / sqrt(Hz)
  double accelerometer_random_walk = 0.0;    // m / s^3 / sqrt(Hz)
};

struct EurocDatasetSpec {
  CameraCalibration camera;
  // Camera and IMU frames in the body frame (EuRoC's T_BS).
  Eigen::Isometry3d T_body_camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_body_imu = Eigen::Isometry3d::Identity();
  double camera_rate_hz = 20.0;
  EurocImuSpec imu;
};

struct EurocGroundTruth {
  int64_t stamp_ns = 0;
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();       // rad/s
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();      // m/s^2
};

class EurocWriter {
 public:
  // Creates the folder tree under `root` (which must be empty or absent) and
  // the sensor.yaml files. Throws std::runtime_error naming the path on failure.
  EurocWriter(const std::string& root, const EurocDatasetSpec& spec);

  // Each writer throws std::invalid_argument when stamps do not increase.
  void writeImage(int64_t stamp_ns, const cv::Mat& image);
  // The true camera pose when an image was taken (true time, which differs
  // from the image's stamp when the camera clock has an offset).
  void writeCameraGroundTruth(const StampedPose& T_world_camera);
  void writeImu(int64_t stamp_ns, const Eigen::Vector3d& angular_velocity_rad_s,
                const Eigen::Vector3d& acceleration_m_s2);
  void writeNmea(int64_t stamp_ns, const std::string& sentence);
  // Heading clockwise from north (rad), as a compass reports it.
  void writeCompass(int64_t stamp_ns, double heading_rad);
  void writeGroundTruth(const EurocGroundTruth& state);

 private:
  // A csv file whose stamps must increase.
  struct Stream {
    std::ofstream file;
    int64_t last_stamp_ns = INT64_MIN;
    std::string name;
  };
  void open(Stream& stream, const std::string& relative_path, const std::string& header);
  void checkStamp(Stream& stream, int64_t stamp_ns);

  std::string root_;
  Stream images_;
  Stream imu_;
  Stream gps_;
  Stream compass_;
  Stream ground_truth_;
  Stream camera_truth_stamps_;
  std::ofstream nmea_;
  TumWriter camera_ground_truth_;
};

}  // namespace lineloc

// The robot's sensors as mounted and specified: the IMU's noise and range,
// the camera's and the IMU's poses on the body, the GNSS antenna's place on
// it, and the camera clock's offset from the other sensors'. Each comes from
// the robot's config when given there, else from a Kalibr camchain given as
// the camera's calibration (kalibr_camera.h: T_body_camera = T_body_imu
// T_cam_imu^-1), else from the dataset's sensor.yaml files (EuRoC/Kalibr
// keys, euroc_sensor.h), else the navigator's defaults (an ADIS16448 IMU, a
// camera looking forward, inertial_navigator_config.h). The camera clock's
// offset is the config's plus the camchain's, -timeshift_cam_imu.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "common/camera/kalibr_camera.h"
#include "robot/agent/sensor_streams.h"
#include "robot/inertial/gnss_error_model.h"
#include "robot/inertial/inertial_navigator_config.h"

namespace lineloc {

struct SensorSetup {
  // The IMU's white noise and bias random walk, continuous-time densities
  // in Kalibr's units; 0: not configured (all four are, or none).
  double gyro_noise_density = 0.0;   // rad/s/sqrt(Hz)
  double accel_noise_density = 0.0;  // m/s^2/sqrt(Hz)
  double gyro_random_walk = 0.0;     // rad/s^2/sqrt(Hz)
  double accel_random_walk = 0.0;    // m/s^3/sqrt(Hz)
  // The IMU's measurement range; 0: the navigator's default.
  double gyro_range_radps = 0.0;
  double accel_range_mps2 = 0.0;
  // The camera's and the IMU's poses in the body frame, 4x4 row-major as
  // EuRoC's T_BS; empty: not configured. Of the IMU's, the navigator takes
  // the rotation (it neglects the lever arm's centripetal terms).
  std::vector<double> T_body_camera;
  std::vector<double> T_body_imu;
  // The GNSS antenna's phase centre in the body frame (m).
  std::vector<double> p_body_gps_antenna = {0.0, 0.0, 0.0};
  // The receiver's ranging error by fix quality, which with each fix's HDOP
  // gives its sigma (gnss_error_model.h).
  GnssErrorModel gnss_errors;
  // The camera clock minus the clock of the IMU, GNSS and compass (s): a
  // frame stamped t was exposed at t - offset on theirs; added to a
  // camchain's (the negative of Kalibr's timeshift_cam_imu).
  double camera_time_offset_s = 0.0;
};

// `navigator` with the sensors of `setup`, and where it leaves one
// unconfigured those of `streams` (read from the dataset). Throws
// std::invalid_argument naming the option when the IMU's noise is configured
// in part or not positive, a range is negative, or a pose is not a rigid
// transform.
void applySensorSetup(const SensorSetup& setup, const SensorStreams& streams,
                      const std::optional<KalibrCamera>& camchain,
                      InertialNavigatorConfig& navigator);

// The camera clock's offset in nanoseconds, for loadSensorStreams:
// camera_time_offset_s - the camchain's timeshift_cam_imu.
int64_t cameraTimeOffsetNs(const SensorSetup& setup, const std::optional<KalibrCamera>& camchain);

}  // namespace lineloc

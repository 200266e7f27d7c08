#include "sim/sensors/sensor_synthesis.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <stdexcept>

#include "common/nmea/nmea_sentence.h"

namespace lineloc::sim {
namespace {

constexpr int64_t kNsPerDay = 86'400'000'000'000;
constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;
constexpr uint64_t kVelocityStreamKey = 0x5ee9'd0bb'1e2c'0a57;
constexpr int kDgpsFixQuality = 2;
constexpr int kSimulatedSatellites = 10;
constexpr double kSimulatedHdop = 0.9;
constexpr double kRadToDeg = 180.0 / M_PI;

int64_t periodNs(double rate_hz) {
  if (!(rate_hz > 0.0)) {
    throw std::invalid_argument(fmt::format("sensor rate must be > 0 Hz, got {}", rate_hz));
  }
  return static_cast<int64_t>(std::llround(1e9 / rate_hz));
}

Eigen::Vector3d gaussian3(std::mt19937_64& random, double sigma) {
  std::normal_distribution<double> normal(0.0, sigma);
  return Eigen::Vector3d(normal(random), normal(random), normal(random));
}

std::ofstream openForWriting(const std::string& path) {
  std::ofstream stream(path);
  if (!stream) {
    throw std::runtime_error(fmt::format("cannot open '{}' for writing", path));
  }
  return stream;
}

}  // namespace

std::vector<SimImuSample> synthesiseImu(const TruthTrajectory& trajectory, const ImuModel& model,
                                        uint64_t seed) {
  const int64_t period_ns = periodNs(model.rate_hz);
  const double dt = static_cast<double>(period_ns) * 1e-9;
  std::mt19937_64 random(seed);
  const double noise_scale = model.noise ? 1.0 : 0.0;
  Eigen::Vector3d gyro_bias = noise_scale * gaussian3(random, model.gyro_turn_on_bias_sigma_radps);
  Eigen::Vector3d accel_bias = noise_scale * gaussian3(random, model.accel_turn_on_bias_sigma_mps2);
  const double gyro_sigma = noise_scale * model.gyro_noise_radps_per_sqrt_hz / std::sqrt(dt);
  const double accel_sigma = noise_scale * model.accel_noise_mps2_per_sqrt_hz / std::sqrt(dt);
  const double gyro_walk =
      noise_scale * model.gyro_bias_random_walk_radps2_per_sqrt_hz * std::sqrt(dt);
  const double accel_walk =
      noise_scale * model.accel_bias_random_walk_mps3_per_sqrt_hz * std::sqrt(dt);

  std::vector<SimImuSample> samples;
  for (int64_t stamp = trajectory.startStamp_ns(); stamp <= trajectory.endStamp_ns();
       stamp += period_ns) {
    const TruthSample truth = trajectory.at(stamp);
    SimImuSample sample;
    sample.stamp_ns = stamp;
    sample.true_gyro_bias_radps = gyro_bias;
    sample.true_accel_bias_mps2 = accel_bias;
    sample.gyro_radps = truth.gyro_body_radps + gyro_bias + gaussian3(random, gyro_sigma);
    sample.accel_mps2 =
        truth.specific_force_body_mps2 + accel_bias + gaussian3(random, accel_sigma);
    samples.push_back(sample);
    gyro_bias += gaussian3(random, gyro_walk);
    accel_bias += gaussian3(random, accel_walk);
  }
  return samples;
}

std::vector<SimGpsFix> synthesiseGps(const TruthTrajectory& trajectory, const GpsModel& model,
                                     uint64_t seed) {
  const int64_t period_ns = periodNs(model.rate_hz);
  const double dt = static_cast<double>(period_ns) * 1e-9;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // First-order Gauss-Markov: e_k+1 = a e_k + sigma sqrt(1 - a^2) n keeps variance sigma^2.
  const double a = std::exp(-dt / model.correlation_time_s);
  const Eigen::Vector3d sigma(model.correlated_horizontal_sigma_m,
                              model.correlated_horizontal_sigma_m,
                              model.correlated_vertical_sigma_m);
  if (!(model.initial_horizontal_error_m >= 0.0) ||
      !std::isfinite(model.initial_horizontal_error_m)) {
    throw std::invalid_argument(
        fmt::format("GPS initial horizontal error must be >= 0 m and finite, got {}",
                    model.initial_horizontal_error_m));
  }
  const Eigen::Vector3d first_draw = gaussian3(random, 1.0);
  Eigen::Vector3d error = sigma.cwiseProduct(first_draw);
  if (model.initial_horizontal_error_m > 0.0) {
    error.head<2>() = model.initial_horizontal_error_m * first_draw.head<2>().normalized();
  }
  // The velocity's noise has a stream of its own: the positions of a seed stay
  // as they were before the velocity was simulated.
  std::mt19937_64 velocity_random(seed ^ kVelocityStreamKey);
  int64_t outage_end_ns = 0;
  std::vector<SimGpsFix> fixes;
  for (int64_t stamp = trajectory.startStamp_ns(); stamp <= trajectory.endStamp_ns();
       stamp += period_ns) {
    const TruthSample truth = trajectory.at(stamp);
    SimGpsFix fix;
    fix.stamp_ns = stamp;
    fix.true_p_world_antenna = truth.p_world_body + truth.q_world_body * model.p_body_antenna;
    // v_antenna = v_body + R (omega x r).
    fix.true_v_world_antenna_mps =
        (truth.v_world_body +
         truth.q_world_body * truth.gyro_body_radps.cross(model.p_body_antenna))
            .head<2>();
    fix.v_world_antenna_mps = fix.true_v_world_antenna_mps +
                              gaussian3(velocity_random, model.velocity_sigma_mps).head<2>();
    if (stamp >= outage_end_ns && uniform(random) < model.outage_probability) {
      const double outage_s =
          model.min_outage_s + uniform(random) * (model.max_outage_s - model.min_outage_s);
      outage_end_ns = stamp + static_cast<int64_t>(outage_s * 1e9);
    }
    fix.valid = stamp >= outage_end_ns;
    fix.p_world_antenna = fix.true_p_world_antenna + error + gaussian3(random, model.white_sigma_m);
    fixes.push_back(fix);
    error = a * error + std::sqrt(1.0 - a * a) * sigma.cwiseProduct(gaussian3(random, 1.0));
  }
  return fixes;
}

std::vector<std::string> formatNmeaEpoch(const SimGpsFix& fix, const SiteProjection& projection) {
  const GeodeticPosition position = projection.toGeodetic(fix.p_world_antenna);
  GgaSentence gga;
  gga.time_of_day_ns = fix.stamp_ns % kNsPerDay;
  gga.fix_quality = fix.valid ? kDgpsFixQuality : 0;
  gga.satellites = fix.valid ? kSimulatedSatellites : 0;
  gga.hdop = kSimulatedHdop;
  gga.latitude_deg = position.latitude_deg;
  gga.longitude_deg = position.longitude_deg;
  gga.altitude_msl_m = position.height_msl_m;

  const std::chrono::year_month_day date{
      std::chrono::sys_days(std::chrono::days(fix.stamp_ns / kNsPerDay))};
  RmcSentence rmc;
  rmc.time_of_day_ns = gga.time_of_day_ns;
  rmc.valid = fix.valid;
  rmc.latitude_deg = position.latitude_deg;
  rmc.longitude_deg = position.longitude_deg;
  if (fix.valid) {
    // Course = grid bearing of the velocity - grid bearing of true north.
    const Eigen::Vector2d& velocity = fix.v_world_antenna_mps;
    const double course_rad =
        std::atan2(velocity.x(), velocity.y()) - projection.gridBearingOfTrueNorth_rad(position);
    rmc.speed_knots = velocity.norm() / kMetresPerSecondPerKnot;
    rmc.course_deg = std::fmod(course_rad * 180.0 / M_PI + 720.0, 360.0);
  }
  rmc.year = static_cast<int>(date.year());
  rmc.month = static_cast<int>(static_cast<unsigned>(date.month()));
  rmc.day = static_cast<int>(static_cast<unsigned>(date.day()));
  return {formatGga(gga), formatRmc(rmc)};
}

std::vector<SimCompassReading> synthesiseCompass(const TruthTrajectory& trajectory,
                                                 const CompassModel& model,
                                                 double grid_bearing_of_true_north_rad,
                                                 uint64_t seed) {
  const int64_t period_ns = periodNs(model.rate_hz);
  const double dt = static_cast<double>(period_ns) * 1e-9;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, model.sigma_rad);
  int64_t disturbance_end_ns = 0;
  double disturbance_rad = 0.0;
  std::vector<SimCompassReading> readings;
  for (int64_t stamp = trajectory.startStamp_ns(); stamp <= trajectory.endStamp_ns();
       stamp += period_ns) {
    if (stamp >= disturbance_end_ns && uniform(random) < model.disturbance_rate_hz * dt) {
      const double span_s = model.min_disturbance_s +
                            uniform(random) * (model.max_disturbance_s - model.min_disturbance_s);
      disturbance_end_ns = stamp + static_cast<int64_t>(span_s * 1e9);
      disturbance_rad = (uniform(random) < 0.5 ? -1.0 : 1.0) *
                        (model.min_disturbance_rad +
                         uniform(random) * (model.max_disturbance_rad - model.min_disturbance_rad));
    }
    const TruthSample truth = trajectory.at(stamp);
    const Eigen::Vector3d forward = truth.q_world_body * Eigen::Vector3d::UnitX();
    const double yaw = std::atan2(forward.y(), forward.x());
    SimCompassReading reading;
    reading.stamp_ns = stamp;
    reading.disturbed = stamp < disturbance_end_ns;
    const double heading = M_PI_2 - yaw - grid_bearing_of_true_north_rad -
                           model.magnetic_declination_rad + model.bias_rad + noise(random) +
                           (reading.disturbed ? disturbance_rad : 0.0);
    reading.magnetic_heading_rad = heading - 2.0 * M_PI * std::floor(heading / (2.0 * M_PI));
    readings.push_back(reading);
  }
  return readings;
}

void writeEurocImuCsv(const std::string& path, const std::vector<SimImuSample>& samples) {
  std::ofstream stream = openForWriting(path);
  stream << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  for (const SimImuSample& s : samples) {
    stream << fmt::format("{},{},{},{},{},{},{}\n", s.stamp_ns, s.gyro_radps.x(), s.gyro_radps.y(),
                          s.gyro_radps.z(), s.accel_mps2.x(), s.accel_mps2.y(), s.accel_mps2.z());
  }
}

void writeCompassCsv(const std::string& path, const std::vector<SimCompassReading>& readings) {
  std::ofstream stream = openForWriting(path);
  stream << "#timestamp [ns],magnetic_heading [deg]\n";
  for (const SimCompassReading& r : readings) {
    stream << fmt::format("{},{}\n", r.stamp_ns, r.magnetic_heading_rad * kRadToDeg);
  }
}

void writeNmeaFile(const std::string& path, const std::vector<SimGpsFix>& fixes,
                   const SiteProjection& projection) {
  std::ofstream stream = openForWriting(path);
  for (const SimGpsFix& fix : fixes) {
    for (const std::string& sentence : formatNmeaEpoch(fix, projection)) {
      stream << sentence << "\r\n";
    }
  }
}

}  // namespace lineloc::sim

#include "sim/sensors/ground_truth_trajectory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

namespace lineloc::sim {
namespace {

constexpr double kKnotSpacing_s = 0.01;
// Peak of s'(u) is 15/8: a ramp of size D over T has peak rate 1.875 D / T.
constexpr double kSmoothstepPeakSlope = 1.875;
constexpr double kMinTurnRate_radps = 0.15;
constexpr double kMaxTurnSpeed_mps = 1.2;
// Spatial wavelengths of the pavement: roll, pitch and height undulations.
constexpr double kMinTiltWavelength_m = 8.0;
constexpr double kMaxTiltWavelength_m = 20.0;
constexpr double kMinHeightWavelength_m = 40.0;
constexpr double kMaxHeightWavelength_m = 80.0;

// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 5> kGaussNodes = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                               0.5384693101056831, 0.9061798459386640};
constexpr std::array<double, 5> kGaussWeights = {0.2369268850561891, 0.4786286704993665,
                                                 0.5688888888888889, 0.4786286704993665,
                                                 0.2369268850561891};

double smoothstep(double u) {
  return u <= 0.0 ? 0.0 : u >= 1.0 ? 1.0 : u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}
double smoothstepSlope(double u) {
  return u <= 0.0 || u >= 1.0 ? 0.0 : 30.0 * u * u * (1.0 - u) * (1.0 - u);
}
double smoothstepCurvature(double u) {
  return u <= 0.0 || u >= 1.0 ? 0.0 : 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u);
}
// Integral of s from 0 to u.
double smoothstepIntegral(double u) {
  if (u <= 0.0) {
    return 0.0;
  }
  if (u >= 1.0) {
    return 0.5 + (u - 1.0);
  }
  return u * u * u * u * (2.5 + u * (-3.0 + u));
}

}  // namespace

double GroundTruthTrajectory::Profile::value(double t) const {
  double sum = initial;
  for (const Ramp& r : ramps) {
    sum += r.change * smoothstep((t - r.start_s) / r.duration_s);
  }
  return sum;
}

double GroundTruthTrajectory::Profile::rate(double t) const {
  double sum = 0.0;
  for (const Ramp& r : ramps) {
    sum += r.change * smoothstepSlope((t - r.start_s) / r.duration_s) / r.duration_s;
  }
  return sum;
}

double GroundTruthTrajectory::Profile::second(double t) const {
  double sum = 0.0;
  for (const Ramp& r : ramps) {
    sum += r.change * smoothstepCurvature((t - r.start_s) / r.duration_s) /
           (r.duration_s * r.duration_s);
  }
  return sum;
}

double GroundTruthTrajectory::Profile::integral(double t) const {
  double sum = initial * t;
  for (const Ramp& r : ramps) {
    sum += r.change * r.duration_s * smoothstepIntegral((t - r.start_s) / r.duration_s);
  }
  return sum;
}

GroundTruthTrajectory::GroundTruthTrajectory(const TrajectoryConfig& config) : config_(config) {
  if (!(config.duration_s > config.initial_still_s) || !(config.min_speed_mps > 0.0) ||
      !(config.max_speed_mps >= config.min_speed_mps) || !(config.max_accel_mps2 > 0.0) ||
      !(config.min_leg_s > 0.0) || !(config.max_leg_s >= config.min_leg_s)) {
    throw std::invalid_argument(
        "trajectory: need duration > initial_still, 0 < min_speed <= max_speed, max_accel > 0, "
        "0 < min_leg <= max_leg");
  }
  planLegs();
  const int knot_count = static_cast<int>(std::ceil(config.duration_s / kKnotSpacing_s)) + 1;
  knots_.reserve(knot_count);
  knots_.push_back(Eigen::Vector2d::Zero());
  for (int k = 1; k < knot_count; ++k) {
    const double a = (k - 1) * kKnotSpacing_s;
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < kGaussNodes.size(); ++i) {
      step += kGaussWeights[i] * planarVelocity(a + 0.5 * kKnotSpacing_s * (1.0 + kGaussNodes[i]));
    }
    knots_.push_back(knots_.back() + 0.5 * kKnotSpacing_s * step);
  }
}

void GroundTruthTrajectory::planLegs() {
  std::mt19937_64 random(config_.seed);
  const auto uniform = [&random](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random);
  };
  const double two_pi = 2.0 * M_PI;
  const auto wave = [&](double amplitude, double min_wavelength, double max_wavelength) {
    return Wave{amplitude * uniform(0.5, 1.0), two_pi / uniform(min_wavelength, max_wavelength),
                uniform(0.0, two_pi)};
  };
  roll_ = wave(config_.tilt_amplitude_rad, kMinTiltWavelength_m, kMaxTiltWavelength_m);
  pitch_ = wave(config_.tilt_amplitude_rad, kMinTiltWavelength_m, kMaxTiltWavelength_m);
  height_ = wave(config_.height_amplitude_m, kMinHeightWavelength_m, kMaxHeightWavelength_m);

  yaw_rate_.initial = 0.0;
  double speed = 0.0;
  double yaw_rate = 0.0;
  for (double t = config_.initial_still_s; t < config_.duration_s;) {
    const double choice = uniform(0.0, 1.0);
    double next_speed = uniform(config_.min_speed_mps, config_.max_speed_mps);
    double next_yaw_rate = 0.0;
    if (speed > 0.0 && choice < config_.stop_probability) {
      next_speed = 0.0;
    } else if (speed > 0.0 && choice < config_.stop_probability + config_.turn_probability) {
      next_speed =
          uniform(config_.min_speed_mps, std::min(config_.max_speed_mps, kMaxTurnSpeed_mps));
      const double max_rate =
          std::min(config_.max_yaw_rate_radps, config_.max_lateral_accel_mps2 / next_speed);
      next_yaw_rate = (uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0) *
                      uniform(std::min(kMinTurnRate_radps, max_rate), max_rate);
    }
    const double ramp_s =
        std::max(config_.ramp_s,
                 kSmoothstepPeakSlope * std::abs(next_speed - speed) / config_.max_accel_mps2);
    speed_.ramps.push_back({t, ramp_s, next_speed - speed});
    yaw_rate_.ramps.push_back({t, ramp_s, next_yaw_rate - yaw_rate});
    speed = next_speed;
    yaw_rate = next_yaw_rate;
    t += std::max(ramp_s, uniform(config_.min_leg_s, config_.max_leg_s));
  }
}

Eigen::Vector2d GroundTruthTrajectory::planarVelocity(double t) const {
  const double yaw = config_.start_yaw_rad + yaw_rate_.integral(t);
  return speed_.value(t) * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
}

Eigen::Vector2d GroundTruthTrajectory::planarPosition(double t) const {
  const int k =
      std::clamp(static_cast<int>(t / kKnotSpacing_s), 0, static_cast<int>(knots_.size()) - 1);
  const double a = k * kKnotSpacing_s;
  Eigen::Vector2d step = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < kGaussNodes.size(); ++i) {
    step += kGaussWeights[i] * planarVelocity(a + 0.5 * (t - a) * (1.0 + kGaussNodes[i]));
  }
  return knots_[k] + 0.5 * (t - a) * step;
}

int64_t GroundTruthTrajectory::endStamp_ns() const {
  return config_.start_stamp_ns + static_cast<int64_t>(std::llround(config_.duration_s * 1e9));
}

TruthSample GroundTruthTrajectory::at(int64_t stamp_ns) const {
  stamp_ns = std::clamp(stamp_ns, config_.start_stamp_ns, endStamp_ns());
  const double t = static_cast<double>(stamp_ns - config_.start_stamp_ns) * 1e-9;
  const double v = speed_.value(t);
  const double dv = speed_.rate(t);
  const double distance = speed_.integral(t);
  const double yaw = config_.start_yaw_rad + yaw_rate_.integral(t);
  const double yaw_rate = yaw_rate_.value(t);

  // A wave A sin(k d + phase) along the travelled distance d: its time derivatives.
  struct WaveState {
    double value, rate, second;
  };
  const auto evaluate = [&](const Wave& w) {
    const double angle = w.angular_frequency * distance + w.phase;
    const double k = w.angular_frequency;
    return WaveState{w.amplitude * std::sin(angle), w.amplitude * k * std::cos(angle) * v,
                     w.amplitude * k * (std::cos(angle) * dv - k * std::sin(angle) * v * v)};
  };
  const WaveState roll = evaluate(roll_);
  const WaveState pitch = evaluate(pitch_);
  const WaveState height = evaluate(height_);

  TruthSample sample;
  sample.stamp_ns = stamp_ns;
  const Eigen::Vector2d xy = planarPosition(t);
  sample.p_world_body =
      config_.start_position_m +
      Eigen::Vector3d(xy.x(), xy.y(), height.value - height_.amplitude * std::sin(height_.phase));
  const double c = std::cos(yaw);
  const double s = std::sin(yaw);
  sample.v_world_body = Eigen::Vector3d(v * c, v * s, height.rate);
  sample.a_world_body =
      Eigen::Vector3d(dv * c - v * yaw_rate * s, dv * s + v * yaw_rate * c, height.second);
  sample.q_world_body = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                        Eigen::AngleAxisd(pitch.value, Eigen::Vector3d::UnitY()) *
                        Eigen::AngleAxisd(roll.value, Eigen::Vector3d::UnitX());
  const double sr = std::sin(roll.value);
  const double cr = std::cos(roll.value);
  const double sp = std::sin(pitch.value);
  const double cp = std::cos(pitch.value);
  sample.gyro_body_radps =
      Eigen::Vector3d(roll.rate - yaw_rate * sp, pitch.rate * cr + yaw_rate * sr * cp,
                      -pitch.rate * sr + yaw_rate * cr * cp);
  sample.specific_force_body_mps2 =
      sample.q_world_body.conjugate() *
      (sample.a_world_body + Eigen::Vector3d(0.0, 0.0, config_.gravity_mps2));
  return sample;
}

}  // namespace lineloc::sim

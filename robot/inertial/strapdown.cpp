#include "robot/inertial/strapdown.h"

#include "common/geometry/pose.h"

namespace lineloc {
namespace {

constexpr double kNsToS = 1e-9;

}  // namespace

ImuSample interpolateImu(const ImuSample& a, const ImuSample& b, int64_t stamp_ns) {
  const double span = static_cast<double>(b.stamp_ns - a.stamp_ns);
  const double s = span > 0.0 ? static_cast<double>(stamp_ns - a.stamp_ns) / span : 0.0;
  ImuSample sample;
  sample.stamp_ns = stamp_ns;
  sample.gyro_radps = a.gyro_radps + s * (b.gyro_radps - a.gyro_radps);
  sample.accel_mps2 = a.accel_mps2 + s * (b.accel_mps2 - a.accel_mps2);
  return sample;
}

ErrorCovariance ErrorTransition::toMatrix() const {
  ErrorCovariance phi = ErrorCovariance::Identity();
  phi.block<3, 3>(kPosition, kVelocity) = Eigen::Matrix3d::Identity() * dt_s;
  phi.block<3, 3>(kPosition, kAttitude) = p_theta;
  phi.block<3, 3>(kPosition, kAccelBias) = p_ba;
  phi.block<3, 3>(kVelocity, kAttitude) = v_theta;
  phi.block<3, 3>(kVelocity, kGyroBias) = v_bg;
  phi.block<3, 3>(kVelocity, kAccelBias) = v_ba;
  phi.block<3, 3>(kAttitude, kGyroBias) = theta_bg;
  return phi;
}

ErrorCovariance ErrorTransition::applyLeft(const ErrorCovariance& m) const {
  ErrorCovariance out = m;
  // Rows in the order p, v, theta: each reads only rows not yet overwritten.
  out.middleRows<3>(kPosition) += dt_s * m.middleRows<3>(kVelocity) +
                                  p_theta * m.middleRows<3>(kAttitude) +
                                  p_ba * m.middleRows<3>(kAccelBias);
  out.middleRows<3>(kVelocity) += v_theta * m.middleRows<3>(kAttitude) +
                                  v_bg * m.middleRows<3>(kGyroBias) +
                                  v_ba * m.middleRows<3>(kAccelBias);
  out.middleRows<3>(kAttitude) += theta_bg * m.middleRows<3>(kGyroBias);
  return out;
}

ProcessNoise::ProcessNoise(const ImuNoiseDensities& d)
    : accel_psd_(d.accel_noise_mps2_per_sqrt_hz * d.accel_noise_mps2_per_sqrt_hz),
      gyro_psd_(d.gyro_noise_radps_per_sqrt_hz * d.gyro_noise_radps_per_sqrt_hz),
      gyro_bias_psd_(d.gyro_bias_random_walk_radps2_per_sqrt_hz *
                     d.gyro_bias_random_walk_radps2_per_sqrt_hz),
      accel_bias_psd_(d.accel_bias_random_walk_mps3_per_sqrt_hz *
                      d.accel_bias_random_walk_mps3_per_sqrt_hz) {}

void ProcessNoise::addTo(double dt_s, ErrorCovariance& covariance) const {
  const double q_pp = accel_psd_ * dt_s * dt_s * dt_s / 3.0;
  const double q_pv = accel_psd_ * dt_s * dt_s / 2.0;
  for (int i = 0; i < 3; ++i) {
    covariance(kPosition + i, kPosition + i) += q_pp;
    covariance(kPosition + i, kVelocity + i) += q_pv;
    covariance(kVelocity + i, kPosition + i) += q_pv;
    covariance(kVelocity + i, kVelocity + i) += accel_psd_ * dt_s;
    covariance(kAttitude + i, kAttitude + i) += gyro_psd_ * dt_s;
    covariance(kGyroBias + i, kGyroBias + i) += gyro_bias_psd_ * dt_s;
    covariance(kAccelBias + i, kAccelBias + i) += accel_bias_psd_ * dt_s;
  }
}

Strapdown::Strapdown(const ImuNoiseDensities& densities, const Eigen::Vector3d& gravity_world_mps2)
    : process_noise_(densities), gravity_world_mps2_(gravity_world_mps2) {}

ErrorTransition Strapdown::propagate(const ImuSample& a, const ImuSample& b,
                                     NavigationState& state) const {
  const double dt = static_cast<double>(b.stamp_ns - a.stamp_ns) * kNsToS;
  const Eigen::Matrix3d R_a = state.q_world_body.toRotationMatrix();
  const Eigen::Vector3d mean_rate = 0.5 * (a.gyro_radps + b.gyro_radps) - state.gyro_bias_radps;
  state.q_world_body = (state.q_world_body * expSO3(mean_rate * dt)).normalized();
  const Eigen::Matrix3d R_b = state.q_world_body.toRotationMatrix();
  const Eigen::Vector3d force_world = 0.5 * (R_a * (a.accel_mps2 - state.accel_bias_mps2) +
                                             R_b * (b.accel_mps2 - state.accel_bias_mps2));
  const Eigen::Vector3d v_a = state.v_world_body;
  state.v_world_body += (force_world + gravity_world_mps2_) * dt;
  state.p_world_body += 0.5 * (v_a + state.v_world_body) * dt;
  state.stamp_ns = b.stamp_ns;

  ErrorTransition phi;
  phi.dt_s = dt;
  const Eigen::Matrix3d force_skew = skew(force_world);
  const Eigen::Matrix3d R_mean = 0.5 * (R_a + R_b);
  phi.v_theta = -force_skew * dt;
  phi.p_theta = 0.5 * dt * phi.v_theta;
  phi.v_ba = -R_mean * dt;
  phi.p_ba = 0.5 * dt * phi.v_ba;
  phi.theta_bg = phi.v_ba;
  phi.v_bg = -0.5 * dt * force_skew * phi.theta_bg;
  return phi;
}

void Strapdown::propagate(const ImuSample& a, const ImuSample& b, NavigationState& state,
                          ErrorCovariance& covariance) const {
  const ErrorTransition phi = propagate(a, b, state);
  // Phi P Phi^T = Phi (Phi P)^T for symmetric P.
  covariance = phi.applyLeft(phi.applyLeft(covariance).transpose());
  process_noise_.addTo(phi.dt_s, covariance);
}

}  // namespace lineloc

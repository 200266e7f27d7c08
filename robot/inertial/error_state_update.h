// The Kalman measurement update of the error-state filter with a Mahalanobis
// gate (Solà 2017, §6.1-6.3; Bar-Shalom, Li, Kirubarajan, "Estimation with
// Applications to Tracking and Navigation", 2001, §5.4 gating):
//   S = H P H^T + R,  NIS = r^T S^-1 r,  rejected when NIS > gate,
//   K = P H^T S^-1,  dx = K r,  P = (I - K H) P (I - K H)^T + K R K^T (Joseph),
// then dx is injected into the nominal state and reset to zero.
//
// A measurement whose error it shares with other measurements (a
// time-correlated error, an offset common to them) is gated with its own R,
// the spread of its error, but updates with R_u, the part of R that is new
// information (c R, c >= 1, for a time-correlated error; R less the offset's
// covariance for a common offset): K = P H^T (H P H^T + R_u)^-1 and the
// Joseph form with R_u.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <optional>

#include "robot/inertial/navigation_state.h"

namespace lineloc {

enum class UpdateStatus {
  kAccepted,
  kGated,       // NIS above the gate
  kDegenerate,  // S not positive definite, or the measurement is undefined here
};

struct UpdateOutcome {
  UpdateStatus status = UpdateStatus::kDegenerate;
  double nis = 0.0;
};

// A linearised measurement: residual r = z - h(x_est) = H dx + noise, noise covariance R.
template <int M>
struct LinearisedMeasurement {
  Eigen::Matrix<double, M, 1> residual = Eigen::Matrix<double, M, 1>::Zero();
  Eigen::Matrix<double, M, kErrorStateSize> jacobian =
      Eigen::Matrix<double, M, kErrorStateSize>::Zero();
  Eigen::Matrix<double, M, M> noise = Eigen::Matrix<double, M, M>::Identity();
};

template <int M>
UpdateOutcome applyUpdate(const LinearisedMeasurement<M>& z, double gate, NavigationState& state,
                          ErrorCovariance& covariance,
                          const Eigen::Matrix<double, M, M>& update_noise) {
  using MatrixMM = Eigen::Matrix<double, M, M>;
  const Eigen::Matrix<double, kErrorStateSize, M> PHt = covariance * z.jacobian.transpose();
  const MatrixMM S = z.jacobian * PHt + z.noise;
  const Eigen::LLT<MatrixMM> llt(S);
  if (llt.info() != Eigen::Success || !z.residual.allFinite()) {
    return {UpdateStatus::kDegenerate, 0.0};
  }
  const double nis = z.residual.dot(llt.solve(z.residual));
  if (!(nis <= gate)) {
    return {UpdateStatus::kGated, nis};
  }
  const Eigen::LLT<MatrixMM> update_llt =
      &update_noise == &z.noise ? llt : Eigen::LLT<MatrixMM>(z.jacobian * PHt + update_noise);
  if (update_llt.info() != Eigen::Success) {
    return {UpdateStatus::kDegenerate, nis};
  }
  const Eigen::Matrix<double, kErrorStateSize, M> K = update_llt.solve(PHt.transpose()).transpose();
  const ErrorCovariance I_KH = ErrorCovariance::Identity() - K * z.jacobian;
  covariance = I_KH * covariance * I_KH.transpose() + K * update_noise * K.transpose();
  covariance = 0.5 * (covariance + covariance.transpose()).eval();
  injectError(K * z.residual, state);
  return {UpdateStatus::kAccepted, nis};
}

template <int M>
UpdateOutcome applyUpdate(const LinearisedMeasurement<M>& z, double gate, NavigationState& state,
                          ErrorCovariance& covariance) {
  return applyUpdate(z, gate, state, covariance, z.noise);
}

// A measurement whose error persists over the filter's whole span (a DGPS
// fix: its error is correlated over minutes) bounds the estimate at its own
// covariance R instead of adding to it: repeated, it carries no new
// information. With S_p = H P H^T, it updates with the information
//   W = R^-1 - S_p^-1, its negative eigenvalues clipped to zero,
// so that S_p becomes R along the directions where it was wider than R and
// stays where it was not, and with the gain K = P H^T W (I + S_p W)^-1, the
// Kalman gain P H^T (S_p + W^-1)^-1 for a W that may be singular; then
// P = (I - K H) P. It is gated with R as any other, first: one beyond the gate
// disagrees with the estimate, whatever it would add. Returns nullopt when it
// passes the gate and S_p is within R along every direction: it adds nothing.
template <int M>
std::optional<UpdateOutcome> applyBoundingUpdate(const LinearisedMeasurement<M>& z, double gate,
                                                 NavigationState& state,
                                                 ErrorCovariance& covariance) {
  using MatrixMM = Eigen::Matrix<double, M, M>;
  const Eigen::Matrix<double, kErrorStateSize, M> PHt = covariance * z.jacobian.transpose();
  const MatrixMM S_p = z.jacobian * PHt;
  const Eigen::LLT<MatrixMM> llt(S_p + z.noise);
  const Eigen::LLT<MatrixMM> predicted_llt(S_p);
  if (llt.info() != Eigen::Success || predicted_llt.info() != Eigen::Success ||
      !z.residual.allFinite()) {
    return UpdateOutcome{UpdateStatus::kDegenerate, 0.0};
  }
  const double nis = z.residual.dot(llt.solve(z.residual));
  if (!(nis <= gate)) {
    return UpdateOutcome{UpdateStatus::kGated, nis};
  }
  const Eigen::SelfAdjointEigenSolver<MatrixMM> information(
      z.noise.inverse() - predicted_llt.solve(MatrixMM::Identity()));
  const auto clipped = information.eigenvalues().cwiseMax(0.0);
  if (clipped.maxCoeff() <= 0.0) {
    return std::nullopt;
  }
  const MatrixMM W =
      information.eigenvectors() * clipped.asDiagonal() * information.eigenvectors().transpose();
  const Eigen::Matrix<double, kErrorStateSize, M> K =
      PHt * W * (MatrixMM::Identity() + S_p * W).inverse();
  covariance = (ErrorCovariance::Identity() - K * z.jacobian) * covariance;
  covariance = 0.5 * (covariance + covariance.transpose()).eval();
  injectError(K * z.residual, state);
  return UpdateOutcome{UpdateStatus::kAccepted, nis};
}

}  // namespace lineloc

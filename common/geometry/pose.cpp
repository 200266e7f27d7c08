#include "common/geometry/pose.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lineloc {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Eigen::Isometry3d makePose(const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation.normalized().toRotationMatrix();
  pose.translation() = translation;
  return pose;
}

Eigen::Matrix<double, 6, 1> poseError(const Eigen::Isometry3d& estimate,
                                      const Eigen::Isometry3d& truth) {
  Eigen::Matrix<double, 6, 1> error;
  error.head<3>() = truth.translation() - estimate.translation();
  const Eigen::AngleAxisd rotation(truth.linear() * estimate.linear().transpose());
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
}

Eigen::Isometry3d applyPoseError(const Eigen::Isometry3d& pose,
                                 const Eigen::Matrix<double, 6, 1>& error) {
  Eigen::Isometry3d moved = pose;
  moved.translation() += error.head<3>();
  const double angle = error.tail<3>().norm();
  if (angle > 0.0) {
    moved.linear() =
        Eigen::AngleAxisd(angle, error.tail<3>() / angle).toRotationMatrix() * pose.linear();
  }
  return moved;
}

PoseWithCovariance composeExactMotion(const PoseWithCovariance& T_world_a,
                                      const Eigen::Isometry3d& T_a_b) {
  const Eigen::Vector3d lever = T_world_a.pose.linear() * T_a_b.translation();
  Matrix6d jacobian = Matrix6d::Identity();
  jacobian.topRightCorner<3, 3>() = -skew(lever);
  return {T_world_a.pose * T_a_b, jacobian * T_world_a.covariance * jacobian.transpose()};
}

PoseWithCovariance changeWorldFrame(const Eigen::Isometry3d& T_b_a,
                                    const PoseWithCovariance& T_a_c) {
  Matrix6d rotation = Matrix6d::Zero();
  rotation.topLeftCorner<3, 3>() = T_b_a.linear();
  rotation.bottomRightCorner<3, 3>() = T_b_a.linear();
  return {T_b_a * T_a_c.pose, rotation * T_a_c.covariance * rotation.transpose()};
}

PoseWithCovariance scaledWorld(const PoseWithCovariance& pose, double factor) {
  Eigen::Matrix<double, 6, 1> scale;
  scale << factor, factor, factor, 1.0, 1.0, 1.0;
  PoseWithCovariance scaled = pose;
  scaled.pose.translation() *= factor;
  scaled.covariance = scale.asDiagonal() * pose.covariance * scale.asDiagonal();
  return scaled;
}

PoseWithCovariance fusePoses(const PoseWithCovariance& a, const PoseWithCovariance& b) {
  const Matrix6d information_a = a.covariance.ldlt().solve(Matrix6d::Identity());
  const Matrix6d information_b = b.covariance.ldlt().solve(Matrix6d::Identity());
  PoseWithCovariance fused;
  fused.covariance = (information_a + information_b).ldlt().solve(Matrix6d::Identity());
  fused.covariance = 0.5 * (fused.covariance + fused.covariance.transpose());
  fused.pose = applyPoseError(a.pose, fused.covariance * information_b * poseError(a.pose, b.pose));
  return fused;
}

Matrix6d scatterAboutMean(const std::vector<Eigen::Matrix<double, 6, 1>>& samples) {
  Eigen::Matrix<double, 6, 1> mean = Eigen::Matrix<double, 6, 1>::Zero();
  for (const auto& sample : samples) {
    mean += sample;
  }
  mean /= static_cast<double>(samples.size());
  Matrix6d scatter = Matrix6d::Zero();
  for (const auto& sample : samples) {
    scatter.noalias() += (sample - mean) * (sample - mean).transpose();
  }
  return scatter;
}

Matrix6d coveringCovariance(const Matrix6d& a, const Matrix6d& b) {
  const Eigen::LLT<Matrix6d> llt(a);
  if (llt.info() != Eigen::Success) {
    return Matrix6d::Constant(std::numeric_limits<double>::infinity());
  }
  const Matrix6d L = llt.matrixL();
  const Matrix6d whitened =
      L.triangularView<Eigen::Lower>().solve(L.triangularView<Eigen::Lower>().solve(b).transpose());
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(0.5 * (whitened + whitened.transpose()));
  const Matrix6d V = eigen.eigenvectors();
  const Matrix6d covering =
      L * V * eigen.eigenvalues().cwiseMax(1.0).asDiagonal() * V.transpose() * L.transpose();
  return 0.5 * (covering + covering.transpose());
}

double largestSigma(const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eigen.eigenvalues().maxCoeff()));
}

double largestPositionSigma(const Matrix6d& covariance) {
  return largestSigma(covariance.topLeftCorner<3, 3>());
}

double normalizedErrorSquared(const PoseWithCovariance& estimate, const Eigen::Isometry3d& truth) {
  const Eigen::Matrix<double, 6, 1> error = poseError(estimate.pose, truth);
  return error.dot(estimate.covariance.ldlt().solve(error));
}

Matrix6d diagonalPoseCovariance(double position_sigma_m, double rotation_sigma_rad) {
  Matrix6d covariance = Matrix6d::Zero();
  covariance.diagonal().head<3>().setConstant(position_sigma_m * position_sigma_m);
  covariance.diagonal().tail<3>().setConstant(rotation_sigma_rad * rotation_sigma_rad);
  return covariance;
}

bool isFinitePose(const PoseWithCovariance& pose, double tolerance) {
  if (!pose.pose.matrix().allFinite() || !pose.covariance.allFinite()) {
    return false;
  }
  const Eigen::Matrix3d R = pose.pose.linear();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < tolerance;
}

Eigen::Isometry3d rigidTransform(const std::vector<double>& entries, const std::string& source) {
  constexpr double kRigidTolerance = 1e-6;
  if (entries.size() != 16) {
    throw std::runtime_error(fmt::format(
        "{}: a rigid transform is 16 numbers (4x4, row-major), not {}", source, entries.size()));
  }
  for (const double entry : entries) {
    if (!std::isfinite(entry)) {
      throw std::runtime_error(fmt::format("{}: holds a non-finite number", source));
    }
  }
  const Eigen::Matrix4d T =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(entries.data());
  if (!T.row(3).isApprox(Eigen::RowVector4d(0.0, 0.0, 0.0, 1.0), kRigidTolerance)) {
    throw std::runtime_error(fmt::format("{}: the last row must be 0 0 0 1", source));
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  if (!(R.transpose() * R).isIdentity(kRigidTolerance) ||
      std::abs(R.determinant() - 1.0) > kRigidTolerance) {
    throw std::runtime_error(fmt::format("{}: the rotation is not a proper rotation", source));
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = R;
  pose.translation() = T.topRightCorner<3, 1>();
  return pose;
}

}  // namespace lineloc

#include "common/pose/pose_input_check.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <vector>

namespace lineloc {

namespace {

template <typename Derived>
bool isWithinRange(const Eigen::MatrixBase<Derived>& value) {
  return value.allFinite() && value.cwiseAbs().maxCoeff() <= kMaxAbsCoordinate;
}

PoseFailure invalid(std::string message) {
  return {PoseStatus::kInvalidInput, std::move(message)};
}

std::optional<PoseFailure> checkCamera(const PinholeCamera& camera) {
  const Eigen::Vector4d centre_and_skew(camera.cx, camera.cy, camera.skew, 0.0);
  if (!(camera.fx > 0.0) || !(camera.fy > 0.0) || camera.fx > kMaxAbsCoordinate ||
      camera.fy > kMaxAbsCoordinate || !isWithinRange(centre_and_skew)) {
    return invalid(fmt::format("camera: intrinsics fx={} fy={} cx={} cy={} skew={} are invalid",
                               camera.fx, camera.fy, camera.cx, camera.cy, camera.skew));
  }
  return std::nullopt;
}

std::optional<PoseFailure> checkCovariance(const Eigen::Matrix2d& covariance,
                                           const std::string& where) {
  if (!covariance.allFinite()) {
    return invalid(where + " is not finite");
  }
  const double asymmetry = std::abs(covariance(0, 1) - covariance(1, 0));
  if (asymmetry > 1e-9 * covariance.cwiseAbs().maxCoeff()) {
    return invalid(where + " is not symmetric");
  }
  const Eigen::Vector2d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues();
  if (!(eigenvalues(0) >= kMinVariancePx2) || !(eigenvalues(1) <= kMaxVariancePx2)) {
    return invalid(fmt::format("{} has eigenvalues {} and {} outside [{}, {}] px^2", where,
                               eigenvalues(0), eigenvalues(1), kMinVariancePx2, kMaxVariancePx2));
  }
  return std::nullopt;
}

std::optional<PoseFailure> checkPoint(const PointCorrespondence& point, size_t index) {
  const std::string where = fmt::format("point {}", index);
  if (!isWithinRange(point.p_world)) {
    return invalid(where + ": p_world is not finite or beyond 1e8");
  }
  if (!isWithinRange(point.pixel)) {
    return invalid(where + ": pixel is not finite or beyond 1e8");
  }
  return checkCovariance(point.covariance, where + ": covariance");
}

std::optional<PoseFailure> checkLine(const LineCorrespondence& line, size_t index) {
  const std::string where = fmt::format("line {}", index);
  if (!isWithinRange(line.start_world) || !isWithinRange(line.end_world)) {
    return invalid(where + ": model endpoint is not finite or beyond 1e8");
  }
  if (!isWithinRange(line.start_pixel) || !isWithinRange(line.end_pixel)) {
    return invalid(where + ": image endpoint is not finite or beyond 1e8");
  }
  if ((line.end_world - line.start_world).norm() < kMinModelSegmentLengthM) {
    return invalid(
        fmt::format("{}: model segment shorter than {} m", where, kMinModelSegmentLengthM));
  }
  if ((line.end_pixel - line.start_pixel).norm() < kMinImageSegmentLengthPx) {
    return invalid(
        fmt::format("{}: image segment shorter than {} px", where, kMinImageSegmentLengthPx));
  }
  if (auto failure = checkCovariance(line.start_covariance, where + ": start covariance")) {
    return failure;
  }
  return checkCovariance(line.end_covariance, where + ": end covariance");
}

// Singular values of the centred support points, largest first.
Eigen::Vector3d spreadOf(const std::vector<Eigen::Vector3d>& support) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : support)
    centroid += p;
  centroid /= static_cast<double>(support.size());
  Eigen::MatrixXd centred(3, support.size());
  for (size_t i = 0; i < support.size(); ++i)
    centred.col(i) = support[i] - centroid;
  return Eigen::JacobiSVD<Eigen::MatrixXd>(centred).singularValues();
}

// Lines as point + unit direction; the least-squares common point X solves
// sum_i (I - d_i d_i^T) X = sum_i (I - d_i d_i^T) a_i. All parallel when that
// matrix has rank 2, all concurrent when X lies on every line.
std::optional<PoseFailure> checkLineBundle(const std::vector<LineCorrespondence>& lines,
                                           double scale_m) {
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right_side = Eigen::Vector3d::Zero();
  for (const auto& line : lines) {
    const Eigen::Vector3d direction = (line.end_world - line.start_world).normalized();
    const Eigen::Matrix3d projector =
        Eigen::Matrix3d::Identity() - direction * direction.transpose();
    normal_matrix += projector;
    right_side += projector * line.start_world;
  }
  const Eigen::Vector3d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(normal_matrix, Eigen::EigenvaluesOnly)
          .eigenvalues();
  if (eigenvalues(0) <= kRelativeDegeneracyTolerance * eigenvalues(2)) {
    return PoseFailure{PoseStatus::kDegenerate, "lines: all model lines are parallel"};
  }
  const Eigen::Vector3d common_point = normal_matrix.ldlt().solve(right_side);
  for (const auto& line : lines) {
    const Eigen::Vector3d direction = (line.end_world - line.start_world).normalized();
    const Eigen::Vector3d offset = common_point - line.start_world;
    if ((offset - offset.dot(direction) * direction).norm() >
        kRelativeDegeneracyTolerance * scale_m) {
      return std::nullopt;
    }
  }
  return PoseFailure{PoseStatus::kDegenerate, "lines: all model lines pass through one point"};
}

}  // namespace

std::optional<PoseFailure> checkPoseInput(const PoseProblem& problem) {
  if (auto failure = checkCamera(problem.camera)) {
    return failure;
  }
  for (size_t i = 0; i < problem.points.size(); ++i) {
    if (auto failure = checkPoint(problem.points[i], i)) {
      return failure;
    }
  }
  for (size_t i = 0; i < problem.lines.size(); ++i) {
    if (auto failure = checkLine(problem.lines[i], i)) {
      return failure;
    }
  }
  return std::nullopt;
}

std::optional<PoseFailure> checkPoseGeometry(const PoseProblem& problem) {
  const size_t constraints = 2 * (problem.points.size() + problem.lines.size());
  if (constraints < 6) {
    return PoseFailure{PoseStatus::kNotEnoughCorrespondences,
                       fmt::format("{} points and {} lines give {} of the 6 constraints needed",
                                   problem.points.size(), problem.lines.size(), constraints)};
  }
  std::vector<Eigen::Vector3d> support;
  for (const auto& point : problem.points)
    support.push_back(point.p_world);
  for (const auto& line : problem.lines) {
    support.push_back(line.start_world);
    support.push_back(line.end_world);
  }
  const Eigen::Vector3d spread = spreadOf(support);
  if (spread(1) <= kRelativeDegeneracyTolerance * spread(0)) {
    return PoseFailure{PoseStatus::kDegenerate,
                       "model: all points and segment endpoints are collinear or coincident"};
  }
  if (problem.points.empty()) {
    const double rms_extent_m = spread(0) / std::sqrt(static_cast<double>(support.size()));
    return checkLineBundle(problem.lines, rms_extent_m);
  }
  return std::nullopt;
}

}  // namespace lineloc

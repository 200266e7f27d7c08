#include "common/pose/linear_pose.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "common/pose/nearest_rotation.h"

namespace lineloc {

namespace {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

// The second-smallest eigenvalue of A^T A below this fraction of the largest
// means a null space of dimension > 1 (e.g. a planar model).
constexpr double kRankTolerance = 1e-12;

// Centroid and 1 / RMS distance of every model point and endpoint.
struct ModelNormalization {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double scale = 1.0;

  Eigen::Vector4d apply(const Eigen::Vector3d& p_world) const {
    return (Eigen::Vector4d() << scale * (p_world - centroid), 1.0).finished();
  }
};

ModelNormalization normalizationOf(const PoseProblem& problem) {
  ModelNormalization normalization;
  double count = 0.0;
  const auto visit = [&](auto&& use) {
    for (const auto& point : problem.points)
      use(point.p_world);
    for (const auto& line : problem.lines) {
      use(line.start_world);
      use(line.end_world);
    }
  };
  visit([&](const Eigen::Vector3d& p) {
    normalization.centroid += p;
    count += 1.0;
  });
  normalization.centroid /= count;
  double squared = 0.0;
  visit([&](const Eigen::Vector3d& p) { squared += (p - normalization.centroid).squaredNorm(); });
  normalization.scale = std::sqrt(count / squared);
  return normalization;
}

// Adds the equation row^T vec(P) = 0 (P row-major) with row = c^T kron X.
void addEquation(const Eigen::Vector3d& coefficients, const Eigen::Vector4d& X,
                 Matrix12d* normal_matrix) {
  Vector12d row;
  for (int r = 0; r < 3; ++r)
    row.segment<4>(4 * r) = coefficients(r) * X;
  normal_matrix->noalias() += row * row.transpose();
}

}  // namespace

PoseStart linearPose(const PoseProblem& problem) {
  PoseStart start;
  if (problem.points.size() + problem.lines.size() < 6) {
    start.message = fmt::format("linear start: {} correspondences, 6 needed",
                                problem.points.size() + problem.lines.size());
    return start;
  }
  const Eigen::Matrix3d K_inverse = problem.camera.K().inverse();
  const Eigen::Matrix3d K_transpose = problem.camera.K().transpose();
  const ModelNormalization normalization = normalizationOf(problem);
  Matrix12d normal_matrix = Matrix12d::Zero();
  for (const auto& point : problem.points) {
    const Eigen::Vector3d x = K_inverse * point.pixel.homogeneous();
    const Eigen::Vector4d X = normalization.apply(point.p_world);
    addEquation({-1.0, 0.0, x.x() / x.z()}, X, &normal_matrix);
    addEquation({0.0, -1.0, x.y() / x.z()}, X, &normal_matrix);
  }
  for (const auto& line : problem.lines) {
    Eigen::Vector3d l =
        K_transpose * line.start_pixel.homogeneous().cross(line.end_pixel.homogeneous());
    l /= l.head<2>().norm();
    addEquation(l, normalization.apply(line.start_world), &normal_matrix);
    addEquation(l, normalization.apply(line.end_world), &normal_matrix);
  }
  const Eigen::SelfAdjointEigenSolver<Matrix12d> solver(normal_matrix);
  if (!(solver.eigenvalues()(1) > kRankTolerance * solver.eigenvalues()(11))) {
    start.status = PoseStatus::kDegenerate;
    start.message = "linear start: the model is planar or the equations are rank deficient";
    return start;
  }
  Eigen::Matrix<double, 3, 4> P_normalized =
      Eigen::Map<const Eigen::Matrix<double, 4, 3>>(solver.eigenvectors().col(0).data())
          .transpose();
  // Undo the normalization: P = P' [s I, -s c; 0, 1].
  Eigen::Matrix<double, 3, 4> P;
  P.leftCols<3>() = normalization.scale * P_normalized.leftCols<3>();
  P.col(3) = P_normalized.col(3) - P.leftCols<3>() * normalization.centroid;
  // The sign of P puts most model points in front: depth ~ P3 [X; 1] > 0.
  double front_votes = 0.0;
  for (const auto& point : problem.points) {
    front_votes += P.row(2).dot(point.p_world.homogeneous()) > 0.0 ? 1.0 : -1.0;
  }
  for (const auto& line : problem.lines) {
    front_votes += P.row(2).dot(line.start_world.homogeneous()) > 0.0 ? 1.0 : -1.0;
    front_votes += P.row(2).dot(line.end_world.homogeneous()) > 0.0 ? 1.0 : -1.0;
  }
  if (front_votes < 0.0) {
    P = -P;
  }
  // |s R|_F = sqrt(3) |s|.
  const double scale = P.leftCols<3>().norm() / std::sqrt(3.0);
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    start.status = PoseStatus::kDegenerate;
    start.message = "linear start: the camera matrix has no rotation part";
    return start;
  }
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
  T_camera_world.linear() = nearestRotation(P.leftCols<3>());
  T_camera_world.translation() = P.col(3) / scale;
  start.status = PoseStatus::kConverged;
  start.T_world_camera = T_camera_world.inverse();
  return start;
}

}  // namespace lineloc

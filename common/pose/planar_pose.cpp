#include "common/pose/planar_pose.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/homography/homography.h"
#include "common/pose/nearest_rotation.h"

namespace lineloc {

namespace {

// Collinear when the second singular value of the centred points is below this
// fraction of the largest (the eigenvalues of the scatter matrix are accurate to
// ~1e-16 of the largest, so their square roots to ~1e-8).
constexpr double kCollinearTolerance = 1e-6;

// Normals closer than this (radians) to the line of sight give one candidate.
constexpr double kMinFlipAngleRad = 1e-9;

double rmsResidualPx(const PinholeCamera& camera, const std::vector<PointCorrespondence>& points,
                     const Eigen::Isometry3d& T_camera_world) {
  double squared = 0.0;
  for (const auto& point : points) {
    squared += (camera.project(T_camera_world * point.p_world) - point.pixel).squaredNorm();
  }
  return std::sqrt(squared / static_cast<double>(points.size()));
}

// When noise folds the exact homography (the line at infinity between model
// points, as four noisy points can), the weak-perspective start: the
// least-squares affine map [A b; 0 0 1], each image row u = a^T [x y 1].
Eigen::Matrix3d affineApproximation(const std::vector<Eigen::Vector2d>& model_points,
                                    const std::vector<Eigen::Vector2d>& image_points) {
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> right_side = Eigen::Matrix<double, 3, 2>::Zero();
  for (size_t i = 0; i < model_points.size(); ++i) {
    const Eigen::Vector3d m = model_points[i].homogeneous();
    normal_matrix.noalias() += m * m.transpose();
    right_side.noalias() += m * image_points[i].transpose();
  }
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
  H.topRows<2>() = normal_matrix.ldlt().solve(right_side).transpose();
  return H;
}

// The mirrored candidate: rotate the plane about its centroid (t) so that its
// normal n becomes 2 (n.v) v - n, v the unit line of sight to the centroid.
std::optional<Eigen::Isometry3d> flippedPose(const Eigen::Isometry3d& T_camera_plane) {
  const Eigen::Vector3d normal = T_camera_plane.linear().col(2);
  const Eigen::Vector3d sight = T_camera_plane.translation().normalized();
  const Eigen::Vector3d mirrored = 2.0 * normal.dot(sight) * sight - normal;
  const Eigen::Vector3d axis = normal.cross(mirrored);
  const double angle = std::atan2(axis.norm(), normal.dot(mirrored));
  if (angle < kMinFlipAngleRad) {
    return std::nullopt;
  }
  Eigen::Isometry3d flipped = T_camera_plane;
  flipped.linear() = Eigen::AngleAxisd(angle, axis.normalized()) * T_camera_plane.linear();
  return flipped;
}

}  // namespace

std::optional<Eigen::Isometry3d> fitModelPlane(const std::vector<PointCorrespondence>& points) {
  if (points.size() < 3) {
    return std::nullopt;
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& point : points)
    centroid += point.p_world;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& point : points) {
    const Eigen::Vector3d d = point.p_world - centroid;
    scatter.noalias() += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3d singular_values = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  if (!(singular_values(2) > 0.0) ||
      singular_values(1) <= kCollinearTolerance * singular_values(2) ||
      singular_values(0) > kCoplanarTolerance * singular_values(2)) {
    return std::nullopt;
  }
  Eigen::Isometry3d T_world_plane = Eigen::Isometry3d::Identity();
  T_world_plane.linear().col(0) = solver.eigenvectors().col(2);
  T_world_plane.linear().col(1) = solver.eigenvectors().col(1);
  T_world_plane.linear().col(2) = solver.eigenvectors().col(2).cross(solver.eigenvectors().col(1));
  T_world_plane.translation() = centroid;
  return T_world_plane;
}

PlanarPoseStart planarPose(const PinholeCamera& camera,
                           const std::vector<PointCorrespondence>& points) {
  PlanarPoseStart start;
  if (points.size() < 4) {
    start.message = fmt::format("planar start: {} points, 4 needed", points.size());
    return start;
  }
  start.status = PoseStatus::kDegenerate;
  const std::optional<Eigen::Isometry3d> T_world_plane = fitModelPlane(points);
  if (!T_world_plane) {
    start.message = "planar start: the model points are not coplanar, or are collinear";
    return start;
  }
  const Eigen::Isometry3d T_plane_world = T_world_plane->inverse();
  std::vector<Eigen::Vector2d> model_points;
  std::vector<Eigen::Vector2d> image_points;
  for (const auto& point : points) {
    model_points.push_back((T_plane_world * point.p_world).head<2>());
    image_points.push_back(point.pixel);
  }
  const HomographyEstimate homography = estimateHomographyDlt(model_points, image_points);
  if (homography.status == HomographyStatus::kNonFinite) {
    start.message = "planar start: homography failed: non-finite";
    return start;
  }
  const Eigen::Matrix3d H = homography.status == HomographyStatus::kOk
                                ? homography.H
                                : affineApproximation(model_points, image_points);
  const Eigen::Matrix3d B = camera.K().inverse() * H;
  const double norm_sum = B.col(0).norm() + B.col(1).norm();
  if (!(norm_sum > 0.0) || !std::isfinite(norm_sum)) {
    start.message = "planar start: the homography has no rotation part";
    return start;
  }
  const double lambda = std::copysign(2.0 / norm_sum, B(2, 2));
  Eigen::Matrix3d rotation_columns;
  rotation_columns << lambda * B.col(0), lambda * B.col(1),
      (lambda * B.col(0)).cross(lambda * B.col(1));
  Eigen::Isometry3d T_camera_plane = Eigen::Isometry3d::Identity();
  T_camera_plane.linear() = nearestRotation(rotation_columns);
  T_camera_plane.translation() = lambda * B.col(2);
  std::vector<Eigen::Isometry3d> poses = {T_camera_plane};
  if (const auto flipped = flippedPose(T_camera_plane)) {
    poses.push_back(*flipped);
  }
  for (const auto& T_camera_plane_candidate : poses) {
    const Eigen::Isometry3d T_camera_world = T_camera_plane_candidate * T_plane_world;
    start.candidates.push_back(
        {T_camera_world.inverse(), rmsResidualPx(camera, points, T_camera_world)});
  }
  std::sort(start.candidates.begin(), start.candidates.end(),
            [](const auto& a, const auto& b) { return a.rms_residual_px < b.rms_residual_px; });
  start.status = PoseStatus::kConverged;
  return start;
}

}  // namespace lineloc

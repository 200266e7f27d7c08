#include "backbone/matching/line_matcher.h"

#include <algorithm>
#include <cmath>

namespace lineloc {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Pixel of a world point and its 2x2 covariance under the pose covariance.
std::pair<Eigen::Vector2d, Eigen::Matrix2d> projectWithCovariance(
    const Eigen::Vector3d& p_world, const PoseWithCovariance& T_world_camera,
    const PinholeCamera& camera) {
  const Eigen::Matrix3d R = T_world_camera.pose.linear();
  const Eigen::Vector3d x = p_world - T_world_camera.pose.translation();
  const Eigen::Vector3d p_camera = R.transpose() * x;
  const double z = p_camera.z();
  Eigen::Matrix<double, 2, 3> d_pixel_d_camera;
  d_pixel_d_camera << camera.fx / z, camera.skew / z,
      -(camera.fx * p_camera.x() + camera.skew * p_camera.y()) / (z * z), 0.0, camera.fy / z,
      -camera.fy * p_camera.y() / (z * z);
  Eigen::Matrix<double, 3, 6> d_camera_d_error;
  d_camera_d_error << -R.transpose(), R.transpose() * skew(x);
  const Eigen::Matrix<double, 2, 6> J = d_pixel_d_camera * d_camera_d_error;
  return {camera.project(p_camera), J * T_world_camera.covariance * J.transpose()};
}

}  // namespace

ProjectedSegment projectSegment(const Eigen::Vector3d& start_world,
                                const Eigen::Vector3d& end_world,
                                const PoseWithCovariance& T_world_camera,
                                const PinholeCamera& camera) {
  const auto [start_px, start_covariance] =
      projectWithCovariance(start_world, T_world_camera, camera);
  const auto [end_px, end_covariance] = projectWithCovariance(end_world, T_world_camera, camera);
  return {start_px, end_px, start_covariance, end_covariance};
}

std::vector<std::vector<LineMatch>> gateCandidates(const std::vector<ImageSegment>& image,
                                                   const std::vector<VisibleSegment>& model,
                                                   const PoseWithCovariance& T_world_camera,
                                                   const PinholeCamera& camera,
                                                   const MatchingOptions& options) {
  std::vector<ProjectedSegment> projected;
  projected.reserve(model.size());
  for (const VisibleSegment& segment : model) {
    projected.push_back(
        projectSegment(segment.start_world, segment.end_world, T_world_camera, camera));
  }
  const double floor_variance = options.model_sigma_floor_px * options.model_sigma_floor_px;
  std::vector<std::vector<LineMatch>> candidates(image.size());
  for (size_t i = 0; i < image.size(); ++i) {
    const Eigen::Vector2d q0 = image[i].start.cast<double>();
    const Eigen::Vector2d q1 = image[i].end.cast<double>();
    const double image_length = (q1 - q0).norm();
    for (size_t m = 0; m < projected.size(); ++m) {
      const ProjectedSegment& p = projected[m];
      const Eigen::Vector2d along = p.end_px - p.start_px;
      const double model_length = along.norm();
      if (model_length < 1e-9 || image_length < 1e-9) {
        continue;
      }
      const Eigen::Vector2d direction = along / model_length;
      const Eigen::Vector2d normal(-direction.y(), direction.x());
      // Overlap of the image segment's extent along the model line.
      const double t0 = direction.dot(q0 - p.start_px);
      const double t1 = direction.dot(q1 - p.start_px);
      const double overlap =
          std::min(std::max(t0, t1), model_length) - std::max(std::min(t0, t1), 0.0);
      if (overlap < options.min_overlap_fraction * image_length) {
        continue;
      }
      double chi2 = 0.0;
      for (const auto& [q, covariance] :
           {std::pair{q0, image[i].start_covariance.cast<double>().eval()},
            std::pair{q1, image[i].end_covariance.cast<double>().eval()}}) {
        const double t = std::clamp(direction.dot(q - p.start_px) / model_length, 0.0, 1.0);
        const Eigen::Matrix2d model_covariance =
            (1.0 - t) * p.start_covariance + t * p.end_covariance;
        const double variance =
            normal.dot((covariance + model_covariance) * normal) + floor_variance;
        const double distance = normal.dot(q - p.start_px);
        chi2 += distance * distance / variance;
      }
      if (chi2 <= options.gate_chi2) {
        candidates[i].push_back({static_cast<int>(i), static_cast<int>(m), chi2});
      }
    }
    std::sort(candidates[i].begin(), candidates[i].end(),
              [](const LineMatch& a, const LineMatch& b) { return a.chi2 < b.chi2; });
  }
  return candidates;
}

}  // namespace lineloc
